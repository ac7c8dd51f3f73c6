/* SPDX-License-Identifier: MPL-2.0 */
/* test_sim_api.c -- the simulation handle's contract (swarf_sim.h).
 *
 * Streaming: a program fed in random splits gives the grid of one feed, bit
 * for bit; motions added directly give the grid of the G-code that makes
 * them; a run continued on the stock of an earlier run (new_with_stock)
 * gives the grid of one run of both programs. Callbacks: the alarms heard
 * are the rapid moves that cut (lines known from the geometry, as in
 * alarms.sh), the per-line results sum to the report, a progress callback
 * that says stop aborts. Errors: their status, identity and place; calls
 * out of order are refused.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "swarf_sim.h"

#define VOXEL 0.25

/* Same program as tests/tools/alarms.sh: rapids on lines 5, 8 and 9 cut. */
static const char program[] =
    "G0 Z5\nG0 X5 Y10\nG1 Z-2 F100\nG1 X30 Y10\nG0 X35\nG0 Z5\n"
    "G0 X5 Y20\nG0 Z-1\nG0 X20\nG0 Z5\nG0 X10 Y10\nG0 Z-2\nG0 X25\nG0 Z5\n";

static void base_config(swarf_sim_config *cfg) {
  swarf_error err;
  swarf_sim_tool t;
  swarf_sim_config_init(cfg);
  cfg->fragment = 1; /* the test texts need not end (one case checks the rule) */
  cfg->voxel = VOXEL;
  CHECK(swarf_sim_parse_stock("box:0,0,-10,40,30,0", &cfg->stock, &err) == SWARF_OK, "%s",
        err.message);
  CHECK(swarf_sim_parse_tool("T1=ball,D3,L12", &t, &err) == SWARF_OK, "%s", err.message);
  CHECK(swarf_sim_config_add_tool(cfg, &t, &err) == SWARF_OK, "%s", err.message);
  CHECK(swarf_sim_config_add_tool(cfg, &t, &err) == SWARF_ERR_ARG, "a tool number given twice");
}

typedef struct {
  const swarf_stock *other;
  long n, differ;
} cmp_ctx;

static void cmp_visit(void *ctx, const double c[3], float value) {
  cmp_ctx *k = ctx;
  k->n++;
  if ((float)swarf_stock_voxel_value(k->other, c[0], c[1], c[2], NULL) != value) k->differ++;
}

/* Both ways: every active voxel of one has the same value in the other. */
static void check_same(const swarf_stock *a, const swarf_stock *b, const char *what) {
  cmp_ctx ab = {b, 0, 0}, ba = {a, 0, 0};
  CHECK(a != NULL && b != NULL, "%s: both grids exist", what);
  if (a == NULL || b == NULL) return;
  swarf_stock_visit_active(a, cmp_visit, &ab);
  swarf_stock_visit_active(b, cmp_visit, &ba);
  CHECK(ab.n > 1000 && ab.n == ba.n, "%s: %ld vs %ld active voxels", what, ab.n, ba.n);
  CHECK(ab.differ == 0 && ba.differ == 0, "%s: %ld + %ld voxels differ", what, ab.differ,
        ba.differ);
}

typedef struct {
  long alarm_line[8];
  int nalarms;
  long line_moves, last_line, order_broken, progress_calls, stop_after;
  double line_time;
} heard;

static void on_alarm(void *user, const swarf_alarm *a) {
  heard *h = user;
  if (h->nalarms < 8 && a->kind == SWARF_ALARM_RAPID) h->alarm_line[h->nalarms] = a->line;
  h->nalarms++;
}

static void on_line(void *user, const swarf_line_result *r) {
  heard *h = user;
  if (r->line <= h->last_line) h->order_broken++;
  h->last_line = r->line;
  h->line_moves += r->moves;
  h->line_time += r->time_s;
}

static int on_progress(void *user, const swarf_sim_progress *p) {
  heard *h = user;
  h->progress_calls++;
  return h->stop_after > 0 && p->report->moves >= h->stop_after;
}

typedef struct {
  int in_pass, after_move, stop_in_pass;
  long line;
  double last;
  int increasing;
} pass_heard;

