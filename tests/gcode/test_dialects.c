/* SPDX-License-Identifier: MPL-2.0 */
/* test_dialects.c -- Fanuc, Haas and grbl programs against their manuals.
 *
 * Each program is written in its controller's style (an Autodesk-style
 * post, subprograms after M30, a bolt-hole macro, Haas's local
 * subprograms and vendor codes, a grbl sender's stream) and its moves are
 * worked out here by hand from the rule quoted above each case, not taken
 * from swarf's output. Then the same program under the LinuxCNC dialect,
 * which refuses it where LinuxCNC's rs274 refuses it (rs274's own message
 * for that line is quoted).
 *
 * The machine starts at 0,0,0; tool 1 has length 0 (G43 H1 moves nothing),
 * so the machine frame is the program frame except where work offsets are
 * set. Positions are mm.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "gcode.h"

#define MAX_MOVES 256
#define MAX_NOTES 16

typedef struct {
  swarf_move v[MAX_MOVES];
  int n;
  long note_line[MAX_NOTES];
  char note[MAX_NOTES][200];
  int nnotes;
  swarf_error err;
  int status;
} run_out;

static int keep(const swarf_move *m, void *user) {
  run_out *o = user;
  if (m->kind != SWARF_MOVE_TOOL_CHANGE && o->n < MAX_MOVES) o->v[o->n++] = *m;
  return 0;
}

static void note(long line, int column, const char *text, void *user) {
  run_out *o = user;
  (void)column;
  if (o->nnotes < MAX_NOTES) {
    o->note_line[o->nnotes] = line;
    snprintf(o->note[o->nnotes++], 200, "%s", text);
  }
}

static run_out out;

static run_out *run(swarf_gcode_dialect d, const char *text) {
  swarf_gcode_parser *p = NULL;
  memset(&out, 0, sizeof out);
  swarf_gcode_parser_new("test.nc", keep, &out, &p);
  swarf_gcode_parser_clear_tools(p);
  swarf_gcode_parser_set_tool(p, 1, 0, 6);
  swarf_gcode_parser_set_notes(p, note, &out);
  out.status = swarf_gcode_parser_set_dialect(p, d, &out.err);
  if (out.status == SWARF_OK) out.status = swarf_gcode_parser_feed(p, text, strlen(text));
  if (out.status == SWARF_OK) out.status = swarf_gcode_parser_finish(p);
  if (swarf_gcode_parser_error(p) != NULL) out.err = *swarf_gcode_parser_error(p);
  swarf_gcode_parser_free(p);
  return &out;
}

typedef struct {
  swarf_move_kind kind;
  double x, y, z;
  double dwell; /* DWELL moves */
} want_move;

#define R_ SWARF_MOVE_RAPID
#define L_ SWARF_MOVE_LINE
#define A_ SWARF_MOVE_ARC
#define D_ SWARF_MOVE_DWELL

static void expect(const char *name, const run_out *o, const want_move *w, int n) {
  CHECK(o->status == SWARF_OK, "%s: refused at %ld:%d: %s", name, o->err.line, o->err.column,
        o->err.message);
  CHECK(o->n == n, "%s: %d moves, expected %d", name, o->n, n);
  for (int i = 0; i < n && i < o->n; i++) {
    const swarf_move *m = &o->v[i];
    CHECK(m->kind == w[i].kind, "%s: move %d kind %d, expected %d", name, i + 1, m->kind,
          w[i].kind);
    if (w[i].kind == D_) {
      CHECK(fabs(m->dwell - w[i].dwell) < 1e-12, "%s: move %d dwell %g s, expected %g", name, i + 1,
            m->dwell, w[i].dwell);
      continue;
    }
    CHECK(fabs(m->end[0] - w[i].x) < 1e-9 && fabs(m->end[1] - w[i].y) < 1e-9 &&
              fabs(m->end[2] - w[i].z) < 1e-9,
          "%s: move %d (line %ld) ends at %g %g %g, expected %g %g %g", name, i + 1, m->line,
          m->end[0], m->end[1], m->end[2], w[i].x, w[i].y, w[i].z);
  }
}

