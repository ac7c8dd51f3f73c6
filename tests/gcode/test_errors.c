/* test_errors.c -- bad input: each error at its exact line and column (the
 * offending word or character), with a message naming it; a rejected block
 * emits nothing (parse, check, then commit); a stopped or failed parser
 * stays stopped; unreadable files; nothing crashes on garbage.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "collect.h"

typedef struct {
  const char *program;
  long line;
  int column;
  const char *words; /* must appear in the message */
  int status;
} bad_case;

#define SYN SWARF_GCODE_ERR_SYNTAX
#define SEM SWARF_GCODE_ERR_SEMANTIC

static const bad_case cases[] = {
    /* Unknown words and codes. */
    {"G0 X1\nQ1\n", 2, 1, "Q word with no G64, G73, G83 or M code to use it", SEM},
    {"G0 X1\nG12.5 X2\n", 2, 1, "Unknown g code used: G12.5", SEM},
    {"M1.5\n", 1, 1, "Unknown m code used: M1.5", SEM},
    {"G0 M528\n", 1, 4, "M code greater than 199: M528", SEM},
    {"G38.2 Z1 F1\n", 1, 1, "G38.2 (probing) is not supported yet", SEM},
    {"G0 X1 U2\n", 1, 7, "U2", SEM},
    {"G0 X1e5\n", 1, 6, "E5", SEM},
    /* Cutter radius compensation (messages as rs274 gives them). */
    {"G41.1 G1 X1 F1\n", 1, 1, "G41.1 with no D word", SEM},
    {"G42.1\n", 1, 1, "G42.1 with no D word", SEM},
    {"G41.1 D1\nG42.1 D1\n", 2, 1, "Cannot turn cutter radius comp on when on", SEM},
    {"G19 G41.1 D1\n", 1, 5, "Cutter radius compensation allowed only in XY, XZ planes", SEM},
    {"G41.1 D1\nG1 X.4 F1\n", 2, 1,
     "Length of cutter compensation entry move is not greater than the tool radius", SEM},
    {"G41.1 D1\nG2 X.4 I.2 F1\n", 2, 1,
     "Radius of cutter compensation entry arc is not greater than the tool radius", SEM},
    {"G41.1 D1\nG1 X5 F1\nG28\n", 3, 1, "Cannot use g28 or g30 with cutter radius comp", SEM},
    {"G41.1 D1\nG1 X5 F1\nG1 G53 X6\n", 3, 4, "Cannot use g53 with cutter radius comp", SEM},
    {"G41.1 D1\nG1 X5 F1\nG18\n", 3, 1, "Cannot change planes with cutter radius compensation on",
     SEM},
    {"G41.1 D1\nG1 X5 F1\nG92 X0\n", 3, 1, "Cannot change axis offsets with cutter radius comp",
     SEM},
    {"G41.1 D1\nG1 X5 F1\nT1 M6\n", 3, 4, "Cannot change tools with cutter radius compensation on",
     SEM},
    {"G41.1 D1\nG1 X5 F1\nG43 H1\n", 3, 1,
     "Cannot change tool offset with cutter radius compensation on", SEM},
    {"G41.1 D1\nG1 X5 F1\nG55\n", 3, 1,
     "Cannot change coordinate systems with cutter radius compensation on", SEM},
    {"G41.1 D1\nG1 X5 F1\nG64 P.1\n", 3, 1,
     "Cannot change control mode with cutter radius compensation on", SEM},
    {"G41.1 D1\nG1 X5 F1\nG81 R1 Z-1\n", 3, 1,
     "Cannot use canned cycles with cutter compensation on", SEM},
    {"G41 D7\n", 1, 5, "Requested tool 7 not found in the tool table", SEM},
    {"G42 D1.5\n", 1, 5, "G42 requires D word to be a whole number", SEM},
    {"G1 D1 X1 F1\n", 1, 4,
     "D word with no G41, G41.1, G42, G42.1, G71, G71.1, G71.2 or G96 to use it", SEM},
    {"G41.1 D1\nG1 X5 F1\nG3 X5 Y.8 J.4\n", 3, 1, "Tool radius not less than arc radius with comp",
     SEM},
    {"G41.1 D.5\nG1 X5 F1\nG40\nG2 X6 I.5\n", 4, 1,
     "The move just after exiting cutter compensation mode must be straight, not an arc", SEM},
    {"G41.1 D.5\nG1 X1 F1\nG1 X2\nG1 Y.1\nG1 X1\n", 5, 1,
     "Straight feed in concave corner cannot be reached by the tool without gouging", SEM},
    {"G41.1 D.5\nG0 X1\nG0 X2\nG0 Y.1\nG0 X1\n", 5, 1,
     "Straight traverse in concave corner cannot be reached by the tool without gouging", SEM},
    /* Malformed numbers. */
    {"G1 X1.2.3 F10\n", 1, 4, "bad number format in word \"X1.2.3\"", SYN},
    {"G0 X-\n", 1, 4, "bad number format in word \"X-\"", SYN},
    {"G0 X1 G\n", 1, 7, "bad number format in word \"G\"", SYN},
    {"G0 X.\n", 1, 4, "bad number format in word \"X.\"", SYN},
    {"G0 X1-2\n", 1, 4, "\"X1-2\"", SYN},
    {"G0 X99999999999\n", 1, 4, "number out of range", SYN},
    /* Arcs. */
    {"G0 X0 Y0\nG2 X10 Y0 I4 J0 F100\n", 2, 1,
     "Radius to end of arc differs from radius to start: start=(X0.0000,Y0.0000) "
     "center=(X4.0000,Y0.0000) end=(X10.0000,Y0.0000) r1=4.0000 r2=6.0000 abs_err=2 "
     "rel_err=33.3333%",
     SEM},
    {"G0 X0\nG1 F10\nG2 X10 R4\n", 3, 1, "Arc radius too small to reach end point", SEM},
    {"G2 R5 X0 F1\n", 1, 1, "Current point same as end point of arc", SEM},
    {"G2 X1 Y1 F10\n", 1, 1, "R, I, J and K words all missing for arc", SEM},
    {"G2 X1 R1 I1 F1\n", 1, 7, "Mixed radius-ijk format for arc", SEM},
    {"G0 X10\nG2 X0 Y10 I-10 K1 F10\n", 2, 16, "K word given for arc in XY plane", SEM},
    {"G18 G2 X1 J1 F10\n", 1, 11, "J word given for arc in XZ plane", SEM},
    {"G90.1 G2 X1 I1 F10\n", 1, 7, "J word missing in absolute center arc", SEM},
    {"G2 X1 I1 P1.5 F1\n", 1, 10, "P value not an integer with G2 or G3", SEM},
    {"G2 X1 I1 P0 F1\n", 1, 10, "P value should be 1 or greater", SEM},
    {"G0 X1 I1\n", 1, 7, "I word with no G2 or G3 to use it", SEM},
    {"G2 I1\n", 1, 1, "Cannot make arc with zero feed rate", SEM},
    /* Feed, modal groups, repeated words. */
    {"G1 X1\n", 1, 1, "Cannot do G1 with zero feed rate", SEM},
    {"G0 X1\n  Y2 G1\n", 2, 6, "Cannot do G1 with zero feed rate", SEM},
    {"G0 G1 X1\n", 1, 4, "Two G codes used from same modal group: G0 and G1", SEM},
    {"M3 M4\n", 1, 4, "Two M codes used from same modal group: M3 and M4", SEM},
    {"G0 X1 X2\n", 1, 7, "Multiple X words on one line: X1 and X2", SEM},
    {"G80 X1\n", 1, 5, "Cannot use axis values with G80", SEM},
    {"X1\n", 1, 1, "Cannot use axis values without a G code", SEM},
    {"G0 X1 N5\n", 1, 7, "N5", SYN},
    {"G4\n", 1, 1, "Dwell time P word missing with G4", SEM},
    {"G1 F-1 X1\n", 1, 4, "Negative F word used: F-1", SEM},
    {"T1.5\n", 1, 1, "Non-integer value for integer: T1.5", SEM},
    {"G91 G53 G0 X1\n", 1, 5, "Cannot use G53 incremental", SEM},
    {"G53 G2 X1 I1 F1\n", 1, 1, "Must use G0 or G1 with G53", SEM},
    /* Comments, characters, parameters, expressions, O-words, %. */
    {"G0 X1 (abc\n", 1, 7, "Unclosed comment found", SYN},
    {"G0 (a(b)) X1\n", 1, 6, "Nested comment found", SYN},
    {"#1=\n", 1, 4, "bad number format", SYN},
    {"G0 Z#<nope>\n", 1, 5, "Named parameter #<nope> not defined", SEM},
    {"G0 X[1/0]\n", 1, 7, "Attempt to divide by zero", SEM},
    {"G0 X[1+2\n", 1, 9, "Unclosed expression", SYN},
    {"G0 X[SQRT[-1]]\n", 1, 6, "Negative argument to sqrt", SEM},
    {"G0 X#6000\n", 1, 6, "Parameter number out of range", SEM},
    {"G0 X1\no100 sub\nG0 X2\n", 2, 1, "ended inside an O-word construct", SEM},
    {"o100 endwhile\n", 1, 1, "needs an open construct", SEM},
    {"o<nope> call\n", 1, 1, "Unknown subroutine", SEM},
    {"o1 while [1]\no1 endwhile\n", 2, 1, "Loop limit reached", SEM},
    {"G81 X1 Y1 Z-1 F10\n", 1, 1, "R clear plane missing", SEM},
    {"G0 Z0\nG81 X1 Z1 R0 F10\n", 2, 1, "R value less than Z value", SEM},
    {"G43 H7\n", 1, 1, "Requested tool 7 not found", SEM},
    {"G0 X1 O100\n", 1, 7, "O word must come first", SYN},
    {"G0 X1 $\n", 1, 7, "Bad character '$' used", SYN},
    {"G0 X1\x01\n", 1, 6, "Bad character '\\x01' used", SYN},
    {"G0 X1\n%\n", 2, 1, "Bad character '%'", SYN},
    {"%\nG0 X1\n% text\n", 3, 1, "Bad character '%'", SYN},
};

