/* sim.c -- the simulation driver (see sim.h).
 *
 * The parser calls on_move for every canonical move; motions are queued with
 * their sweeps in a fixed-size batch that is removed from the stock in one
 * pass when full and at the end. Memory is bounded by the batch size, not by
 * the program. The sim_state owns the batch arrays and the stock until the
 * run hands the stock to the caller.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "sim.h"

/* A move stamped at n + 1 evenly spaced poses (the benchmark baseline). */
typedef struct {
  const swarf_cutter *cutter;
  const swarf_motion *motion;
  int n;
} stamp_ctx;

typedef struct {
  const swarf_sim_config *cfg;
  const char *name;
  swarf_stock *stock;
  const swarf_cutter *cutter; /* in the spindle, NULL when empty */
  swarf_motion *motions;      /* batch: motions, their sweeps and cuts */
  swarf_sweep *sweeps;
  swarf_stock_cut *cuts;
  stamp_ctx *stamps;
  int n, cap;
  double pad_lo[3], pad_hi[3]; /* stock box grown by the narrow band */
  swarf_sim_report *rep;
  char *msg;
  size_t msglen;
  int status; /* 0, 1 internal, 2 bad input */
} sim_state;

static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double sweep_sdf(const void *ctx, double x, double y, double z) {
  const double p[3] = {x, y, z};
  return swarf_sweep_sdf((const swarf_sweep *)ctx, p, NULL);
}

/* The cutter's sdf at p for one pose. */
static double pose_sdf(const swarf_cutter *c, const double t[3], const double U[9], double x,
                       double y, double z) {
  const double d3[3] = {x - t[0], y - t[1], z - t[2]};
  const double q[3] = {U[0] * d3[0] + U[3] * d3[1] + U[6] * d3[2],
                       U[1] * d3[0] + U[4] * d3[1] + U[7] * d3[2],
                       U[2] * d3[0] + U[5] * d3[1] + U[8] * d3[2]};
  return swarf_cutter_sdf(c, q);
}

/* Minimum over the stamped poses, from the per-thread pose table (the same
 * one the swept sdf uses) for moves of up to 4096 stamps (600 kB a slot). */
static double stamp_sdf(const void *ctx, double x, double y, double z) {
  const stamp_ctx *s = ctx;
  const swarf_pose *table = s->n <= 4096 ? swarf_motion_pose_table(s->motion, s->n) : NULL;
  double best = INFINITY, t[3], U[9];
  for (int i = 0; i <= s->n; i++) {
    double d;
    if (table != NULL)
      d = pose_sdf(s->cutter, table[i].t, table[i].U, x, y, z);
    else {
      swarf_motion_eval(s->motion, (double)i / s->n, t, U);
      d = pose_sdf(s->cutter, t, U, x, y, z);
    }
    if (d < best) best = d;
  }
  return best;
}

static const swarf_sim_tool *find_tool(const swarf_sim_config *cfg, int number) {
  for (int i = 0; i < cfg->ntools; i++)
    if (cfg->tools[i].number == number) return &cfg->tools[i];
  return NULL;
}

static int fail_at(sim_state *st, const swarf_move *mv, const char *what) {
  snprintf(st->msg, st->msglen, "%s:%ld:%d: %s", st->name, mv->line, mv->column, what);
  st->status = 2;
  return 1;
}

static int flush(sim_state *st) {
  if (st->n == 0) return 0;
  if (swarf_stock_remove_batch(st->stock, st->cuts, (size_t)st->n, st->msg, st->msglen) != 0) {
    st->status = 1;
    return 1;
  }
  st->n = 0;
  return 0;
}

static int boxes_overlap(const double alo[3], const double ahi[3], const double blo[3],
                         const double bhi[3]) {
  for (int k = 0; k < 3; k++)
    if (ahi[k] < blo[k] || alo[k] > bhi[k]) return 0;
  return 1;
}