static void refused(const char *name, const run_out *o, long line, int code) {
  CHECK(o->status != SWARF_OK && o->err.line == line && o->err.code == code,
        "%s: status %d at line %ld, %s (%s); expected line %ld, %s", name, o->status, o->err.line,
        swarf_gcode_error_name(o->err.code) ? swarf_gcode_error_name(o->err.code) : "none",
        o->err.message, line, swarf_gcode_error_name(code));
}

/* ---- Fanuc ----------------------------------------------------------------- */

/* An Autodesk-style Fanuc post. Rules (Fanuc 0i-MF Operator's Manual):
 * "%" opens and closes the program, O1001 is its number; canned cycles are
 * group 09 and G0-G3 group 01: "when G80 is specified, the canned cycle is
 * canceled and the modal G code of group 01 in effect before the cycle is
 * restored" (here G0 of N55), so the bare Z15. of N75 is a rapid; G98
 * returns to the initial level (Z5., where N60 found the tool), the tool
 * goes down to R at rapid, feeds to Z, rapids out; G28 G91 Z0.: the
 * intermediate point is the current one (incremental 0), then Z goes to
 * the reference position (machine 0). */
static const char fanuc_post[] = "%\n"
                                 "O1001 (BRACKET)\n"
                                 "(T1  D=6. - DRILL)\n"
                                 "N10 G90 G94 G17 G49 G40 G80\n"
                                 "N15 G21\n"
                                 "N20 G28 G91 Z0.\n"
                                 "N25 G90\n"
                                 "N30 T1 M6\n"
                                 "N35 S5000 M3\n"
                                 "N40 G54\n"
                                 "N45 G0 X10. Y10.\n"
                                 "N50 G43 Z15. H1\n"
                                 "N55 G0 Z5.\n"
                                 "N60 G98 G81 X10. Y10. Z-5. R2. F100.\n"
                                 "N65 X20.\n"
                                 "N70 G80\n"
                                 "N75 Z15.\n"
                                 "N80 M5\n"
                                 "N85 G28 G91 Z0.\n"
                                 "N90 G90\n"
                                 "N95 M30\n"
                                 "%\n";

static void test_fanuc_post(void) {
  static const want_move w[] = {
      {R_, 0, 0, 0, 0},   {R_, 0, 0, 0, 0},    {R_, 10, 10, 0, 0},  {R_, 10, 10, 15, 0},
      {R_, 10, 10, 5, 0}, {R_, 10, 10, 5, 0},  {R_, 10, 10, 2, 0},  {L_, 10, 10, -5, 0},
      {R_, 10, 10, 5, 0}, {R_, 20, 10, 5, 0},  {R_, 20, 10, 2, 0},  {L_, 20, 10, -5, 0},
      {R_, 20, 10, 5, 0}, {R_, 20, 10, 15, 0}, {R_, 20, 10, 15, 0}, {R_, 20, 10, 0, 0}};
  expect("fanuc post", run(SWARF_GCODE_DIALECT_FANUC, fanuc_post), w, 16);
  CHECK(out.v[13].line == 17, "the bare Z15. after G80 is line 17 (%ld)", out.v[13].line);
  /* rs274: "Cannot use axis values without a g code that uses them" at Z15. */
  refused("fanuc post as linuxcnc", run(SWARF_GCODE_DIALECT_LINUXCNC, fanuc_post), 17,
          SWARF_GCODE_E_AXES_WITHOUT_MOTION);
}

/* Subprograms after the main program. Rules: "M98 P_ L_: the subprogram
 * O_ is called L times" and "P with more than four digits: the leading
 * digits are the repeat count, the last four the program number" (M98
 * P30002 = O0002 three times); M99 returns to the block after the call; a
 * subprogram shares the caller's modes (G91 set in it stays until G90). */
static const char fanuc_subs[] = "%\n"
                                 "O2000 (MAIN)\n"
                                 "G21 G90 G17 G94\n"
                                 "G0 X0 Y0 Z5.\n"
                                 "M98 P2001 L2\n"
                                 "G0 X50. Y0\n"
                                 "M98 P30002\n"
                                 "M30\n"
                                 "O2001 (STEP)\n"
                                 "G91 G1 X10. F200.\n"
                                 "Y10.\n"
                                 "G90\n"
                                 "M99\n"
                                 "O0002\n"
                                 "G91 G0 Z-1.\n"
                                 "G90\n"
                                 "M99\n"
                                 "%\n";