static int on_pass_progress(void *user, const swarf_sim_progress *p) {
  pass_heard *h = user;
  if (p->pass < 0) {
    h->after_move++, h->last = -1.0;
    return 0;
  }
  if (!(p->pass >= 0.0 && p->pass <= 1.0) || p->stock == NULL) h->increasing = 0;
  if (p->line != h->line) return 0; /* the plunge's pass */
  if (!(p->pass > h->last)) h->increasing = 0;
  h->last = p->pass;
  h->in_pass++;
  return h->stop_in_pass > 0 && h->in_pass >= h->stop_in_pass;
}

/* One long helix (G2 P40 around a 16 mm circle, one move): progress is told
 * within its removal pass too (cfg.tick < 0: after every chunk of blocks),
 * with its line, and a stop there aborts the run. */
static void test_progress_within_a_move(void) {
  static const char helix[] =
      "G21 G90 G17\nG0 X28 Y15 Z1\nG1 Z-0.5 F500\nG2 X28 Y15 I-8 J0 Z-6 P40\n";
  swarf_sim_config cfg;
  swarf_error err;
  swarf_stock *out = NULL;
  pass_heard h = {0, 0, 0, 4, -1.0, 1};
  base_config(&cfg);
  cfg.tick = -1.0;
  cfg.batch = 1;
  cfg.cb = (swarf_sim_callbacks){.progress = on_pass_progress, .user = &h};
  CHECK(swarf_sim_run_text(&cfg, "h.ngc", helix, strlen(helix), &out, NULL, &err) == SWARF_OK, "%s",
        err.message);
  printf("helix: %d progress calls within passes, %d after moves\n", h.in_pass, h.after_move);
  CHECK(h.in_pass >= 3 && h.increasing, "progress within the helix's pass (line 4), increasing");
  swarf_stock_free(out);
  h = (pass_heard){0, 0, 2, 4, -1.0, 1};
  CHECK(swarf_sim_run_text(&cfg, "h.ngc", helix, strlen(helix), &out, NULL, &err) ==
                SWARF_ERR_ABORTED &&
            out == NULL && h.in_pass == 2,
        "a stop within a pass aborts the run (%d calls)", h.in_pass);
}

static swarf_stock *run_chunks(const swarf_sim_config *cfg, const char *text, unsigned seed) {
  swarf_sim *sim;
  size_t len = strlen(text), at = 0;
  CHECK(swarf_sim_new(cfg, "p.ngc", &sim, NULL) == SWARF_OK, "new");
  srand(seed);
  while (at < len) {
    size_t n = 1 + (size_t)rand() % 37;
    if (n > len - at) n = len - at;
    CHECK(swarf_sim_feed(sim, text + at, n) == SWARF_OK, "feed at %zu", at);
    at += n;
  }
  CHECK(swarf_sim_finish(sim) == SWARF_OK, "finish");
  CHECK(swarf_sim_feed(sim, "G0 X0\n", 6) == SWARF_ERR_STATE, "feed after finish is refused");
  swarf_stock *out = swarf_sim_take_stock(sim);
  swarf_sim_free(sim);
  return out;
}

