/* SPDX-License-Identifier: MPL-2.0 */
/* test_errors.c -- bad input: each error with its identity (errors.def: a
 * SWARF_GCODE_E_* code, matched instead of message text) and status at its
 * exact line and column (the offending word or character), the word filled
 * in; the table of identities is consistent; a rejected block emits nothing
 * (parse, check, then commit); a stopped or failed parser stays stopped;
 * unreadable files; nothing crashes on garbage.
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
  swarf_status status;
  int code; /* SWARF_GCODE_E_* */
} bad_case;

#define SYN SWARF_ERR_SYNTAX
#define SEM SWARF_ERR_SEMANTIC
#define LIM SWARF_ERR_LIMIT

static const bad_case cases[] = {
    /* Unknown words and codes. */
    {"G0 X1\nQ1\n", 2, 1, SEM, SWARF_GCODE_E_UNUSED_WORD},
    {"G0 X1\nG12.5 X2\n", 2, 1, SEM, SWARF_GCODE_E_UNKNOWN_G_CODE},
    {"M1.5\n", 1, 1, SEM, SWARF_GCODE_E_UNKNOWN_M_CODE},
    {"G0 M528\n", 1, 4, SEM, SWARF_GCODE_E_M_CODE_RANGE},
    {"G33 Z1 K1\n", 1, 1, SEM, SWARF_GCODE_E_CODE_NOT_SUPPORTED},
    {"G0 X1 U2\n", 1, 7, SEM, SWARF_GCODE_E_LETTER_NOT_SUPPORTED},
    {"G0 X1e5\n", 1, 6, SEM, SWARF_GCODE_E_LETTER_NOT_SUPPORTED},
    /* Cutter radius compensation (messages as rs274 gives them). */
    {"G41.1 G1 X1 F1\n", 1, 1, SEM, SWARF_GCODE_E_COMP_D_MISSING},
    {"G42.1\n", 1, 1, SEM, SWARF_GCODE_E_COMP_D_MISSING},
    {"G41.1 D1\nG42.1 D1\n", 2, 1, SEM, SWARF_GCODE_E_COMP_ON_WHEN_ON},
    {"G19 G41.1 D1\n", 1, 5, SEM, SWARF_GCODE_E_COMP_PLANE},
    {"G41.1 D1\nG1 X.4 F1\n", 2, 1, SEM, SWARF_GCODE_E_COMP_ENTRY_LINE},
    {"G41.1 D1\nG2 X.4 I.2 F1\n", 2, 1, SEM, SWARF_GCODE_E_COMP_ENTRY_ARC},
    {"G41.1 D1\nG1 X5 F1\nG28\n", 3, 1, SEM, SWARF_GCODE_E_COMP_G28_G30},
    {"G41.1 D1\nG1 X5 F1\nG1 G53 X6\n", 3, 4, SEM, SWARF_GCODE_E_COMP_G53},
    {"G41.1 D1\nG1 X5 F1\nG18\n", 3, 1, SEM, SWARF_GCODE_E_COMP_PLANE_CHANGE},
    {"G41.1 D1\nG1 X5 F1\nG92 X0\n", 3, 1, SEM, SWARF_GCODE_E_COMP_AXIS_OFFSETS},
    {"G41.1 D1\nG1 X5 F1\nT1 M6\n", 3, 4, SEM, SWARF_GCODE_E_COMP_TOOL_CHANGE},
    {"G41.1 D1\nG1 X5 F1\nG43 H1\n", 3, 1, SEM, SWARF_GCODE_E_COMP_TOOL_OFFSET},
    {"G41.1 D1\nG1 X5 F1\nG55\n", 3, 1, SEM, SWARF_GCODE_E_COMP_COORD_SYSTEM},
    {"G41.1 D1\nG1 X5 F1\nG64 P.1\n", 3, 1, SEM, SWARF_GCODE_E_COMP_CONTROL_MODE},
    {"G41.1 D1\nG1 X5 F1\nG81 R1 Z-1\n", 3, 1, SEM, SWARF_GCODE_E_CYCLE_WITH_COMP},
    {"G41 D7\n", 1, 5, SEM, SWARF_GCODE_E_TOOL_NOT_FOUND},
    {"G42 D1.5\n", 1, 5, SEM, SWARF_GCODE_E_COMP_D_NOT_WHOLE},
    {"G1 D1 X1 F1\n", 1, 4, SEM, SWARF_GCODE_E_UNUSED_WORD},
    {"G41.1 D1\nG1 X5 F1\nG3 X5 Y.8 J.4\n", 3, 1, SEM, SWARF_GCODE_E_COMP_ARC_RADIUS},
    {"G41.1 D.5\nG1 X5 F1\nG40\nG2 X6 I.5\n", 4, 1, SEM, SWARF_GCODE_E_ARC_AFTER_COMP_OFF},
    {"G41.1 D.5\nG1 X1 F1\nG1 X2\nG1 Y.1\nG1 X1\n", 5, 1, SEM, SWARF_GCODE_E_COMP_FEED_GOUGE},
    {"G41.1 D.5\nG0 X1\nG0 X2\nG0 Y.1\nG0 X1\n", 5, 1, SEM, SWARF_GCODE_E_COMP_TRAVERSE_GOUGE},
    /* Malformed numbers. */
    {"G1 X1.2.3 F10\n", 1, 4, SYN, SWARF_GCODE_E_BAD_NUMBER},
    {"G0 X-\n", 1, 4, SYN, SWARF_GCODE_E_BAD_NUMBER},
    {"G0 X1 G\n", 1, 7, SYN, SWARF_GCODE_E_BAD_NUMBER},
    {"G0 X.\n", 1, 4, SYN, SWARF_GCODE_E_BAD_NUMBER},
    {"G0 X1-2\n", 1, 4, SYN, SWARF_GCODE_E_BAD_NUMBER},
    {"G0 X99999999999\n", 1, 4, SYN, SWARF_GCODE_E_NUMBER_RANGE},
    /* Arcs. */
    {"G0 X0 Y0\nG2 X10 Y0 I4 J0 F100\n", 2, 1, SEM, SWARF_GCODE_E_ARC_RADIUS_MISMATCH},
    {"G0 X0\nG1 F10\nG2 X10 R4\n", 3, 1, SEM, SWARF_GCODE_E_ARC_RADIUS_TOO_SMALL},
    {"G2 R5 X0 F1\n", 1, 1, SEM, SWARF_GCODE_E_ARC_SAME_POINT},
    {"G2 X1 Y1 F10\n", 1, 1, SEM, SWARF_GCODE_E_ARC_WORDS_MISSING},
    {"G2 X1 R1 I1 F1\n", 1, 7, SEM, SWARF_GCODE_E_ARC_MIXED_FORMAT},
    {"G0 X10\nG2 X0 Y10 I-10 K1 F10\n", 2, 16, SEM, SWARF_GCODE_E_ARC_PLANE_WORD},
    {"G18 G2 X1 J1 F10\n", 1, 11, SEM, SWARF_GCODE_E_ARC_PLANE_WORD},
    {"G90.1 G2 X1 I1 F10\n", 1, 7, SEM, SWARF_GCODE_E_ARC_CENTER_MISSING},
    {"G2 X1 I1 P1.5 F1\n", 1, 10, SEM, SWARF_GCODE_E_ARC_P_NOT_INTEGER},
    {"G2 X1 I1 P0 F1\n", 1, 10, SEM, SWARF_GCODE_E_ARC_P_BELOW_ONE},
    {"G0 X1 I1\n", 1, 7, SEM, SWARF_GCODE_E_UNUSED_WORD},
    {"G2 I1\n", 1, 1, SEM, SWARF_GCODE_E_ARC_ZERO_FEED},
    /* Feed, modal groups, repeated words. */
    {"G1 X1\n", 1, 1, SEM, SWARF_GCODE_E_G1_ZERO_FEED},
    {"G0 X1\n  Y2 G1\n", 2, 6, SEM, SWARF_GCODE_E_G1_ZERO_FEED},
    {"G0 G1 X1\n", 1, 4, SEM, SWARF_GCODE_E_G_MODAL_GROUP},
    {"M3 M4\n", 1, 4, SEM, SWARF_GCODE_E_M_MODAL_GROUP},
    {"G0 X1 X2\n", 1, 7, SEM, SWARF_GCODE_E_MULTIPLE_WORDS},
    {"G80 X1\n", 1, 5, SEM, SWARF_GCODE_E_AXES_WITH_G80},
    {"X1\n", 1, 1, SEM, SWARF_GCODE_E_AXES_WITHOUT_MOTION},
    {"G0 X1 N5\n", 1, 7, SYN, SWARF_GCODE_E_LINE_NUMBER_NOT_FIRST},
    {"G4\n", 1, 1, SEM, SWARF_GCODE_E_DWELL_P_MISSING},
    {"G1 F-1 X1\n", 1, 4, SEM, SWARF_GCODE_E_NEGATIVE_WORD},
    {"T1.5\n", 1, 1, SEM, SWARF_GCODE_E_WORD_NOT_INTEGER},
    {"G91 G53 G0 X1\n", 1, 5, SEM, SWARF_GCODE_E_G53_INCREMENTAL},
    {"G53 G2 X1 I1 F1\n", 1, 1, SEM, SWARF_GCODE_E_G53_MOTION},
    /* Comments, characters, parameters, expressions, O-words, %. */
    {"G0 X1 (abc\n", 1, 7, SYN, SWARF_GCODE_E_UNCLOSED_COMMENT},
    {"G0 (a(b)) X1\n", 1, 6, SYN, SWARF_GCODE_E_NESTED_COMMENT},
    {"#1=\n", 1, 4, SYN, SWARF_GCODE_E_NUMBER_CONVERSION},
    {"G0 Z#<nope>\n", 1, 5, SEM, SWARF_GCODE_E_NAMED_UNDEFINED},
    {"G0 X[1/0]\n", 1, 7, SEM, SWARF_GCODE_E_DIVIDE_BY_ZERO},
    {"G0 X[1+2\n", 1, 9, SYN, SWARF_GCODE_E_UNCLOSED_EXPRESSION},
    {"G0 X[SQRT[-1]]\n", 1, 6, SEM, SWARF_GCODE_E_SQRT_ARGUMENT},
    {"G0 X#6000\n", 1, 6, SEM, SWARF_GCODE_E_PARAMETER_RANGE},
    {"G0 X1\no100 sub\nG0 X2\n", 2, 1, SEM, SWARF_GCODE_E_O_OPEN_AT_END},
    {"o100 endwhile\n", 1, 1, SEM, SWARF_GCODE_E_O_NOT_OPEN},
    {"o<nope> call\n", 1, 1, SEM, SWARF_GCODE_E_O_UNKNOWN_SUB},
    {"o1 while [1]\no1 endwhile\n", 1, 1, LIM, SWARF_GCODE_E_O_WORK_LIMIT},
    {"G81 X1 Y1 Z-1 F10\n", 1, 1, SEM, SWARF_GCODE_E_CYCLE_R_MISSING},
    {"G0 Z0\nG81 X1 Z1 R0 F10\n", 2, 1, SEM, SWARF_GCODE_E_CYCLE_R_BELOW_DEPTH},
    {"G43 H7\n", 1, 1, SEM, SWARF_GCODE_E_TOOL_NOT_FOUND},
    {"G0 X1 O100\n", 1, 7, SYN, SWARF_GCODE_E_O_WORD_NOT_FIRST},
    {"G0 X1 $\n", 1, 7, SYN, SWARF_GCODE_E_BAD_CHARACTER},
    {"G0 X1\x01\n", 1, 6, SYN, SWARF_GCODE_E_BAD_CHARACTER},
    {"G0 X1\n%\n", 2, 1, SYN, SWARF_GCODE_E_PERCENT_NOT_OPEN},
    {"%\nG0 X1\n% text\n", 3, 1, SYN, SWARF_GCODE_E_BAD_CHARACTER},
};

