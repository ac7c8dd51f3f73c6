/* SPDX-License-Identifier: MPL-2.0 */
/* test_motion.c -- straight moves and the dialect around them: modal motion,
 * G90/G91, G20, comments, spacing, CRLF, %, N, block delete, program end,
 * tools, spindle, dwell, and streaming in arbitrary pieces. Expected values
 * are worked out by hand from the program text.
 */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "collect.h"

static collected c;

static void check_end(const swarf_move *mv, double x, double y, double z, const char *what) {
  CHECK_NEAR(mv->end[0], x, 1e-12, what);
  CHECK_NEAR(mv->end[1], y, 1e-12, what);
  CHECK_NEAR(mv->end[2], z, 1e-12, what);
}

static void test_modal_motion(void) {
  run_text("G0 X1 Y2\n X3\nN7 G1 X4 F100\nY5\n", &c);
  CHECK(c.status == 0 && c.n == 4, "modal: status %d, %d moves", c.status, c.n);
  if (c.n != 4) return;
  CHECK(c.moves[0].kind == SWARF_MOVE_RAPID && c.moves[1].kind == SWARF_MOVE_RAPID, "G0 is modal");
  CHECK(c.moves[2].kind == SWARF_MOVE_LINE && c.moves[3].kind == SWARF_MOVE_LINE, "G1 is modal");
  check_end(&c.moves[0], 1, 2, 0, "G0 X1 Y2");
  check_end(&c.moves[1], 3, 2, 0, "X3 keeps Y");
  check_end(&c.moves[3], 4, 5, 0, "Y5 keeps X");
  CHECK_NEAR(c.moves[1].start[0], 1, 0, "a move starts where the last ended");
  CHECK(c.moves[0].feed == 0 && c.moves[2].feed == 100 && c.moves[3].feed == 100, "feeds");
  CHECK(c.moves[0].line == 1 && c.moves[3].line == 4, "lines %ld %ld", c.moves[0].line,
        c.moves[3].line);
  CHECK(c.moves[0].column == 1, "column of G0: %d", c.moves[0].column);
  CHECK(c.moves[1].column == 2, "column of the first axis word: %d", c.moves[1].column);
  CHECK(c.moves[2].column == 4, "column of G1 after N7: %d", c.moves[2].column);
  CHECK(c.moves[3].column == 1, "column of Y5: %d", c.moves[3].column);
}

static void test_distance_modes(void) {
  run_text("G91 G0 X1 Y1\nX1 Z-2\nG90 X5\n", &c);
  CHECK(c.status == 0 && c.n == 3, "G91: %d moves", c.n);
  if (c.n != 3) return;
  check_end(&c.moves[0], 1, 1, 0, "G91 from 0");
  check_end(&c.moves[1], 2, 1, -2, "G91 adds");
  check_end(&c.moves[2], 5, 1, -2, "G90 again");
}

static void test_inches(void) {
  run_text("G20 G0 X1 Y-0.5 Z.1 A10\nG1 X2 F10\nG21 G1 X1\n", &c);
  CHECK(c.status == 0 && c.n == 3, "G20: %d moves", c.n);
  if (c.n != 3) return;
  check_end(&c.moves[0], 25.4, -12.7, 2.54, "G20 lengths in mm");
  CHECK_NEAR(c.moves[0].end[3], 10, 0, "angles are not converted");
  CHECK_NEAR(c.moves[1].feed, 254, 1e-9, "G20 feed 10 in/min in mm/min");
  check_end(&c.moves[2], 1, -12.7, 2.54, "back to G21: the position is kept in mm");
  CHECK_NEAR(c.moves[2].feed, 254, 1e-9, "the feed keeps its speed across G21");
  /* LinuxCNC sets F before G20 on the same line takes effect. */
  run_text("G20 G1 X1 F10\n", &c);
  CHECK(c.status == 0 && c.n == 1 && c.moves[0].feed == 10, "F on the G20 line is mm/min");
}

static void test_spelling(void) {
  run_text("g0 x 1 0.5 y-.5 (a comment X9) z+3 ; X8\nG01 X1. F 1 2 0\n(MSG, hello)\n", &c);
  CHECK(c.status == 0 && c.n == 2, "spelling: status %d (%s), %d moves", c.status, c.error.message,
        c.n);
  if (c.n != 2) return;
  check_end(&c.moves[0], 10.5, -0.5, 3, "blanks inside numbers, comments skipped");
  CHECK(c.moves[1].kind == SWARF_MOVE_LINE && c.moves[1].end[0] == 1 && c.moves[1].feed == 120,
        "G01 X1. F 1 2 0");
  run_text("G0 X1\r\nG0 X2\r\n\r\nG0 X3", &c);
  CHECK(c.status == 0 && c.n == 3 && c.moves[2].line == 4 && c.moves[2].end[0] == 3,
        "CRLF and a last line without newline");
  run_text("G17 G90 G21 G40 G49 G54 G94 G61 M8 M0\nG64 P0.01 Q0.02 M9 M1\nG61.1\n"
           "G43 H1 Z5 G0\nG0 G80 X1\n",
           &c);
  CHECK(c.status == 0 && c.n == 2, "modes of no effect: %d (%s)", c.status, c.error.message);
  /* G43 H1: rs274's built-in tool 1 is 0.511 in long; moves are machine frame. */
  if (c.n == 2) check_end(&c.moves[1], 1, 0, 5 + 0.511 * 25.4, "G80 next to G0 gives way");
}