static void check_case(const bad_case *k) {
  static collected c;
  run_text(k->program, &c);
  CHECK(c.status == k->status, "\"%s\": status %d, expected %d (%s)", k->program, c.status,
        k->status, c.error.message);
  CHECK(c.error.line == k->line && c.error.column == k->column,
        "\"%s\": at %ld:%d, expected %ld:%d (%s)", k->program, c.error.line, c.error.column,
        k->line, k->column, c.error.message);
  CHECK(strstr(c.error.message, k->words) != NULL, "\"%s\": message \"%s\" lacks \"%s\"",
        k->program, c.error.message, k->words);
  CHECK(strcmp(c.error.file, "test.ngc") == 0, "file name in the error: %s", c.error.file);
}

/* A NUL byte is a bad character like any other (the line goes on after it). */
static void test_nul_byte(void) {
  static collected c;
  static const char text[] = "G0 X1\nG0\0X2\n";
  run_pieces(text, sizeof text - 1, 4, &c);
  CHECK(c.status == SYN && c.error.line == 2 && c.error.column == 3 && c.n == 1,
        "NUL: status %d at %ld:%d, %d moves", c.status, c.error.line, c.error.column, c.n);
}

/* Parse, check, commit: a block that fails emits none of its moves, even
 * those (tool change, dwell) it would have made before the failing part. */