static void check_case(const bad_case *k) {
  static collected c;
  run_text(k->program, &c);
  CHECK(c.error.code == k->code, "\"%s\": %s, expected %s (%s)", k->program,
        swarf_gcode_error_name(c.error.code), swarf_gcode_error_name(k->code), c.error.message);
  CHECK(c.status == (int)k->status && c.error.status == k->status, "\"%s\": status %s, expected %s",
        k->program, swarf_status_name(c.status), swarf_status_name(k->status));
  CHECK(c.error.line == k->line && c.error.column == k->column,
        "\"%s\": at %ld:%d, expected %ld:%d (%s)", k->program, c.error.line, c.error.column,
        k->line, k->column, c.error.message);
  CHECK(c.error.message[0] != '\0', "\"%s\": no message", k->program);
  CHECK(strcmp(c.error.file, "test.ngc") == 0, "file name in the error: %s", c.error.file);
}

/* Every identity has a distinct name, a status of the table and a message;
 * the parser's errors use them. */
static void test_identities(void) {
  CHECK(swarf_gcode_error_name(0) != NULL && swarf_gcode_error_name(-1) == NULL &&
            swarf_gcode_error_name(SWARF_GCODE_E_END_) == NULL,
        "names out of range");
  CHECK(strcmp(swarf_gcode_error_name(SWARF_GCODE_E_NESTED_COMMENT),
               "SWARF_GCODE_E_NESTED_COMMENT") == 0,
        "name: %s", swarf_gcode_error_name(SWARF_GCODE_E_NESTED_COMMENT));
  for (int i = 1; i < SWARF_GCODE_E_END_; i++) {
    const char *name = swarf_gcode_error_name(i), *format = swarf_gcode_error_format(i);
    swarf_status s = swarf_gcode_error_status(i);
    CHECK(name != NULL && strncmp(name, "SWARF_GCODE_E_", 14) == 0, "identity %d: name", i);
    CHECK(format != NULL && format[0] != '\0', "%s: no message", name);
    CHECK(s != SWARF_OK && strcmp(swarf_status_name(s), "SWARF_UNKNOWN") != 0, "%s: status %d",
          name, s);
    for (int j = 1; j < i; j++)
      CHECK(strcmp(name, swarf_gcode_error_name(j)) != 0 &&
                strcmp(format, swarf_gcode_error_format(j)) != 0,
            "%s and %s are not distinct", name, swarf_gcode_error_name(j));
  }
  CHECK(swarf_gcode_error_status(SWARF_GCODE_E_OUT_OF_MEMORY) == SWARF_ERR_MEMORY &&
            swarf_gcode_error_status(SWARF_GCODE_E_STOPPED) == SWARF_ERR_ABORTED &&
            swarf_gcode_error_status(SWARF_GCODE_E_BAD_NUMBER) == SWARF_ERR_SYNTAX,
        "statuses of the table");
}