static void test_fanuc_subprograms(void) {
  static const want_move w[] = {{R_, 0, 0, 5, 0},   {L_, 10, 0, 5, 0},  {L_, 10, 10, 5, 0},
                                {L_, 20, 10, 5, 0}, {L_, 20, 20, 5, 0}, {R_, 50, 0, 5, 0},
                                {R_, 50, 0, 4, 0},  {R_, 50, 0, 3, 0},  {R_, 50, 0, 2, 0}};
  expect("fanuc M98/M99", run(SWARF_GCODE_DIALECT_FANUC, fanuc_subs), w, 9);
  CHECK(out.v[1].line == 10 && out.v[6].line == 15, "subprogram moves carry their own lines");
  /* Haas reads P as the program number: there is no O30002. */
  refused("haas M98 P30002", run(SWARF_GCODE_DIALECT_HAAS, fanuc_subs), 7,
          SWARF_GCODE_E_FANUC_NO_PROGRAM);
}

/* A custom macro: "G65 P_ L_ <arguments>: A=#1 ... H=#11 ... R=#18 ...
 * X=#24 Y=#25 Z=#26" (argument specification I); "local variables #1-#33
 * are cleared at each call and restored on return"; #100-#199 are common
 * to all macros; "WHILE [<expression>] DO m ... END m" repeats while the
 * expression holds; "IF [<expression>] GOTO n"; arithmetic on the right of
 * "=" needs no brackets. Four holes on a circle of radius 10 about (50,
 * 20), at 0, 90, 180 and 270 degrees. */
static const char fanuc_macro[] = "%\n"
                                  "O3000\n"
                                  "G21 G90 G0 X0 Y0 Z10.\n"
                                  "#100 = 0\n"
                                  "G65 P9010 X50. Y20. R10. H4. Z-3.\n"
                                  "G0 X[#24 + 1.] Y#100\n"
                                  "G0 Z10.\n"
                                  "M30\n"
                                  "O9010 (BOLT HOLES)\n"
                                  "#30 = 0\n"
                                  "WHILE [#30 LT #11] DO1\n"
                                  "#31 = #24 + #18 * COS[#30 * 360 / #11]\n"
                                  "#32 = #25 + #18 * SIN[#30 * 360 / #11]\n"
                                  "G0 X#31 Y#32\n"
                                  "G1 Z#26 F100.\n"
                                  "G0 Z2.\n"
                                  "#30 = #30 + 1\n"
                                  "#100 = #100 + 1\n"
                                  "END1\n"
                                  "IF [#100 NE 4] GOTO 99\n"
                                  "G0 X#24 Y#25\n"
                                  "N99 M99\n"
                                  "%\n";

static void test_fanuc_macro(void) {
  want_move w[16];
  int k = 0;
  double z = 10;
  w[k++] = (want_move){R_, 0, 0, 10, 0};
  for (int i = 0; i < 4; i++) {
    double a = i * 90 * 3.14159265358979323846 / 180, x = 50 + 10 * cos(a), y = 20 + 10 * sin(a);
    w[k++] = (want_move){R_, x, y, z, 0};
    w[k++] = (want_move){L_, x, y, -3, 0};
    w[k++] = (want_move){R_, x, y, 2, 0};
    z = 2;
  }
  w[k++] = (want_move){R_, 50, 20, 2, 0}; /* #100 is 4: no jump */
  w[k++] = (want_move){R_, 1, 4, 2, 0};   /* #24 is the main's again (0); #100 common */
  w[k++] = (want_move){R_, 1, 4, 10, 0};
  expect("fanuc G65 macro", run(SWARF_GCODE_DIALECT_FANUC, fanuc_macro), w, k);
  /* rs274: "Unknown g code used" (G65 is no LinuxCNC code). */
  refused("fanuc macro as linuxcnc", run(SWARF_GCODE_DIALECT_LINUXCNC, fanuc_macro), 5,
          SWARF_GCODE_E_UNKNOWN_G_CODE);
}