/* A rapid move is checked against the stock as it stands when it runs:
 * cutting deeper than half a voxel into material raises an alarm. The moves
 * queued before it have been removed (queue_motion). */
static int check_rapid(sim_state *st, const swarf_motion *m, const swarf_stock_cut *c) {
  swarf_sim_report *r = st->rep;
  int hit = 0;
  if (swarf_stock_overlaps(st->stock, c, 0.5 * st->cfg->voxel, &hit, NULL, st->msg, st->msglen) != 0) {
    st->status = 1;
    return 1;
  }
  if (hit && r->alarms < SWARF_SIM_MAX_ALARMS) {
    r->alarm_line[r->alarms] = m->line;
    r->alarm_column[r->alarms] = m->column;
  }
  r->alarms += hit;
  return 0;
}

/* Remove the queued moves before the rapid in slot st->n, which moves to slot 0. */
static int flush_before_rapid(sim_state *st) {
  swarf_motion m = st->motions[st->n];
  if (flush(st) != 0) return 1;
  st->motions[0] = m;
  return 0;
}

/* Queue the sweep of the motion in slot st->n if it can touch the stock. */
static int queue_motion(sim_state *st) {
  swarf_motion *m = &st->motions[st->n];
  swarf_sweep *s = &st->sweeps[st->n];
  swarf_stock_cut *c = &st->cuts[st->n];
  swarf_sweep_init_voxel(s, st->cutter, m, st->cfg->voxel);
  swarf_sweep_bounds(s, c->lo, c->hi);
  if (!boxes_overlap(c->lo, c->hi, st->pad_lo, st->pad_hi)) return 0;
  if (m->rapid && st->n > 0) /* checked against the stock as it stands: once, from slot 0 */
    return flush_before_rapid(st) != 0 ? 1 : queue_motion(st);
  c->sdf = sweep_sdf;
  c->ctx = s;
  if (st->cfg->stamp_step > 0) {
    stamp_ctx *sc = &st->stamps[st->n];
    /* poses stamp_step apart along the path of the cutter's farthest point */
    double n = ceil((m->length + m->turn * hypot(0.5 * st->cutter->diameter, st->cutter->length)) /
                    st->cfg->stamp_step);
    sc->cutter = st->cutter;
    sc->motion = m;
    sc->n = n < 1 ? 1 : n > 1e6 ? 1000000 : (int)n;
    c->sdf = stamp_sdf;
    c->ctx = sc;
  }
  st->rep->cutting_moves++;
  if (m->rapid && check_rapid(st, m, c) != 0) return 1;
  if (++st->n == st->cap) return flush(st);
  return 0;
}

static int on_tool_change(sim_state *st, const swarf_move *mv) {
  const swarf_sim_tool *t = find_tool(st->cfg, mv->tool);
  char what[160];
  st->rep->tool_changes++;
  if (mv->tool == 0) {
    st->cutter = NULL;
    return 0;
  }
  if (t == NULL) {
    snprintf(what, sizeof what,
             "tool T%d is not in the tool table; describe it with --tool T%d=<shape>,D<diameter>",
             mv->tool, mv->tool);
    return fail_at(st, mv, what);
  }
  st->cutter = &t->cutter;
  return 0;
}

/* Tell the observer (if any) about the move; 1 if it asks to stop. */
static int observe(sim_state *st, const swarf_move *mv) {
  int tool = mv->tool;
  if (st->cfg->observe == NULL) return 0;
  if (tool == 0 && st->cutter != NULL && st->cfg->ntools == 1) tool = st->cfg->tools[0].number;
  if (st->cfg->observe(st->cfg->observe_ctx, st->rep, mv->line, tool, st->stock) == 0) return 0;
  snprintf(st->msg, st->msglen, "%s:%ld: aborted by a Modbus command", st->name, mv->line);
  st->status = 3;
  return 1;
}