static void test_streaming(void) {
  swarf_sim_config cfg;
  swarf_sim_report rep;
  swarf_stock *one = NULL, *split;
  swarf_error err;
  heard h;
  memset(&h, 0, sizeof h);
  base_config(&cfg);
  cfg.cb = (swarf_sim_callbacks){on_progress, on_alarm, on_line, &h, NULL, NULL};
  CHECK(swarf_sim_run_text(&cfg, "p.ngc", program, strlen(program), &one, &rep, &err) == SWARF_OK,
        "%s", err.message);
  CHECK(h.nalarms == 3 && h.alarm_line[0] == 5 && h.alarm_line[1] == 8 && h.alarm_line[2] == 9,
        "alarms heard at lines 5 8 9 (%d heard)", h.nalarms);
  CHECK(rep.alarm_count[SWARF_ALARM_RAPID] == 3 && rep.alarms == 3, "report counts 3 alarms");
  CHECK(rep.alarm[1].line == 8 && rep.alarm[1].kind == SWARF_ALARM_RAPID, "report keeps them");
  CHECK(h.line_moves == rep.moves && h.order_broken == 0, "lines: %ld moves of %ld, in order",
        h.line_moves, rep.moves);
  CHECK_NEAR(h.line_time, rep.machining_s, 1e-9 * rep.machining_s, "line times sum");
  CHECK(h.progress_calls >= rep.moves, "progress after every move");
  CHECK(rep.volume_before - rep.volume_after > 100, "material removed");
  cfg.cb = (swarf_sim_callbacks){0};
  for (unsigned seed = 1; seed <= 3; seed++) {
    split = run_chunks(&cfg, program, seed);
    check_same(one, split, "random splits = one feed");
    swarf_stock_free(split);
  }
  for (int threads = 1; threads <= 3; threads++) { /* the default above: all cores */
    swarf_stock *t = NULL;
    cfg.threads = threads;
    CHECK(swarf_sim_run_text(&cfg, "p.ngc", program, strlen(program), &t, NULL, &err) == SWARF_OK,
          "%s", err.message);
    CHECK(swarf_stock_threads(t) == threads, "the stock runs on %d threads", threads);
    check_same(one, t, "any number of threads = all cores");
    swarf_stock_free(t);
  }
  cfg.threads = -1;
  CHECK(swarf_sim_run_text(&cfg, "p.ngc", program, strlen(program), &split, NULL, &err) ==
                SWARF_ERR_ARG &&
            strstr(err.message, "threads") != NULL,
        "threads < 0 is refused: %s", err.message);
  swarf_stock_free(one);
}

/* G1 X5 Y10 Z-2 -> X30 from above: the same motions added directly. */
static void test_add_motion(void) {
  static const char slot[] = "G0 X5 Y10 Z5\nG1 Z-2 F100\nG1 X30\n";
  const double pts[3][3] = {{5, 10, 5}, {5, 10, -2}, {30, 10, -2}};
  swarf_sim_config cfg;
  swarf_stock *ref = NULL;
  swarf_sim *sim;
  base_config(&cfg);
  CHECK(swarf_sim_run_text(&cfg, "slot", slot, strlen(slot), &ref, NULL, NULL) == SWARF_OK, "ref");
  CHECK(swarf_sim_new(&cfg, "motions", &sim, NULL) == SWARF_OK, "new");
  for (int i = 0; i < 2; i++) {
    swarf_motion m;
    memset(&m, 0, sizeof m);
    m.kind = SWARF_MOTION_LINE;
    memcpy(m.p0, pts[i], sizeof m.p0);
    memcpy(m.p1, pts[i + 1], sizeof m.p1);
    m.length = fabs(pts[i + 1][0] - pts[i][0]) + fabs(pts[i + 1][2] - pts[i][2]);
    m.duration = m.length / 100 * 60;
    m.tool = 1;
    m.line = i + 2;
    CHECK(swarf_sim_add_motion(sim, &m) == SWARF_OK, "add motion %d", i);
  }
  swarf_motion bad;
  memset(&bad, 0, sizeof bad);
  bad.tool = 7;
  CHECK(swarf_sim_finish(sim) == SWARF_OK, "finish");
  swarf_stock *got = swarf_sim_take_stock(sim);
  check_same(ref, got, "motions = their G-code");
  swarf_sim_free(sim);
  CHECK(swarf_sim_new(&cfg, "motions", &sim, NULL) == SWARF_OK, "new");
  CHECK(swarf_sim_add_motion(sim, &bad) == SWARF_ERR_TOOL, "a motion with an unknown tool");
  swarf_sim_free(sim);
  swarf_stock_free(ref);
  swarf_stock_free(got);
}

/* Program A, then B on A's stock = one run of A and B. */
static void test_continue(void) {
  static const char a[] = "G0 X5 Y10 Z5\nG1 Z-2 F100\nG1 X30\nG0 Z5\n";
  static const char b[] = "G0 X10 Y5 Z5\nG1 Z-3 F100\nG1 Y25\nG0 Z5\n";
  char ab[256];
  swarf_sim_config cfg;
  swarf_stock *sa = NULL, *sab = NULL;
  swarf_sim *sim;
  snprintf(ab, sizeof ab, "%s%s", a, b);
  base_config(&cfg);
  CHECK(swarf_sim_run_text(&cfg, "a", a, strlen(a), &sa, NULL, NULL) == SWARF_OK, "A");
  CHECK(swarf_sim_run_text(&cfg, "ab", ab, strlen(ab), &sab, NULL, NULL) == SWARF_OK, "A+B");
  cfg.voxel = 1.0; /* the stock's own voxel wins */
  CHECK(swarf_sim_new_with_stock(&cfg, "b", sa, &sim, NULL) == SWARF_OK, "new on A's stock");
  CHECK(swarf_sim_feed(sim, b, strlen(b)) == SWARF_OK && swarf_sim_finish(sim) == SWARF_OK, "B");
  check_same(sab, swarf_sim_stock(sim), "A then B = A+B");
  swarf_sim_free(sim);
  swarf_stock_free(sab);
}