/* Offsets. Rules: "G10 L2 Pp IP_: p = 1-6 is the workpiece origin of G54 to
 * G59"; "G10 L20 Pn IP_: the origin of the additional system G54.1 Pn";
 * "in incremental mode (G91) the value is added to the offset". */
static void test_fanuc_offsets(void) {
  static const char prog[] = "G21 G90\n"
                             "G10 L2 P1 X100. Y50. Z-20.\n"
                             "G10 L20 P5 X-10. Y-10. Z0\n"
                             "G54 G0 X0 Y0 Z0\n"
                             "G54.1 P5 G0 X1. Y1. Z1.\n"
                             "G91 G10 L2 P1 X1.\n"
                             "G90 G54 G0 X0 Y0 Z0\n"
                             "M30\n";
  static const want_move w[] = {{R_, 100, 50, -20, 0}, {R_, -9, -9, 1, 0}, {R_, 101, 50, -20, 0}};
  expect("fanuc G10 and G54.1", run(SWARF_GCODE_DIALECT_FANUC, prog), w, 3);
  /* rs274: "Unknown g code used" for G54.1 (line 5). */
  refused("G54.1 as linuxcnc", run(SWARF_GCODE_DIALECT_LINUXCNC, prog), 5,
          SWARF_GCODE_E_UNKNOWN_G_CODE);
}

/* Dwells and repeats. Rules: "G04 P_: no decimal point, 1 = 1 ms"; "G04
 * X_: seconds"; "G82 ... P: dwell at the bottom, as for G04"; "K: the
 * number of repeats" of a cycle; under G91 "R: the distance from the
 * initial level to R, Z: from R to the bottom", the position advances by X
 * on each repeat; G99 returns to R. */
static void test_fanuc_dwell_repeats(void) {
  static const char prog[] = "G21 G90 G0 X0 Y0 Z5. F100.\n"
                             "G04 P1500\n"
                             "G04 X2.5\n"
                             "G91 G99 G81 X10. Z-5. R-3. K3\n"
                             "G90 G82 X40. Z-1. R2. P500\n"
                             "G80\n"
                             "M30\n";
  static const want_move w[] = {{R_, 0, 0, 5, 0},   {D_, 0, 0, 0, 1.5}, {D_, 0, 0, 0, 2.5},
                                {R_, 10, 0, 5, 0},  {R_, 10, 0, 2, 0},  {L_, 10, 0, -3, 0},
                                {R_, 10, 0, 2, 0},  {R_, 20, 0, 2, 0},  {L_, 20, 0, -3, 0},
                                {R_, 20, 0, 2, 0},  {R_, 30, 0, 2, 0},  {L_, 30, 0, -3, 0},
                                {R_, 30, 0, 2, 0},  {R_, 40, 0, 2, 0},  {L_, 40, 0, -1, 0},
                                {D_, 0, 0, 0, 0.5}, {R_, 40, 0, 2, 0}};
  expect("fanuc dwell and K", run(SWARF_GCODE_DIALECT_FANUC, prog), w, 17);
}

/* G76 fine boring. Rule (Fanuc 0i-MF): "at the bottom of the hole the
 * spindle stops at a fixed position, the tool moves in the direction
 * opposite to the tool tip by Q and is retracted"; the shift is +X with the
 * parameters as shipped (Haas: Setting 27 X+); P dwells at the bottom (ms
 * without a point); G98 returns to the initial level; then the tool shifts
 * back over the hole. */
static void test_fanuc_fine_boring(void) {
  static const char prog[] = "G21 G90 G0 X10. Y10. Z5. F100. S1000 M3\n"
                             "G98 G76 X10. Y10. Z-8. R2. Q0.5 P1000\n"
                             "G80\n"
                             "M30\n";
  static const want_move w[] = {{R_, 10, 10, 5, 0},   {R_, 10, 10, 5, 0}, {R_, 10, 10, 2, 0},
                                {L_, 10, 10, -8, 0},  {D_, 0, 0, 0, 1.0}, {R_, 10.5, 10, -8, 0},
                                {R_, 10.5, 10, 5, 0}, {R_, 10, 10, 5, 0}};
  expect("fanuc G76", run(SWARF_GCODE_DIALECT_FANUC, prog), w, 8);
  /* LinuxCNC's G76 is lathe threading: not supported (refused at line 2). */
  refused("G76 as linuxcnc", run(SWARF_GCODE_DIALECT_LINUXCNC, prog), 2,
          SWARF_GCODE_E_CODE_NOT_SUPPORTED);
}

