/* SPDX-License-Identifier: MPL-2.0 */
/* test_lcnc.c -- the corners of the LinuxCNC dialect against rs274, on
 * programs of our own (tests/gcode/lcnc/: <case>.ngc, and <case>.expected
 * made from it by rs274 with make_expected.sh, tools.tbl, lcnc.ini):
 * program number lines, tool length offsets in G28/G30/G53/G43.1, block
 * delete (switch off, and on for *-bdel*), G38.x probing, M19, G87 back
 * boring, G5/G5.1 splines, subroutine files on a search path, the G99
 * start-up retract mode, and their errors.
 *
 * For each case: swarf's motion calls (STRAIGHT_TRAVERSE, STRAIGHT_FEED,
 * ARC_FEED, DWELL, STRAIGHT_PROBE, NURBS_FEED) equal rs274's to 1e-4 in
 * order, and so do the numbers of its MESSAGE calls (positions and probe
 * results read from parameters), except where the probe cases differ on
 * purpose (below); the program stops where rs274 stops, with rs274's
 * message; and the simulator's moves make one continuous path.
 *
 * What swarf chose where rs274 is not the machine: after a G38.x move that
 * did not trip, rs274's stand-alone canon puts the tool 0.254 mm back from
 * the target; swarf leaves it at the target (where LinuxCNC's motion stops
 * an untripped probe move), so probe.ngc gives every axis after each probe.
 *
 * And the splines' lines against the curve LinuxCNC's manual defines (G5:
 * the cubic Bezier with control points P0, P0 + (I, J), P3 + (P, Q), P3;
 * G5.1: the quadratic one with P0 + (I, J)): every line ends on the curve
 * and no chord strays from it by more than the stated 0.001 mm.
 *
 * Usage: test_lcnc <folder of the cases>.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "canon_compare.h"
#include "check.h"

#define MAX_MOVES 8192

typedef struct {
  swarf_move v[MAX_MOVES];
  int n;
} moves;

static const char *cases[] = {"program-number",
                              "m61",
                              "tool-length",
                              "block-delete",
                              "block-delete-bdel",
                              "probe",
                              "m19",
                              "g87",
                              "g87-no-spindle",
                              "g87-no-k",
                              "spline",
                              "spline-plane",
                              "spline-pq",
                              "spline-ij",
                              "probe-close",
                              "probe-comp",
                              "subfile",
                              "retract-default",
                              "m98",
                              "m98-percent"};

static int keep_move(const swarf_move *mv, void *user) {
  moves *m = user;
  if (mv->kind <= SWARF_MOVE_ARC && m->n < MAX_MOVES) m->v[m->n++] = *mv;
  return 0;
}

static int run(const char *dir, const char *name, canon_text *out, moves *m, swarf_error *err) {
  char path[1024], tools[1024], subs[2100];
  size_t len;
  char *text;
  swarf_gcode_parser *p = NULL;
  int status;
  snprintf(path, sizeof path, "%s/%s.ngc", dir, name);
  snprintf(tools, sizeof tools, "%s/tools.tbl", dir);
  snprintf(subs, sizeof subs, "%s/nowhere:%s/subs", dir, dir);
  text = canon_slurp(path, &len);
  memset(out, 0, sizeof *out);
  memset(err, 0, sizeof *err);
  swarf_gcode_parser_new(path, keep_move, m, &p);
  swarf_gcode_parser_set_canon(p, canon_collect, out);
  status = text == NULL ? SWARF_ERR_ARG : swarf_gcode_parser_load_tools(p, tools, err);
  if (status == SWARF_OK) status = swarf_gcode_parser_set_subroutine_path(p, subs, err);
  if (status == SWARF_OK && strstr(name, "-bdel") != NULL)
    status = swarf_gcode_parser_set_block_delete(p, 1, err);
  if (status == SWARF_OK) status = swarf_gcode_parser_feed(p, text, len);
  if (status == SWARF_OK) status = swarf_gcode_parser_finish(p);
  if (swarf_gcode_parser_error(p) != NULL) *err = *swarf_gcode_parser_error(p);
  swarf_gcode_parser_free(p);
  free(text);
  if (out->text == NULL) canon_collect("", out);
  return status;
}

/* rs274's error message in its output (a line that is not a call), or NULL. */
static const char *rs274_error(const char *expected) {
  for (const char *s = expected; s != NULL && *s; s = strchr(s, '\n'), s = s ? s + 1 : NULL)
    if (*s != ' ' && *s != '\n' && strncmp(s, "executing", 9) != 0) return s;
  return NULL;
}