static int on_move(const swarf_move *mv, void *user) {
  sim_state *st = user;
  swarf_motion *m = &st->motions[st->n];
  if (mv->kind == SWARF_MOVE_TOOL_CHANGE) return on_tool_change(st, mv);
  if (mv->kind == SWARF_MOVE_DWELL) return 0;
  int rc = swarf_machine_motion(&st->cfg->machine, mv, m);
  if (rc == -2)
    return fail_at(st, mv,
                   "this move turns a rotary axis the machine does not have; choose "
                   "one with --machine xyza, xyzac-trt or xyzbc-trt");
  if (rc != 0) return 0;
  st->rep->moves++;
  st->rep->rapids += m->rapid;
  st->rep->arcs += m->kind == SWARF_MOTION_HELIX;
  st->rep->path_mm += m->length;
  st->rep->machining_s += m->duration;
  if (observe(st, mv)) return 1;
  if (st->cutter == NULL || swarf_motion_is_null(m)) return 0;
  if (st->cfg->progress && st->rep->moves % 4096 == 0)
    st->cfg->progress(st->cfg->progress_ctx, -1.0, st->rep->moves);
  return queue_motion(st);
}

static int state_init(sim_state *st, const swarf_sim_config *cfg, const char *name,
                      swarf_sim_report *rep, char *msg, size_t msglen) {
  memset(st, 0, sizeof *st);
  memset(rep, 0, sizeof *rep);
  st->cfg = cfg;
  st->name = name;
  st->rep = rep;
  st->msg = msg;
  st->msglen = msglen;
  st->cap = cfg->batch > 0 ? (cfg->batch < 4096 ? cfg->batch : 4096) : 128;
  st->motions = malloc(sizeof *st->motions * (size_t)st->cap);
  st->sweeps = malloc(sizeof *st->sweeps * (size_t)st->cap);
  st->cuts = malloc(sizeof *st->cuts * (size_t)st->cap);
  st->stamps = malloc(sizeof *st->stamps * (size_t)st->cap);
  if (!st->motions || !st->sweeps || !st->cuts || !st->stamps) {
    snprintf(msg, msglen, "out of memory");
    return 1;
  }
  if (cfg->ntools == 1) st->cutter = &cfg->tools[0].cutter;
  if (cfg->stock_cylinder)
    st->stock = swarf_stock_new_cylinder(cfg->cyl_axis, cfg->cyl_radius,
                                         cfg->stock_lo[cfg->cyl_axis], cfg->stock_hi[cfg->cyl_axis],
                                         cfg->voxel, cfg->half_width, msg, msglen);
  else
    st->stock =
        swarf_stock_new_box(cfg->stock_lo, cfg->stock_hi, cfg->voxel, cfg->half_width, msg, msglen);
  if (st->stock == NULL) return 1;
  double band = swarf_stock_voxel(st->stock) * (swarf_stock_half_width(st->stock) + 1);
  for (int k = 0; k < 3; k++) {
    st->pad_lo[k] = cfg->stock_lo[k] - band;
    st->pad_hi[k] = cfg->stock_hi[k] + band;
  }
  rep->volume_before = swarf_stock_volume(st->stock);
  return 0;
}

static void state_clear(sim_state *st) {
  free(st->motions);
  free(st->sweeps);
  free(st->cuts);
  free(st->stamps);
  swarf_stock_free(st->stock);
}

/* Map a parser status to the run's status; fills msg for parser errors. */
static int parser_outcome(sim_state *st, swarf_gcode_parser *p, int rc) {
  const swarf_error *e = swarf_gcode_parser_error(p);
  if (rc == SWARF_OK) return 0;
  if (rc == SWARF_ERR_ABORTED) return st->status ? st->status : 1;
  if (e != NULL)
    snprintf(st->msg, st->msglen, "%s:%ld:%d: %s", e->file, e->line, e->column, e->message);
  return swarf_status_classify(rc) == SWARF_CLASS_INPUT ? 2 : 1;
}