static void test_errors(void) {
  static const char bad[] = "G0 X1\nG1 X2 F100\nG2 X3\n";
  static const char tool[] = "G0 X1\nT5 M6\n";
  swarf_sim_config cfg;
  swarf_stock *out = (swarf_stock *)1;
  swarf_error err;
  swarf_sim *sim;
  heard h;
  base_config(&cfg);
  CHECK(swarf_sim_run_text(&cfg, "bad.ngc", bad, strlen(bad), &out, NULL, &err) != SWARF_OK &&
            out == NULL,
        "a bad arc fails, no stock");
  CHECK(swarf_status_classify(err.status) == SWARF_CLASS_INPUT && err.line == 3 && err.code != 0 &&
            !strcmp(err.file, "bad.ngc"),
        "input error at bad.ngc:3 with an identity (%s %ld %d)", swarf_status_name(err.status),
        err.line, err.code);
  cfg.fragment = 0; /* a whole LinuxCNC program must end (rs274), after its moves */
  CHECK(swarf_sim_run_text(&cfg, "open.ngc", tool, 6, &out, NULL, &err) == SWARF_ERR_SEMANTIC &&
            out == NULL && err.line == 1 && err.code == SWARF_GCODE_E_NO_PROGRAM_END,
        "no M2: refused at its last line (%s %ld)", err.message, err.line);
  cfg.fragment = 1;
  { /* a config on the heap, with the defaults; the handle keeps its copy */
    swarf_sim_config *heap = swarf_sim_config_new();
    swarf_sim *one = NULL;
    CHECK(heap != NULL && heap->voxel == 0.2 && heap->half_width == 3 && heap->batch == 1024,
          "swarf_sim_config_new: the defaults");
    if (heap != NULL) {
      base_config(heap);
      CHECK(swarf_sim_new(heap, "p.ngc", &one, &err) == SWARF_OK, "new from a heap config");
      swarf_sim_config_free(heap);
      CHECK(one != NULL && swarf_sim_feed(one, "G0 X1 Y1 Z5\nG1 Z-1 F100\n", 24) == SWARF_OK &&
                swarf_sim_finish(one) == SWARF_OK,
            "the run goes on after the config is freed");
      swarf_sim_free(one);
    }
    swarf_sim_config_free(NULL);
  }
  { /* NULL outputs and ranges refused with the argument's name, no crash */
    swarf_sim_config c2;
    swarf_sim *none = NULL;
    CHECK(swarf_sim_parse_stock("box:0,0,-1,1,1,0", NULL, &err) == SWARF_ERR_ARG &&
              strstr(err.message, "out is NULL") != NULL,
          "parse_stock(spec, NULL): %s", err.message);
    CHECK(swarf_sim_parse_tool("T1=flat,D1", NULL, &err) == SWARF_ERR_ARG,
          "parse_tool(spec, NULL)");
    CHECK(swarf_sim_parse_holder("T1=20x40", NULL, &err) == SWARF_ERR_ARG,
          "parse_holder(spec, NULL)");
    CHECK(swarf_sim_parse_fixture("box:0,0,0,1,1,1", NULL, &err) == SWARF_ERR_ARG,
          "parse_fixture(spec, NULL)");
    base_config(&c2);
    c2.half_width = 2;
    CHECK(swarf_sim_new(&c2, "p.ngc", &none, &err) == SWARF_ERR_ARG && none == NULL &&
              strstr(err.message, "band") != NULL,
          "band 2 refused: %s", err.message);
    base_config(&c2);
    c2.batch = 0;
    CHECK(swarf_sim_new(&c2, "p.ngc", &none, &err) == SWARF_ERR_ARG && none == NULL &&
              strstr(err.message, "batch") != NULL,
          "batch 0 refused: %s", err.message);
  }
  /* rs274's rule: the T word of a tool the table lacks stops the program there */
  CHECK(swarf_sim_run_text(&cfg, "t.ngc", tool, strlen(tool), &out, NULL, &err) ==
                SWARF_ERR_SEMANTIC &&
            err.line == 2 && strstr(err.message, "Requested tool") != NULL,
        "unknown tool at line 2 (%s, line %ld)", swarf_status_name(err.status), err.line);
  memset(&h, 0, sizeof h);
  h.stop_after = 3;
  cfg.cb = (swarf_sim_callbacks){on_progress, NULL, NULL, &h, NULL, NULL};
  CHECK(swarf_sim_new(&cfg, "p.ngc", &sim, NULL) == SWARF_OK, "new");
  CHECK(swarf_sim_feed(sim, program, strlen(program)) == SWARF_ERR_ABORTED, "progress stops it");
  CHECK(swarf_sim_get_report(sim)->moves == 3, "after 3 moves");
  CHECK(swarf_sim_finish(sim) == SWARF_ERR_STATE, "finish after a failure is refused");
  CHECK(swarf_sim_error(sim)->status == SWARF_ERR_ABORTED, "the first failure is kept");
  CHECK(swarf_status_classify(SWARF_ERR_ABORTED) == SWARF_CLASS_ABORTED, "aborted class");
  swarf_sim_free(sim);
  cfg.cb = (swarf_sim_callbacks){0};
  cfg.stock.hi[0] = -1;
  CHECK(swarf_sim_new(&cfg, "p.ngc", &sim, &err) == SWARF_ERR_ARG && sim == NULL, "bad stock");
  CHECK(!strcmp(swarf_status_name(SWARF_ERR_SYNTAX), "SWARF_ERR_SYNTAX"), "status names");
  CHECK(swarf_sim_parse_tool("T1=cone,D3", &(swarf_sim_tool){0}, &err) != SWARF_OK &&
            !strcmp(err.word, "--tool"),
        "a bad tool spec names its flag");
}