/* Jumps and the end of the main program. Rules: "M99 Pn in a subprogram
 * returns to the block Nn of the caller"; "GOTO n" jumps to Nn; M99 in the
 * main program would run it again from its start (the simulation stops
 * with a note); a call to a program the file lacks is an alarm. */
static void test_fanuc_jumps(void) {
  static const char prog[] = "G21 G0 X0 Y0 Z0\n"
                             "M98 P100\n"
                             "G0 X99.\n"
                             "N20 G0 X2.\n"
                             "GOTO 40\n"
                             "G0 X98.\n"
                             "N40 G0 Y3.\n"
                             "M99\n"
                             "G0 Z97.\n"
                             "O100\n"
                             "G0 X1.\n"
                             "M99 P20\n";
  static const want_move w[] = {
      {R_, 0, 0, 0, 0}, {R_, 1, 0, 0, 0}, {R_, 2, 0, 0, 0}, {R_, 2, 3, 0, 0}};
  expect("fanuc M99 P and GOTO", run(SWARF_GCODE_DIALECT_FANUC, prog), w, 4);
  CHECK(out.nnotes == 1 && out.note_line[0] == 8 && strstr(out.note[0], "M99") != NULL,
        "M99 in the main program: a note at line 8 (%d notes)", out.nnotes);
  /* "O9000-O9999: programs the machine builder keeps in the control" (a
   * probing macro): skipped with a note, no motion. */
  run(SWARF_GCODE_DIALECT_FANUC, "G0 X1\nG65 P9810 Z-5. F1000.\nG0 X2\nM30\n");
  CHECK(out.status == SWARF_OK && out.n == 2 && out.nnotes == 1 && out.note_line[0] == 2,
        "G65 P9810 skipped with a note (%d moves, %d notes, %s)", out.n, out.nnotes,
        out.err.message);
  refused("M98 to a missing program", run(SWARF_GCODE_DIALECT_FANUC, "G0 X1\nM98 P77\nM30\n"), 2,
          SWARF_GCODE_E_FANUC_NO_PROGRAM);
  refused("GOTO a missing block", run(SWARF_GCODE_DIALECT_FANUC, "G0 X1\nGOTO 5\nM30\n"), 2,
          SWARF_GCODE_E_FANUC_NO_SEQUENCE);
  refused("a loop that never ends", run(SWARF_GCODE_DIALECT_FANUC, "G0 X1\nDO1\nEND1\nM30\n"), 3,
          SWARF_GCODE_E_O_WORK_LIMIT);
  /* "IF [<expression>] THEN <macro statement>" runs the assignment only when
   * the expression holds. */
  run(SWARF_GCODE_DIALECT_FANUC,
      "#5 = 1\nIF [#5 EQ 1] THEN #5 = 3\nIF [#5 EQ 1] THEN #5 = 9\nG0 X#5\n");
  CHECK(out.status == SWARF_OK && out.n == 1 && out.v[0].end[0] == 3, "IF THEN (%s)",
        out.err.message);
  /* "#0 is always vacant" (read as 0 here); it cannot be set. rs274:
   * "Parameter number out of range". */
  run(SWARF_GCODE_DIALECT_FANUC, "#1 = 7\n#1 = #0\nG0 X[#1 + 5.]\n");
  CHECK(out.status == SWARF_OK && out.n == 1 && out.v[0].end[0] == 5, "fanuc #0 reads 0 (%s)",
        out.err.message);
  refused("fanuc #0 = 1", run(SWARF_GCODE_DIALECT_FANUC, "#0 = 1\n"), 1,
          SWARF_GCODE_E_PARAMETER_RANGE);
  refused("#0 in linuxcnc", run(SWARF_GCODE_DIALECT_LINUXCNC, "G0 X#0\n"), 1,
          SWARF_GCODE_E_PARAMETER_RANGE);
  refused("macro alarm", run(SWARF_GCODE_DIALECT_FANUC, "G0 X1\n#3000 = 12 (TOOL BROKEN)\n"), 2,
          SWARF_GCODE_E_FANUC_ALARM);
}

