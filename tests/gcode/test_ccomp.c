/* SPDX-License-Identifier: MPL-2.0 */
/* test_ccomp.c -- cutter radius compensation against LinuxCNC, on programs
 * of our own (tests/gcode/ccomp/: <case>.ngc, <case>.expected made from it
 * by rs274 with make_expected.sh and tools.tbl; random-sessions.ngc comes from
 * random_compare.py, which compares thousands of such programs).
 *
 * For each case: swarf's canonical motion calls equal rs274's to 1e-4, in
 * order, and so do the numbers of its MESSAGE calls (positions read from
 * parameters); and the moves the simulator gets follow that path: one move per
 * motion call, each starting where the last one ended, ending where the
 * call says (machine frame = program frame here: no offsets), and arcs
 * whose sweep and rise land on their end point.
 *
 * And a long run of held moves takes linear time.
 *
 * Usage: test_ccomp <folder of the cases>.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "canon_compare.h"
#include "check.h"
#include "collect.h"

#define MAX_MOVES 4096

typedef struct {
  const char *name;
  double scale; /* mm per unit of the canon, 0: mixed units (ends not compared) */
  int g18;      /* arcs in the XZ plane */
} ccomp_case;

static const ccomp_case cases[] = {
    {"square-left", 1, 0}, {"pocket-right", 1, 0},    {"arcs-mixed", 25.4, 0},
    {"plane-g18", 1, 1},   {"misc-right", 0, 0},      {"hshape", 1, 0},
    {"gouges", 1, 0},      {"random-sessions", 0, 0}, {"position-params", 1, 0},
};

typedef struct {
  swarf_move v[MAX_MOVES];
  int n;
} moves;

static int keep_move(const swarf_move *mv, void *user) {
  moves *m = user;
  if (mv->kind <= SWARF_MOVE_ARC && m->n < MAX_MOVES) m->v[m->n++] = *mv;
  return 0;
}

static void canon_sink(const char *call, void *user) {
  canon_collect(call, user);
}

/* Program and moves at once; `tools` is the case folder's tools.tbl. */
static int run(const char *path, const char *tools, canon_text *out, moves *m, swarf_error *err) {
  size_t len;
  char *text = canon_slurp(path, &len);
  swarf_gcode_parser *p = NULL;
  swarf_gcode_parser_new(path, keep_move, m, &p);
  int status = text == NULL ? SWARF_ERR_ARG : SWARF_OK;
  memset(out, 0, sizeof *out);
  memset(err, 0, sizeof *err);
  swarf_gcode_parser_set_canon(p, canon_sink, out);
  if (status == SWARF_OK) status = swarf_gcode_parser_load_tools(p, tools, err);
  if (status == SWARF_OK) status = swarf_gcode_parser_feed(p, text, len);
  if (status == SWARF_OK) status = swarf_gcode_parser_finish(p);
  if (swarf_gcode_parser_error(p) != NULL) *err = *swarf_gcode_parser_error(p);
  swarf_gcode_parser_free(p);
  free(text);
  if (out->text == NULL) canon_collect("", out);
  return status;
}

/* The end (x, y, z) a motion call names, in mm. */
static void call_end(const canon_call1 *c, const ccomp_case *k, double e[3]) {
  if (c->kind == 2 && k->g18)
    e[2] = c->v[0], e[0] = c->v[1], e[1] = c->v[5];
  else if (c->kind == 2)
    e[0] = c->v[0], e[1] = c->v[1], e[2] = c->v[5];
  else
    e[0] = c->v[0], e[1] = c->v[1], e[2] = c->v[2];
  for (int i = 0; i < 3; i++)
    e[i] *= k->scale;
}

static void check_path(const ccomp_case *k, const canon_calls *want, const moves *m) {
  size_t n = 0;
  for (size_t i = 0; i < want->n; i++)
    n += want->v[i].kind <= 2;
  CHECK(n == (size_t)m->n, "%s: %d moves for %zu motion calls", k->name, m->n, n);
  for (int i = 0; i < m->n; i++) {
    const swarf_move *mv = &m->v[i];
    double e[3];
    for (int a = 0; i > 0 && a < SWARF_NAXES; a++)
      CHECK_NEAR(mv->start[a], m->v[i - 1].end[a], 1e-9, "move starts where the last one ended");
    if (mv->kind == SWARF_MOVE_ARC) {
      arc_point(mv, 1.0, e);
      for (int a = 0; a < 3; a++)
        CHECK_NEAR(e[a], mv->end[a], 1e-3 * (k->scale > 0 ? k->scale : 25.4),
                   "arc lands on its end");
    }
    if (k->scale == 0 || (size_t)m->n != n) continue;
    call_end(&want->v[i], k, e);
    for (int a = 0; a < 3; a++)
      CHECK_NEAR(mv->end[a], e[a], 1.01e-4 * k->scale, "move ends where rs274's call does");
  }
}