static void check_continuous(const char *name, const moves *m) {
  for (int i = 1; i < m->n; i++)
    for (int a = 0; a < SWARF_NAXES; a++)
      CHECK(fabs(m->v[i].start[a] - m->v[i - 1].end[a]) <= 1e-9,
            "%s: move %d starts where %d ended", name, i, i - 1);
}

static void run_case(const char *dir, const char *name) {
  char exp_path[1024], why[200] = "";
  canon_text out;
  canon_calls got, want;
  swarf_error err;
  static moves m;
  size_t elen;
  char *expected;
  int status;
  snprintf(exp_path, sizeof exp_path, "%s/%s.expected", dir, name);
  expected = canon_slurp(exp_path, &elen);
  CHECK(expected != NULL, "cannot read %s", exp_path);
  if (expected == NULL) return;
  m.n = 0;
  status = run(dir, name, &out, &m, &err);
  canon_extract(out.text, 0, &got);
  canon_extract(expected, 0, &want);
  /* On an error rs274 may have printed part of the failing block (G87
   * checks the spindle after its first rapids); swarf refuses a block
   * whole: its calls are then the ones before that block. */
  if (rs274_error(expected) != NULL && got.n < want.n) want.n = got.n;
  CHECK(!canon_differ(&got, &want, 1.01e-4, why, sizeof why), "%s: %s", name, why);
  free(got.v);
  free(want.v);
  canon_extract(out.text, 1, &got);
  canon_extract(expected, 1, &want);
  CHECK(!canon_differ(&got, &want, 1.01e-6, why, sizeof why), "%s: MESSAGE numbers: %s", name, why);
  free(got.v);
  free(want.v);
  CHECK((status == SWARF_OK) == (rs274_error(expected) == NULL), "%s: %s", name,
        status ? err.message : "rs274 stopped, swarf did not");
  if (status != SWARF_OK && rs274_error(expected) != NULL)
    CHECK(strncmp(err.message, rs274_error(expected), strcspn(rs274_error(expected), "\n")) == 0,
          "%s: message \"%s\", rs274's \"%.*s\"", name, err.message,
          (int)strcspn(rs274_error(expected), "\n"), rs274_error(expected));
  check_continuous(name, &m);
  printf("%-20s %d moves, %s\n", name, m.n, status == SWARF_OK ? "ok" : err.message);
  free(out.text);
  free(expected);
}

/* ---- splines against their definition ----------------------------------- */

typedef struct {
  double px[4], py[4];
  int n; /* degree */
} bez;

static void bez_at(const bez *b, double t, double *x, double *y) {
  double u = 1 - t;
  double w3[4] = {u * u * u, 3 * u * u * t, 3 * u * t * t, t * t * t},
         w2[3] = {u * u, 2 * u * t, t * t};
  *x = *y = 0;
  for (int i = 0; i <= b->n; i++) {
    double w = b->n == 3 ? w3[i] : w2[i];
    *x += w * b->px[i];
    *y += w * b->py[i];
  }
}