/* Every alarm through swarf_sim_alarm_count/_at, past the report's 16: 24
 * rapids down into the stock, each at its own line (2, 4, ..., 48); and the
 * report's removed volume is before - after. */
static void test_all_alarms(void) {
  char text[2048];
  size_t at = 0;
  swarf_sim_config cfg;
  swarf_sim *sim = NULL;
  base_config(&cfg);
  for (int i = 0; i < 24; i++)
    at += (size_t)snprintf(text + at, sizeof text - at, "G0 X%d Y15 Z5\nG0 Z-1\n", 2 + i);
  CHECK(swarf_sim_new(&cfg, "rapids.ngc", &sim, NULL) == SWARF_OK, "new");
  CHECK(swarf_sim_feed(sim, text, at) == SWARF_OK && swarf_sim_finish(sim) == SWARF_OK, "run");
  const swarf_sim_report *r = swarf_sim_get_report(sim);
  long n = swarf_sim_alarm_count(sim), in_order = 1;
  for (long i = 0; i < n; i++)
    in_order &= swarf_sim_alarm_at(sim, i)->line == 2 * (i + 1) &&
                swarf_sim_alarm_at(sim, i)->kind == SWARF_ALARM_RAPID;
  CHECK(n == 24 && r->alarms == 24 && in_order, "all 24 alarms kept, in order (%ld, %ld)", n,
        r->alarms);
  CHECK(swarf_sim_alarm_at(sim, 24) == NULL && swarf_sim_alarm_at(sim, -1) == NULL &&
            swarf_sim_alarm_at(NULL, 0) == NULL && swarf_sim_alarm_count(NULL) == 0,
        "outside the alarms: NULL");
  CHECK(r->removed > 0 && r->removed == r->volume_before - r->volume_after,
        "report.removed %g = %g - %g", r->removed, r->volume_before, r->volume_after);
  swarf_sim_free(sim);
}

int main(void) {
  test_all_alarms();
  test_streaming();
  test_add_motion();
  test_progress_within_a_move();
  test_continue();
  test_errors();
  return check_done();
}