/* ---- Haas ------------------------------------------------------------------ */

/* Rules (Haas Mill Operator's Manual): "M97 Pnnnn Lnn calls a local
 * subprogram: the block Nnnnn of the same program, L times", "M99 ends
 * it"; "G154 P1-P99 selects additional work offsets", set by "G10 L20 P";
 * "G04 P: with a decimal point seconds, without milliseconds"; G187
 * (smoothness), G103 (look-ahead), M31/M33 (chip auger), M88 (through-
 * spindle coolant) make no motion. */
static const char haas_prog[] = "%\n"
                                "O01000 (HAAS MAIN)\n"
                                "G00 G17 G40 G49 G80 G90\n"
                                "G21\n"
                                "G187 P1 E0.01 (SMOOTHNESS)\n"
                                "G103 P1\n"
                                "T1 M06\n"
                                "G10 L20 P3 X5. Y5. Z0\n"
                                "G154 P3\n"
                                "G00 X0 Y0 Z10.\n"
                                "M31\n"
                                "M88\n"
                                "M97 P100 L2\n"
                                "G00 Z50.\n"
                                "G04 P500\n"
                                "G04 P.5\n"
                                "M33\n"
                                "M30\n"
                                "N100 G91 G01 X10. F500.\n"
                                "G90 M99\n"
                                "%\n";

static void test_haas(void) {
  /* line 3's G00 alone is a null rapid, as in LinuxCNC */
  static const want_move w[] = {{R_, 0, 0, 0, 0},   {R_, 5, 5, 10, 0},  {L_, 15, 5, 10, 0},
                                {L_, 25, 5, 10, 0}, {R_, 25, 5, 50, 0}, {D_, 0, 0, 0, 0.5},
                                {D_, 0, 0, 0, 0.5}};
  static const long note_lines[] = {5, 6, 11, 12, 17};
  expect("haas", run(SWARF_GCODE_DIALECT_HAAS, haas_prog), w, 7);
  CHECK(out.nnotes == 5, "haas: 5 notes (%d)", out.nnotes);
  for (int i = 0; i < 5 && i < out.nnotes; i++)
    CHECK(out.note_line[i] == note_lines[i], "haas: note %d at line %ld, expected %ld", i,
          out.note_line[i], note_lines[i]);
  CHECK(out.nnotes >= 3 && strstr(out.note[2], "chip auger") != NULL, "M31 named: %s",
        out.nnotes >= 3 ? out.note[2] : "");
  /* rs274: "G-code out of range" for G187 (line 5). */
  refused("haas as linuxcnc", run(SWARF_GCODE_DIALECT_LINUXCNC, haas_prog), 5,
          SWARF_GCODE_E_UNKNOWN_G_CODE);
  /* Fanuc has no G154 (G54.1 P instead) and no M97: a machine builder's
   * code there, noted, no call made. */
  refused("haas as fanuc", run(SWARF_GCODE_DIALECT_FANUC, haas_prog), 9,
          SWARF_GCODE_E_UNKNOWN_G_CODE);
  run(SWARF_GCODE_DIALECT_FANUC, "G0 X1\nM97 P100\nG0 X2\nM30\nN100 G0 X3\nM99\n");
  CHECK(out.status == SWARF_OK && out.n == 2 && out.nnotes == 1,
        "fanuc: M97 is no call (%d moves, %d notes, %s)", out.n, out.nnotes, out.err.message);
}

/* ---- grbl ------------------------------------------------------------------ */

/* A sender's stream for grbl 1.1 (its wiki: "Grbl v1.1 Commands"): `$`
 * lines are system commands and settings ($H homing, $X unlock, $J= jog),
 * the senders strip `%`; G10 L20 P1 X-10 sets G54 so that the current point
 * reads X-10; G2 with I J is incremental centre; G38.3 probes without an
 * error on no contact. */