static void test_percent_and_end(void) {
  run_text("\n  \n%\nG0 X1\n%\nG0 X2\n", &c);
  CHECK(c.status == 0 && c.n == 1 && c.ended, "%%...%%: %d moves, ended %d", c.n, c.ended);
  run_text("G0 X1\nM2\nG0 X2\nthis is not G-code\n", &c);
  CHECK(c.status == 0 && c.n == 1 && c.ended && c.lines == 2, "M2: %d moves, %ld lines", c.n,
        c.lines);
  run_text("G0 X1\nM30\nX2\n", &c);
  CHECK(c.status == 0 && c.n == 1 && c.ended, "M30");
  run_text("G0 X1\n", &c);
  CHECK(c.status == 0 && !c.ended, "no end: not ended");
}

static void test_line_numbers_and_block_delete(void) {
  /* The block delete switch is off: `/` blocks run, as rs274 runs them
   * (test_dialects.c turns it on). */
  run_text("N10 G0 X1\nn20.5 G0 X2\n/G0 X7\n  / G0 X8\nN30\nG0 X3\n", &c);
  CHECK(c.status == 0 && c.n == 5, "N and /: %d moves (%s)", c.n, c.error.message);
  if (c.n == 5)
    CHECK(c.moves[2].end[0] == 7 && c.moves[3].end[0] == 8 && c.moves[4].line == 6,
          "`/` blocks run with the switch off");
}

static void test_tools_spindle_dwell(void) {
  run_text("T3 M6\nM3 S1000 G0 X1\nT2\nM4 G1 X2 F50\nM6\nM5 G4 P1.5\n", &c);
  CHECK(c.status == 0 && c.n == 5, "tools: %d moves (%s)", c.n, c.error.message);
  if (c.n != 5) return;
  CHECK(c.moves[0].kind == SWARF_MOVE_TOOL_CHANGE && c.moves[0].tool == 3, "T3 M6");
  CHECK(c.moves[0].column == 4, "tool change column %d", c.moves[0].column);
  CHECK(c.moves[1].tool == 3 && c.moves[1].spindle == 1000, "M3 S1000: %g", c.moves[1].spindle);
  CHECK(c.moves[2].tool == 3 && c.moves[2].spindle == -1000, "T2 alone changes nothing; M4");
  CHECK(c.moves[3].kind == SWARF_MOVE_TOOL_CHANGE && c.moves[3].tool == 2, "M6 takes T2");
  CHECK(c.moves[4].kind == SWARF_MOVE_DWELL && c.moves[4].dwell == 1.5, "G4 P1.5");
  CHECK(c.moves[4].spindle == 0 && c.moves[4].column == 4, "M5 before G4; column %d",
        c.moves[4].column);
  check_end(&c.moves[4], 2, 0, 0, "a dwell stays put");
}

static void test_g0_alone_and_g53(void) {
  run_text("G0\nG1 G53 Z-10 F10\n", &c);
  CHECK(c.status == 0 && c.n == 2, "G0 alone, G53: %d (%s)", c.n, c.error.message);
  if (c.n != 2) return;
  CHECK(c.moves[0].kind == SWARF_MOVE_RAPID, "G0 alone is a null rapid");
  check_end(&c.moves[1], 0, 0, -10, "G53 without offsets");
}

static int same_move(const swarf_move *a, const swarf_move *b) {
  int same = a->kind == b->kind && a->angle == b->angle && a->rise == b->rise &&
             a->feed == b->feed && a->spindle == b->spindle && a->dwell == b->dwell &&
             a->tool == b->tool && a->line == b->line && a->column == b->column;
  for (int i = 0; i < SWARF_NAXES; i++)
    same = same && a->start[i] == b->start[i] && a->end[i] == b->end[i];
  for (int i = 0; i < 3; i++)
    same = same && a->center[i] == b->center[i] && a->normal[i] == b->normal[i];
  return same;
}

static void test_streaming(void) {
  static const char program[] =
      "%\r\n(header) ; x\r\nG21 G90 G17\r\nT1 M6\r\nM3 S12000\r\nG0 X10 Y0 Z5\r\n"
      "G1 Z-1 F300\r\nG3 X0 Y10 I-10 J0\r\nG2 X10 Y0 R-10 Z-2\r\nG18 G2 X0 Z-2 I-5 K0\r\n"
      "G4 P0.5\r\nN100 G0 Z 1 0\r\n%\r\nG0 X99\r\n";
  static collected whole, piece;
  size_t len = strlen(program);
  run_text(program, &whole);
  CHECK(whole.status == 0 && whole.n == 8, "streaming program: %d moves (%s)", whole.n,
        whole.error.message);
  for (size_t step = 1; step <= 13; step += 6) {
    run_pieces(program, len, step, &piece);
    CHECK(piece.status == 0 && piece.n == whole.n, "pieces of %zu: %d moves", step, piece.n);
    for (int i = 0; i < whole.n && i < piece.n; i++)
      CHECK(same_move(&whole.moves[i], &piece.moves[i]), "pieces of %zu: move %d differs", step, i);
  }
}

int main(void) {
  test_modal_motion();
  test_distance_modes();
  test_inches();
  test_spelling();
  test_percent_and_end();
  test_line_numbers_and_block_delete();
  test_tools_spindle_dwell();
  test_g0_alone_and_g53();
  test_streaming();
  return check_done();
}