/* The word of the error: the offending word as written. */
static void test_words(void) {
  static const struct {
    const char *program, *word;
  } cases[] = {{"G0 X1 U2\n", "U2"},
               {"G0 G1 X1\n", "G1"},
               {"G1 X1.2.3 F10\n", "X1.2.3"},
               {"G0 X1 (abc\n", "(abc"},
               {"G0 Z#<nope>\n", "#<nope>"},
               {"G0 X[SQRT[-1]]\n", "SQRT[-1]"},
               {"G0 X1 $\n", "$"},
               {"G0 X1\x01\n", ""},
               {"#1=\n", ""},
               {"o<nope> call\n", "o<nope>"},
               {"G0 X1\n%\n", "%"}};
  static collected c;
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    run_text(cases[i].program, &c);
    CHECK(c.status != 0 && strcmp(c.error.word, cases[i].word) == 0,
          "\"%s\": word \"%s\", expected \"%s\"", cases[i].program, c.error.word, cases[i].word);
  }
}

/* A NUL byte is a bad character like any other (the line goes on after it). */
static void test_nul_byte(void) {
  static collected c;
  static const char text[] = "G0 X1\nG0\0X2\n";
  run_pieces(text, sizeof text - 1, 4, &c);
  CHECK(c.status == SYN && c.error.code == SWARF_GCODE_E_BAD_CHARACTER && c.error.line == 2 &&
            c.error.column == 3 && c.n == 1,
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
  swarf_gcode_parser *p = NULL;
  swarf_gcode_parser_new("stop.ngc", stop_at_second, &count, &p);
  status = swarf_gcode_parser_feed(p, "G0 X1\nG0 X2\nG0 X3\n", 18);
  CHECK(status == SWARF_ERR_ABORTED && count == 2, "stopped: %d after %d", status, count);
  CHECK(swarf_gcode_parser_error(p) && swarf_gcode_parser_error(p)->line == 2, "stop line");
  status = swarf_gcode_parser_feed(p, "G0 X4\n", 6);
  CHECK(status == SWARF_ERR_ABORTED && count == 2, "a stopped parser stays stopped");
  CHECK(swarf_gcode_parser_finish(p) == SWARF_ERR_ABORTED, "finish after stop");
  swarf_gcode_parser_free(p);

  swarf_gcode_parser_new("sticky.ngc", collect_move, &c, &p);
  memset(&c, 0, sizeof c);
  status = swarf_gcode_parser_feed(p, "G0 X1\nG0 X1 X2\n", 15);
  CHECK(status == SEM && c.n == 1, "first error");
  status = swarf_gcode_parser_feed(p, "G0 X4\n", 6);
  CHECK(status == SEM && c.n == 1, "input after an error is refused");
  CHECK(swarf_gcode_parser_error(p)->line == 2, "the first error stays");
  swarf_gcode_parser_free(p);
  CHECK(swarf_gcode_parser_feed(NULL, "x", 1) == SWARF_ERR_ARG, "NULL parser");
}

static void test_files(void) {
  swarf_error err;
  int status = swarf_gcode_parse_file("/nonexistent/dir/prog.ngc", NULL, NULL, &err);
  CHECK(status == SWARF_ERR_OPEN && err.status == SWARF_ERR_OPEN && err.line == 0,
        "missing file: %d", status);
  CHECK(err.code == SWARF_GCODE_E_FILE_OPEN && strstr(err.file, "prog.ngc") != NULL,
        "missing file: %s (%s)", swarf_gcode_error_name(err.code), err.file);
}

static void test_long_line(void) {
  static collected c;
  size_t len = (1 << 20) + 10;
  char *text = malloc(len);
  memset(text, ' ', len);
  memcpy(text, "G0 X1\n", 6);
  run_pieces(text, len, 4096, &c);
  CHECK(c.status == LIM && c.error.line == 2 && c.error.code == SWARF_GCODE_E_LINE_TOO_LONG,
        "a line over 1 MiB: status %d at line %ld", c.status, c.error.line);
  run_text("", &c);
  CHECK(c.status == 0 && c.n == 0, "empty program");
  free(text);
}

/* The program under a work limit of `limit` lines (0: the default). */
static collected *run_limited(const char *text, int dialect, long limit, collected *c) {
  swarf_gcode_parser *p = NULL;
  int status;
  swarf_gcode_parser_new("test.ngc", collect_move, c, &p);
  swarf_gcode_parser_set_fragment(p, 1, NULL); /* test texts need not end */
  memset(c, 0, sizeof *c);
  status = swarf_gcode_parser_set_dialect(p, (swarf_gcode_dialect)dialect, NULL);
  if (status == SWARF_OK && limit > 0) status = swarf_gcode_parser_set_work_limit(p, limit, NULL);
  if (status == SWARF_OK) status = swarf_gcode_parser_feed(p, text, strlen(text));
  collect_end(c, p, status);
  return c;
}

/* A lowered work limit: a loop of 300 turns (3 lines run a turn, ~900 in
 * all) passes under 1,000 and the default, stops under 500 at the loop's
 * line with the limit in the message; the same for a Fanuc WHILE (2 lines a
 * turn beyond the program's own). Out-of-range limits and a late call are
 * refused. */
static void test_work_limit(void) {
  static collected c;
  char want[64];
  const char *lcnc = "#1 = 0\no1 while [#1 LT 300]\n#1 = [#1 + 1]\no1 endwhile\nG0 X#1\n";
  const char *fanuc = "#1 = 0\nWHILE [#1 LT 300] DO1\n#1 = [#1 + 1]\nEND1\nG0 X#1\nM30\n";
  for (int k = 0; k < 2; k++) {
    const char *text = k ? fanuc : lcnc;
    int d = k ? SWARF_GCODE_DIALECT_FANUC : SWARF_GCODE_DIALECT_LINUXCNC;
    run_limited(text, d, 0, &c);
    CHECK(c.status == SWARF_OK && c.n == 1 && c.moves[0].end[0] == 300, "%d: default limit: %s", k,
          c.error.message);
    run_limited(text, d, 1000, &c);
    CHECK(c.status == SWARF_OK && c.n == 1, "%d: 300 turns under 1,000 lines: %s", k,
          c.error.message);
    run_limited(text, d, 500, &c);
    snprintf(want, sizeof want, "%d", 500);
    CHECK(c.status == LIM && c.error.code == SWARF_GCODE_E_O_WORK_LIMIT && c.n == 0,
          "%d: 300 turns over 500 lines: status %d (%s)", k, c.status, c.error.message);
    CHECK(k == 1 || strstr(c.error.message, want) != NULL, "the limit in the message: %s",
          c.error.message);
    CHECK(c.error.line >= 2 && c.error.line <= 4, "%d: stopped at line %ld", k, c.error.line);
  }
  swarf_gcode_parser *p = NULL;
  swarf_error err;
  swarf_gcode_parser_new("limit.ngc", collect_move, &c, &p);
  CHECK(swarf_gcode_parser_set_work_limit(p, 0, &err) == SWARF_ERR_ARG &&
            err.code == SWARF_GCODE_E_WORK_LIMIT_VALUE,
        "a limit of 0");
  CHECK(swarf_gcode_parser_set_work_limit(p, SWARF_GCODE_WORK_LIMIT_MAX + 1, &err) == SWARF_ERR_ARG,
        "a limit above the most");
  CHECK(swarf_gcode_parser_set_work_limit(NULL, 10, &err) != SWARF_OK, "no parser");
  swarf_gcode_parser_feed(p, "G0 X1\n", 6);
  CHECK(swarf_gcode_parser_set_work_limit(p, 10, &err) != SWARF_OK, "a limit after the first line");
  swarf_gcode_parser_free(p);
}

/* A whole program in `dialect` (not a fragment): LinuxCNC's must end with
 * M2, M30 or a closing `%`, as rs274 reads it ("File ended with no percent
 * sign or program end", at the last line, after its moves); the others need
 * no end. */
static void test_program_end(void) {
  static const struct {
    const char *text;
    int dialect, code;
    long line, moves;
  } k[] = {
      {"G0 X1\nG0 X2\n", SWARF_GCODE_DIALECT_LINUXCNC, SWARF_GCODE_E_NO_PROGRAM_END, 2, 2},
      {"G0 X1\nG0 X2", SWARF_GCODE_DIALECT_LINUXCNC, SWARF_GCODE_E_NO_PROGRAM_END, 2, 2},
      {"", SWARF_GCODE_DIALECT_LINUXCNC, SWARF_GCODE_E_NO_PROGRAM_END, 1, 0},
      {"%\nG0 X1\n", SWARF_GCODE_DIALECT_LINUXCNC, SWARF_GCODE_E_NO_CLOSING_PERCENT, 2, 1},
      {"%\nG0 X1\nM2\n", SWARF_GCODE_DIALECT_LINUXCNC, 0, 0, 1},
      {"%\nG0 X1\n%\n", SWARF_GCODE_DIALECT_LINUXCNC, 0, 0, 1},
      {"G0 X1\nM30", SWARF_GCODE_DIALECT_LINUXCNC, 0, 0, 1},
      {"G0 X1\nM2\nG0 X5\n", SWARF_GCODE_DIALECT_LINUXCNC, 0, 0, 1},
      {"G0 X1\n", SWARF_GCODE_DIALECT_FANUC, 0, 0, 1},
      {"G0 X1\n", SWARF_GCODE_DIALECT_HAAS, 0, 0, 1},
      {"G0 X1\n", SWARF_GCODE_DIALECT_GRBL, 0, 0, 1},
  };
  static collected c;
  for (size_t i = 0; i < sizeof k / sizeof k[0]; i++) {
    swarf_gcode_parser *p = NULL;
    swarf_gcode_parser_new("end.ngc", collect_move, &c, &p);
    memset(&c, 0, sizeof c);
    swarf_gcode_parser_set_dialect(p, (swarf_gcode_dialect)k[i].dialect, NULL);
    collect_end(&c, p, swarf_gcode_parser_feed(p, k[i].text, strlen(k[i].text)));
    if (k[i].code == 0)
      CHECK(c.status == SWARF_OK && c.n == k[i].moves, "%zu: accepted with %ld moves: %d %s (%d)",
            i, k[i].moves, c.status, c.error.message, c.n);
    else
      CHECK(c.status == SEM && c.error.code == k[i].code && c.error.line == k[i].line &&
                c.error.column == 1 && c.n == k[i].moves,
            "%zu: no end: status %d code %d at %ld:%d after %d moves (%s)", i, c.status,
            c.error.code, c.error.line, c.error.column, c.n, c.error.message);
  }
  swarf_gcode_parser *p = NULL;
  swarf_gcode_parser_new("end.ngc", collect_move, &c, &p);
  memset(&c, 0, sizeof c);
  CHECK(swarf_gcode_parser_set_fragment(p, 1, NULL) == SWARF_OK, "a fragment");
  collect_end(&c, p, swarf_gcode_parser_feed(p, "G0 X1\n", 6));
  CHECK(c.status == SWARF_OK && c.n == 1, "a fragment needs no end: %s", c.error.message);
  CHECK(swarf_gcode_parser_set_fragment(NULL, 1, NULL) == SWARF_ERR_ARG, "no parser");
}

int main(void) {
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    check_case(&cases[i]);
  test_identities();
  test_words();
  test_nul_byte();
  test_rejected_block_emits_nothing();
  test_stop_and_sticky_errors();
  test_files();
  test_long_line();
  test_work_limit();
  test_program_end();
  return check_done();
}