/* The parser's tool table is the cutters given: each with length offset 0,
 * since the simulated point is the tool tip (G43 H<n> then changes nothing,
 * G43 H<unknown> is an error at its line). */
static void set_tool_table(swarf_gcode_parser *p, const swarf_sim_config *cfg) {
  swarf_gcode_parser_clear_tools(p);
  for (int i = 0; i < cfg->ntools; i++)
    swarf_gcode_parser_set_tool(p, cfg->tools[i].number, 0.0, cfg->tools[i].cutter.diameter);
}

typedef int (*feed_fn)(swarf_gcode_parser *p, sim_state *st, const void *src);

static int run(const swarf_sim_config *cfg, const char *name, feed_fn feed, const void *src,
               swarf_stock **out, swarf_sim_report *rep, char *msg, size_t msglen) {
  sim_state st;
  double t0 = now_seconds();
  int rc = 1;
  *out = NULL;
  if (state_init(&st, cfg, name, rep, msg, msglen) == 0) {
    swarf_gcode_parser *p = NULL;
    swarf_gcode_parser_new(name, on_move, &st, &p);
    if (p == NULL) {
      snprintf(msg, msglen, "out of memory");
    } else {
      set_tool_table(p, cfg);
      rc = feed(p, &st, src);
      if (rc == 0) rc = parser_outcome(&st, p, swarf_gcode_parser_finish(p));
      rep->lines = swarf_gcode_parser_lines(p);
      swarf_gcode_parser_free(p);
    }
    if (rc == 0 && flush(&st) != 0) rc = 1;
  }
  if (rc == 0) {
    rep->volume_after = swarf_stock_volume(st.stock);
    *out = st.stock;
    st.stock = NULL;
  }
  state_clear(&st);
  rep->seconds = now_seconds() - t0;
  return rc;
}

typedef struct {
  const char *text;
  size_t len;
} text_src;

static int feed_text(swarf_gcode_parser *p, sim_state *st, const void *src) {
  const text_src *t = src;
  return parser_outcome(st, p, swarf_gcode_parser_feed(p, t->text, t->len));
}

static int feed_file(swarf_gcode_parser *p, sim_state *st, const void *src) {
  FILE *f = (FILE *)src;
  static const size_t chunk = 1 << 16;
  char *buf = malloc(chunk);
  struct stat sb;
  double total = fstat(fileno(f), &sb) == 0 && sb.st_size > 0 ? (double)sb.st_size : 0.0;
  double done = 0.0;
  size_t n;
  int rc = 0;
  if (buf == NULL) return 1;
  while (rc == 0 && (n = fread(buf, 1, chunk, f)) > 0) {
    rc = parser_outcome(st, p, swarf_gcode_parser_feed(p, buf, n));
    done += (double)n;
    if (st->cfg->progress && total > 0)
      st->cfg->progress(st->cfg->progress_ctx, done / total, st->rep->moves);
  }
  if (rc == 0 && ferror(f)) {
    snprintf(st->msg, st->msglen, "%s: read error: %s", st->name, strerror(errno));
    rc = 2;
  }
  free(buf);
  return rc;
}

int swarf_sim_run_text(const swarf_sim_config *cfg, const char *name, const char *text, size_t len,
                       swarf_stock **out, swarf_sim_report *rep, char *msg, size_t msglen) {
  text_src src = {text, len};
  return run(cfg, name, feed_text, &src, out, rep, msg, msglen);
}

int swarf_sim_run(const swarf_sim_config *cfg, const char *path, swarf_stock **out,
                  swarf_sim_report *rep, char *msg, size_t msglen) {
  FILE *f = fopen(path, "rb");
  int rc;
  if (f == NULL) {
    *out = NULL;
    memset(rep, 0, sizeof *rep);
    snprintf(msg, msglen, "%s: cannot open the program: %s", path, strerror(errno));
    return 2;
  }
  rc = run(cfg, path, feed_file, f, out, rep, msg, msglen);
  fclose(f);
  return rc;
}