static const char grbl_prog[] = "$H\n"
                                "$X\n"
                                "%\n"
                                "G21 G90 G94\n"
                                "G10 L20 P1 X-10\n"
                                "G0 X0 Y0 Z5\n"
                                "G1 Z-1 F300\n"
                                "G2 X20 Y0 I10 J0\n"
                                "G4 P0.5\n"
                                "G38.3 Z-5 F50\n"
                                "G0 Z5\n"
                                "$J=G91 X1 F100\n"
                                "M5\n"
                                "M30\n"
                                "%\n";

static void test_grbl(void) {
  static const want_move w[] = {{R_, 10, 0, 5, 0},  {L_, 10, 0, -1, 0}, {A_, 30, 0, -1, 0},
                                {D_, 0, 0, 0, 0.5}, {L_, 30, 0, -5, 0}, {R_, 30, 0, 5, 0}};
  static const long note_lines[] = {1, 2, 3, 10, 12};
  expect("grbl", run(SWARF_GCODE_DIALECT_GRBL, grbl_prog), w, 6);
  CHECK(out.n == 6 && fabs(out.v[2].center[0] - 20) < 1e-9 && out.v[2].normal[2] < 0,
        "grbl: G2 about machine X20 (program X10), clockwise");
  CHECK(out.nnotes == 5, "grbl: 5 notes (%d)", out.nnotes);
  for (int i = 0; i < 5 && i < out.nnotes; i++)
    CHECK(out.note_line[i] == note_lines[i], "grbl: note %d at line %ld, expected %ld", i,
          out.note_line[i], note_lines[i]);
  /* rs274: "Unknown word where unary operation could be" at $H. */
  run(SWARF_GCODE_DIALECT_LINUXCNC, grbl_prog);
  CHECK(out.status != SWARF_OK && out.err.line == 1, "linuxcnc refuses $H (%s)", out.err.message);
  /* grbl refuses what it has not: "error:20 Unsupported or invalid g-code command". */
  refused("grbl G81", run(SWARF_GCODE_DIALECT_GRBL, "G21\nG81 X1 Z-1 R1 F10\n"), 2,
          SWARF_GCODE_E_DIALECT_CODE);
  refused("grbl G43 H", run(SWARF_GCODE_DIALECT_GRBL, "G43 H1\n"), 1, SWARF_GCODE_E_DIALECT_CODE);
  refused("grbl parameters", run(SWARF_GCODE_DIALECT_GRBL, "G0 X1\n#1 = 2\n"), 2,
          SWARF_GCODE_E_DIALECT_PARAMETERS);
  refused("grbl O words", run(SWARF_GCODE_DIALECT_GRBL, "o100 call\n"), 1,
          SWARF_GCODE_E_DIALECT_PARAMETERS);
  refused("grbl A axis", run(SWARF_GCODE_DIALECT_GRBL, "G0 A10\n"), 1,
          SWARF_GCODE_E_DIALECT_LETTER);
  refused("grbl G10 L1", run(SWARF_GCODE_DIALECT_GRBL, "G10 L1 P1 Z1\n"), 1,
          SWARF_GCODE_E_DIALECT_G10);
}

/* Errors come in file order, as a control reading the stream would meet
 * them: a kept Fanuc or Haas program's own error (line 3) before the stray
 * closing `%` (line 4) of a program that did not open with one. */
static void test_error_order(void) {
  static const char prog[] = "O1000\nG0 X1\nG2 X2 F100\n%\n";
  for (int d = 0; d < 2; d++) {
    const run_out *o = run(d ? SWARF_GCODE_DIALECT_HAAS : SWARF_GCODE_DIALECT_FANUC, prog);
    CHECK(o->status != SWARF_OK && o->err.line == 3 &&
              o->err.code != SWARF_GCODE_E_PERCENT_NOT_OPEN,
          "%s: the arc's error at line 3 first (got line %ld: %s)", d ? "haas" : "fanuc",
          o->err.line, o->err.message);
  }
  refused("fanuc stray %", run(SWARF_GCODE_DIALECT_FANUC, "O1000\nG0 X1\n%\n"), 3,
          SWARF_GCODE_E_PERCENT_NOT_OPEN);
}

/* Tool selection. LinuxCNC stops at a T word whose tool
 * the table lacks, as rs274 does ("Requested tool 5 not found in the tool
 * table", at the T word); T0, the empty spindle, is always there. A Fanuc or
 * Haas control holds its tool data: any T, and G43 H of a tool the table
 * lacks takes length 0 with a note. */