static void test_rejected_block_emits_nothing(void) {
  static collected c;
  run_text("G0 X1\nT5 M6 G4 P1 G1 X2\n", &c);
  CHECK(c.status == SEM && c.error.line == 2 && c.n == 1,
        "tool change and dwell of a failed block: status %d, %d moves", c.status, c.n);
  run_text("G0 X1\nG20 T5 M6 G2 X10 R0.1 F100\n", &c);
  CHECK(c.status == SEM && c.n == 1 && c.moves[0].tool == 0, "failed arc: status %d, %d moves",
        c.status, c.n);
}

static int stop_at_second(const swarf_move *mv, void *user) {
  int *count = user;
  (void)mv;
  return ++*count >= 2;
}

static void test_stop_and_sticky_errors(void) {
  static collected c;
  int count = 0, status;
  swarf_gcode_parser *p = swarf_gcode_parser_new("stop.ngc", stop_at_second, &count);
  status = swarf_gcode_parser_feed(p, "G0 X1\nG0 X2\nG0 X3\n", 18);
  CHECK(status == SWARF_GCODE_ERR_STOPPED && count == 2, "stopped: %d after %d", status, count);
  CHECK(swarf_gcode_parser_error(p) && swarf_gcode_parser_error(p)->line == 2, "stop line");
  status = swarf_gcode_parser_feed(p, "G0 X4\n", 6);
  CHECK(status == SWARF_GCODE_ERR_STOPPED && count == 2, "a stopped parser stays stopped");
  CHECK(swarf_gcode_parser_finish(p) == SWARF_GCODE_ERR_STOPPED, "finish after stop");
  swarf_gcode_parser_free(p);

  p = swarf_gcode_parser_new("sticky.ngc", collect_move, &c);
  memset(&c, 0, sizeof c);
  status = swarf_gcode_parser_feed(p, "G0 X1\nG0 X1 X2\n", 15);
  CHECK(status == SEM && c.n == 1, "first error");
  status = swarf_gcode_parser_feed(p, "G0 X4\n", 6);
  CHECK(status == SEM && c.n == 1, "input after an error is refused");
  CHECK(swarf_gcode_parser_error(p)->line == 2, "the first error stays");
  swarf_gcode_parser_free(p);
  CHECK(swarf_gcode_parser_feed(NULL, "x", 1) == SWARF_GCODE_ERR_ARG, "NULL parser");
}

static void test_files(void) {
  swarf_gcode_error err;
  int status = swarf_gcode_parse_file("/nonexistent/dir/prog.ngc", NULL, NULL, &err);
  CHECK(status == SWARF_GCODE_ERR_ARG && err.line == 0, "missing file: %d", status);
  CHECK(strstr(err.message, "cannot open") != NULL && strstr(err.file, "prog.ngc") != NULL,
        "missing file message: %s (%s)", err.message, err.file);
}

static void test_long_line(void) {
  static collected c;
  size_t len = (1 << 20) + 10;
  char *text = malloc(len);
  memset(text, ' ', len);
  memcpy(text, "G0 X1\n", 6);
  run_pieces(text, len, 4096, &c);
  CHECK(c.status == SYN && c.error.line == 2 && strstr(c.error.message, "line too long"),
        "a line over 1 MiB: status %d at line %ld", c.status, c.error.line);
  run_text("", &c);
  CHECK(c.status == 0 && c.n == 0, "empty program");
  free(text);
}

int main(void) {
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    check_case(&cases[i]);
  test_nul_byte();
  test_rejected_block_emits_nothing();
  test_stop_and_sticky_errors();
  test_files();
  test_long_line();
  return check_done();
}