/* Distance from (x, y) to the curve: dense samples, then golden-section. */
static double bez_dist(const bez *b, double x, double y) {
  double best = 1e300, bt = 0;
  for (int i = 0; i <= 4000; i++) {
    double cx, cy, t = i / 4000.0, d;
    bez_at(b, t, &cx, &cy);
    d = hypot(cx - x, cy - y);
    if (d < best) best = d, bt = t;
  }
  double lo = fmax(0, bt - 1 / 4000.0), hi = fmin(1, bt + 1 / 4000.0);
  for (int k = 0; k < 80; k++) {
    double t1 = hi - (hi - lo) * 0.618, t2 = lo + (hi - lo) * 0.618, x1, y1, x2, y2;
    bez_at(b, t1, &x1, &y1);
    bez_at(b, t2, &x2, &y2);
    if (hypot(x1 - x, y1 - y) < hypot(x2 - x, y2 - y))
      hi = t2;
    else
      lo = t1;
  }
  {
    double cx, cy;
    bez_at(b, (lo + hi) / 2, &cx, &cy);
    return fmin(best, hypot(cx - x, cy - y));
  }
}

/* The lines of source line `line` of spline.ngc follow the curve `b`. */
static void check_curve(const moves *m, long line, const bez *b) {
  int k = 0;
  double worst_end = 0, worst_mid = 0;
  for (int i = 0; i < m->n; i++) {
    const swarf_move *mv = &m->v[i];
    if (mv->line != line) continue;
    k++;
    worst_end = fmax(worst_end, bez_dist(b, mv->end[0], mv->end[1]));
    for (int q = 1; q < 4; q++) {
      double x = mv->start[0] + q / 4.0 * (mv->end[0] - mv->start[0]);
      double y = mv->start[1] + q / 4.0 * (mv->end[1] - mv->start[1]);
      worst_mid = fmax(worst_mid, bez_dist(b, x, y));
    }
    CHECK(mv->kind == SWARF_MOVE_LINE && mv->feed == 300, "line %ld: straight feeds at F300", line);
  }
  CHECK(k >= 2, "line %ld: the spline is several lines (%d)", line, k);
  CHECK(worst_end < 1e-6, "line %ld: line ends on the curve (worst %g mm)", line, worst_end);
  CHECK(worst_mid <= 0.001 + 1e-6, "line %ld: chords within 0.001 mm (worst %g mm)", line,
        worst_mid);
  printf("spline line %ld: %d lines, ends within %.1e, chords within %.2e mm\n", line, k, worst_end,
         worst_mid);
}

static void test_spline_geometry(const char *dir) {
  canon_text out;
  swarf_error err;
  static moves m;
  /* From spline.ngc: line 4 from (0,0): G5 I1 J2 P-1 Q2 X5 Y5; line 7 from
   * (0,0): G5 I1 J0 P1 Q0 X2 Y0; line 8 continues it: G5 P1 Q-2 X10 Y0 (I J
   * = -(1, 0)); line 10 from (10,3): G5.1 I2 J3 X12 Y1; line 12 from (12,1):
   * G5 X14 Y2 P1 Q1 after a G1 (I J = 0). */
  const bez curves[] = {{{0, 1, 4, 5}, {0, 2, 7, 5}, 3},
                        {{0, 1, 3, 2}, {0, 0, 0, 0}, 3},
                        {{2, 1, 11, 10}, {0, 0, -2, 0}, 3},
                        {{10, 12, 12}, {3, 6, 1}, 2},
                        {{12, 12, 15, 14}, {1, 1, 3, 2}, 3}};
  const long lines[] = {4, 7, 8, 10, 12};
  m.n = 0;
  CHECK(run(dir, "spline", &out, &m, &err) == SWARF_OK, "spline.ngc: %s", err.message);
  for (int i = 0; i < 5; i++)
    check_curve(&m, lines[i], &curves[i]);
  free(out.text);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: test_lcnc <folder of the cases>\n");
    return 2;
  }
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    run_case(argv[1], cases[i]);
  test_spline_geometry(argv[1]);
  return check_done();
}