static void test_tool_words(void) {
  refused("linuxcnc T5 not in the table", run(SWARF_GCODE_DIALECT_LINUXCNC, "G21\nT5\nG0 X1\nM2\n"),
          2, SWARF_GCODE_E_TOOL_NOT_FOUND);
  CHECK(out.err.column == 1, "at the T word (column %d)", out.err.column);
  run(SWARF_GCODE_DIALECT_LINUXCNC, "G21\nT1 M6\nG0 X1\nT0 M6\nG0 X2\nM2\n");
  CHECK(out.status == SWARF_OK && out.n == 2, "linuxcnc T1 and T0 are taken (%s)", out.err.message);
  for (int d = 0; d < 2; d++) {
    run(d ? SWARF_GCODE_DIALECT_HAAS : SWARF_GCODE_DIALECT_FANUC,
        "%\nO1\nT5 M6\nG43 H5 Z5\nG0 X1\nM30\n%\n");
    CHECK(out.status == SWARF_OK && out.n == 2, "%s: T5 and G43 H5 without a table (%s)",
          d ? "haas" : "fanuc", out.err.message);
    CHECK(out.nnotes >= 1 && out.note_line[out.nnotes - 1] == 4 &&
              strstr(out.note[out.nnotes - 1], "taken as 0") != NULL,
          "%s: G43 H5's note at line 4 (%d notes)", d ? "haas" : "fanuc", out.nnotes);
    if (out.n == 2)
      CHECK(out.v[0].end[2] == 5.0, "%s: Z5 with no length offset", d ? "haas" : "fanuc");
  }
}

/* grbl's $H homes: a file of two jobs, each `$H` then
 * G10 L20 P1 X0 Y0 Z0, cuts the second where it cut the first (ignoring $H,
 * G10 L20 set the second origin where the first job ended: 10 mm off). */
static void test_grbl_home(void) {
  static const char two_jobs[] = "$H\nG21 G90\nG10 L20 P1 X0 Y0 Z0\nG0 X10\nG1 Z-1 F100\nG0 Z5\n"
                                 "$H\nG10 L20 P1 X0 Y0 Z0\nG0 X10\nG1 Z-1\nM30\n";
  run(SWARF_GCODE_DIALECT_GRBL, two_jobs);
  CHECK(out.status == SWARF_OK && out.n == 7, "grbl two jobs: 7 moves (%d, %s)", out.n,
        out.err.message);
  if (out.n == 7) {
    CHECK(out.v[1].end[0] == out.v[6].end[0] && out.v[1].end[2] == out.v[6].end[2],
          "grbl two jobs: the second job's cut at the first's (X%g Z%g vs X%g Z%g)",
          out.v[6].end[0], out.v[6].end[2], out.v[1].end[0], out.v[1].end[2]);
    CHECK(out.v[3].line == 7 && out.v[4].line == 7 && out.v[3].end[0] == 10 &&
              out.v[3].end[2] == 0 && out.v[4].end[0] == 0,
          "grbl $H at line 7: Z to the home first, then X and Y");
  }
}

static void test_names(void) {
  swarf_gcode_dialect d = SWARF_GCODE_DIALECT_LINUXCNC;
  CHECK(swarf_gcode_dialect_from_name("haas", &d) == 0 && d == SWARF_GCODE_DIALECT_HAAS, "haas");
  CHECK(swarf_gcode_dialect_from_name("mach3", &d) != 0, "mach3 is no dialect");
  CHECK(strcmp(swarf_gcode_dialect_name(SWARF_GCODE_DIALECT_GRBL), "grbl") == 0, "grbl's name");
  CHECK(swarf_gcode_dialect_name((swarf_gcode_dialect)7) == NULL, "7 is no dialect");
}

int main(void) {
  test_names();
  test_fanuc_post();
  test_fanuc_subprograms();
  test_fanuc_macro();
  test_fanuc_offsets();
  test_fanuc_dwell_repeats();
  test_fanuc_fine_boring();
  test_fanuc_jumps();
  test_haas();
  test_grbl();
  test_error_order();
  test_tool_words();
  test_grbl_home();
  return check_done();
}