/* rs274's error message in its output (a line that is not a call), or NULL. */
static const char *rs274_error(const char *expected) {
  for (const char *s = expected; s != NULL && *s; s = strchr(s, '\n'), s = s ? s + 1 : NULL)
    if (*s != ' ' && *s != '\n' && strncmp(s, "executing", 9) != 0) return s;
  return NULL;
}

static void run_case(const char *dir, const ccomp_case *k) {
  char path[1024], exp_path[1024], tools[1024], why[200] = "";
  canon_text out;
  canon_calls got, want;
  swarf_error err;
  static moves m;
  size_t elen;
  char *expected;
  int status;
  snprintf(path, sizeof path, "%s/%s.ngc", dir, k->name);
  snprintf(exp_path, sizeof exp_path, "%s/%s.expected", dir, k->name);
  snprintf(tools, sizeof tools, "%s/tools.tbl", dir);
  expected = canon_slurp(exp_path, &elen);
  CHECK(expected != NULL, "cannot read %s", exp_path);
  if (expected == NULL) return;
  m.n = 0;
  status = run(path, tools, &out, &m, &err);
  canon_extract(out.text, 0, &got);
  canon_extract(expected, 0, &want);
  CHECK(!canon_differ(&got, &want, 1.01e-4, why, sizeof why), "%s: %s", k->name, why);
  free(got.v);
  free(want.v);
  canon_extract(out.text, 1, &got);
  canon_extract(expected, 1, &want);
  CHECK(!canon_differ(&got, &want, 1.01e-6, why, sizeof why), "%s: MESSAGE numbers: %s", k->name,
        why);
  free(got.v);
  free(want.v);
  canon_extract(expected, 0, &want);
  CHECK((status == SWARF_OK) == (rs274_error(expected) == NULL), "%s: %s", k->name,
        status ? err.message : "rs274 stopped, swarf did not");
  if (status != SWARF_OK && rs274_error(expected) != NULL)
    CHECK(strncmp(err.message, rs274_error(expected), strcspn(rs274_error(expected), "\n")) == 0,
          "%s: swarf says \"%s\", rs274 \"%.*s\"", k->name, err.message,
          (int)strcspn(rs274_error(expected), "\n"), rs274_error(expected));
  check_path(k, &want, &m);
  printf("%-14s %zu motion calls, %d moves%s%s\n", k->name, want.n, m.n,
         status ? ", refused: " : "", status ? err.message : "");
  free(want.v);
  free(out.text);
  free(expected);
}

/* 100000 moves off the plane after a compensated move are all held (as
 * LinuxCNC holds them) until the next move in the plane: linear time. */
static void long_hold(void) {
  size_t cap = 100000 * 12 + 100, n = 0;
  char *text = malloc(cap);
  canon_text out = {0};
  moves *m = malloc(sizeof *m);
  swarf_gcode_parser *p = NULL;
  swarf_gcode_parser_new("hold.ngc", keep_move, m, &p);
  clock_t t0 = clock();
  int status;
  m->n = 0;
  n += (size_t)snprintf(text, cap, "F100\nG41.1 D1\nG1 X10\n");
  for (int i = 0; i < 100000; i++)
    n += (size_t)snprintf(text + n, cap - n, "G1 Z-%d\n", i % 5);
  n += (size_t)snprintf(text + n, cap - n, "G1 Y10\nM2\n");
  swarf_gcode_parser_set_canon(p, canon_sink, &out);
  status = swarf_gcode_parser_feed(p, text, n);
  if (status == SWARF_OK) status = swarf_gcode_parser_finish(p);
  CHECK(status == SWARF_OK && m->n == MAX_MOVES, "long hold: status %d, %d moves", status, m->n);
  CHECK((double)(clock() - t0) / CLOCKS_PER_SEC < 10, "long hold took %.1f s of CPU",
        (double)(clock() - t0) / CLOCKS_PER_SEC);
  swarf_gcode_parser_free(p);
  free(out.text);
  free(text);
  free(m);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s <tests/gcode/ccomp>\n", argv[0]);
    return 2;
  }
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    run_case(argv[1], &cases[i]);
  long_hold();
  return check_done();
}
