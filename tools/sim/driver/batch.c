/* SPDX-License-Identifier: MPL-2.0 */
/* batch.c -- the simulation's batch of queued sweeps (sim_private.h).
 *
 * Each motion that can touch the material gets its swept volume (or, for
 * the --stamp baseline, the cutter stamped at poses along it) in the next
 * slot; a full batch is removed from the stock in one pass. A rapid move is
 * checked against the stock as it stands when it runs: the moves queued
 * before it are removed first, and cutting deeper than half a voxel into
 * material raises an alarm (the cut is still made, as on the machine).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sim_private.h"

static double sweep_sdf(const void *ctx, double x, double y, double z) {
  const double p[3] = {x, y, z};
  return swarf_sweep_sdf((const swarf_sweep *)ctx, p, NULL);
}

static double sweep_range(const void *ctx, const double p[3], double lo, double hi) {
  return swarf_sweep_sdf_range((const swarf_sweep *)ctx, p, lo, hi);
}

/* The range with a plane near p, where the sweep has one (stock.h). */
static int sweep_range_plane(const void *ctx, const double p[3], double lo, double hi, double r,
                             double *d, double *pd, double g[3]) {
  return swarf_sweep_range_plane((const swarf_sweep *)ctx, p, lo, hi, r, d, pd, g);
}

/* The sweep's sdf with its supporting plane, where it has one (stock.h). */
static int sweep_support(const void *ctx, double x, double y, double z, double *d, double g[3]) {
  const double p[3] = {x, y, z};
  return swarf_sweep_support((const swarf_sweep *)ctx, p, d, g);
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
  const swarf_sim_stamp *s = ctx;
  const swarf_pose *table = NULL;
  if (s->n <= 4096) swarf_motion_pose_table(s->motion, s->n, &table); /* NULL: poses computed */
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

int swarf_sim_batch_init(swarf_sim *s) {
  int b = s->cfg.batch;
  s->cap = b > 0 ? (b < 4096 ? b : 4096) : 128;
  s->motions = malloc(sizeof *s->motions * (size_t)s->cap);
  s->sweeps = malloc(sizeof *s->sweeps * (size_t)s->cap);
  s->cuts = malloc(sizeof *s->cuts * (size_t)s->cap);
  s->supports = malloc(sizeof *s->supports * (size_t)s->cap);
  s->stamps = malloc(sizeof *s->stamps * (size_t)s->cap);
  s->pending_cap = s->cap;
  s->pending = malloc(sizeof *s->pending * (size_t)s->pending_cap);
  s->cut_id = malloc(sizeof *s->cut_id * (size_t)s->cap);
  s->effects = malloc(sizeof *s->effects * (size_t)s->cap);
  return s->motions && s->sweeps && s->cuts && s->supports && s->stamps && s->pending &&
                 s->cut_id && s->effects
             ? 0
             : -1;
}

void swarf_sim_batch_clear(swarf_sim *s) {
  free(s->motions);
  free(s->sweeps);
  free(s->cuts);
  free(s->supports);
  free(s->stamps);
  free(s->pending);
  free(s->cut_id);
  free(s->effects);
}

/* A gouge of cut i: one alarm, told at once. */
static void raise_gouge(swarf_sim *s, int i) {
  const swarf_motion *m = &s->motions[i];
  const swarf_stock_cut_effect *e = &s->effects[i];
  int tool = m->tool != 0 ? m->tool : s->cfg.ntools == 1 ? s->cfg.tools[0].number : 0;
  swarf_alarm a = {SWARF_ALARM_GOUGE,
                   m->line,
                   m->column,
                   tool,
                   e->gouge_depth,
                   {e->gouge_at[0], e->gouge_at[1], e->gouge_at[2]},
                   0,
                   0};
  swarf_sim_raise(s, &a);
}

/* The batch, measuring each cut: its removed volume goes to its line (if
 * asked for: else the gouges alone are measured), a gouge into the design
 * raises an alarm (in program order). */
static int flush_measured(swarf_sim *s) {
  swarf_error err;
  swarf_error_init(&err);
  swarf_status st =
      s->volumes
          ? swarf_stock_remove_batch_measured_support(s->stock, s->cuts, s->supports, (size_t)s->n,
                                                      s->cfg.design, s->tolerance, s->effects, &err)
          : swarf_stock_remove_batch_gouges_support(s->stock, s->cuts, s->supports, (size_t)s->n,
                                                    s->cfg.design, s->tolerance, s->effects, &err);
  if (st != SWARF_OK) {
    swarf_sim_fail(s, err.status, 0, 0, "%s", err.message);
    return 1;
  }
  if (swarf_sim_slab_effects(s, s->effects, s->n) != 0) return 1;
  for (int i = 0; i < s->n; i++) {
    swarf_sim_lines_removed(s, s->cut_id[i], s->effects[i].removed);
    if (s->effects[i].gouge_depth > 0) raise_gouge(s, i);
  }
  return 0;
}

int swarf_sim_batch_flush(swarf_sim *s) {
  swarf_error e;
  s->blocks = 0.0;
  if (swarf_sim_slab_sync(s) != 0) return 1;
  if (s->n > 0 && s->measured) {
    if (flush_measured(s) != 0) return 1;
    s->n = 0;
  } else if (s->n > 0) {
    if (swarf_stock_remove_batch_support(s->stock, s->cuts, s->supports, (size_t)s->n, &e) !=
        SWARF_OK) {
      swarf_sim_fail(s, SWARF_ERR_INTERNAL, 0, 0, "%s", e.message);
      return 1;
    }
    s->n = 0;
  }
  return swarf_sim_lines_flush(s, 0);
}

/* Kept for swarf_sim_alarm_at; out of memory keeps the count only. */
static void keep_alarm(swarf_sim *s, const swarf_alarm *a) {
  if (s->nalarms == s->alarms_cap && s->nalarms < SWARF_SIM_KEPT_ALARMS) {
    const long cap = s->alarms_cap ? 2 * s->alarms_cap : 64;
    swarf_alarm *p = realloc(s->alarms, sizeof *p * (size_t)cap);
    if (p != NULL) s->alarms = p, s->alarms_cap = cap;
  }
  if (s->nalarms < s->alarms_cap) s->alarms[s->nalarms++] = *a;
}

void swarf_sim_raise(swarf_sim *s, const swarf_alarm *a) {
  swarf_sim_report *r = &s->rep;
  if (r->alarms < SWARF_SIM_MAX_ALARMS) r->alarm[r->alarms] = *a;
  keep_alarm(s, a);
  r->alarms++;
  if ((unsigned)a->kind < sizeof r->alarm_count / sizeof r->alarm_count[0])
    r->alarm_count[a->kind]++;
  if (s->cfg.cb.alarm != NULL) s->cfg.cb.alarm(s->cfg.cb.user, a);
}

static int boxes_overlap(const double alo[3], const double ahi[3], const double blo[3],
                         const double bhi[3]) {
  for (int k = 0; k < 3; k++)
    if (ahi[k] < blo[k] || alo[k] > bhi[k]) return 0;
  return 1;
}

/* Whether rapid m's cut c enters the material of the stock as it stands
 * (moves still queued not removed): *hit, and where. */
static int rapid_hits(swarf_sim *s, const swarf_motion *m, const swarf_stock_cut *c, int *hit,
                      double where[3]) {
  swarf_error e;
  *hit = 0;
  if (swarf_stock_overlaps(s->stock, c, 0.5 * s->cfg.voxel, hit, where, &e) != SWARF_OK) {
    swarf_sim_fail(s, SWARF_ERR_INTERNAL, m->line, m->column, "%s", e.message);
    return 1;
  }
  return swarf_sim_slab_hit(s, hit, where);
}

/* The rapid in slot 0 against the stock as it stands. */
static int check_rapid(swarf_sim *s, const swarf_motion *m, const swarf_stock_cut *c) {
  int hit = 0;
  double where[3];
  if (rapid_hits(s, m, c, &hit, where) != 0) return 1;
  if (hit) {
    swarf_alarm a = {SWARF_ALARM_RAPID,
                     m->line,
                     m->column,
                     s->tool->number,
                     NAN,
                     {where[0], where[1], where[2]},
                     0,
                     0};
    swarf_sim_raise(s, &a);
  }
  return 0;
}

/* A feed move with an empty spindle (T0 M6, or several tools and none
 * loaded yet) cuts nothing, but the spindle's nose, at the controlled point,
 * must not run into the material: a probe two voxels wide along the move,
 * against the stock as it stands. Every rank makes the same calls (the
 * flush and the combined hit are collective under MPI). */
int swarf_sim_batch_check_empty(swarf_sim *s, const swarf_motion *m) {
  swarf_cutter probe;
  swarf_sweep w;
  swarf_stock_cut c;
  swarf_error e;
  int hit = 0;
  double where[3];
  if (m->rapid || s->surveyor != NULL) return 0;
  memset(&c, 0, sizeof c);
  swarf_error_init(&e);
  if (swarf_cutter_init(&probe, SWARF_CUTTER_FLAT, 2 * s->cfg.voxel, 0, 2 * s->cfg.voxel, &e) !=
      SWARF_OK)
    return 0;
  swarf_sweep_init_voxel(&w, &probe, m, s->cfg.voxel);
  swarf_sweep_bounds(&w, c.lo, c.hi);
  if (!boxes_overlap(c.lo, c.hi, s->pad_lo, s->pad_hi)) return 0;
  if (s->n > 0 && swarf_sim_batch_flush(s) != 0) return 1;
  c.sdf = sweep_sdf;
  c.ctx = &w;
  c.range = m->kind == SWARF_MOTION_RIGID ? sweep_range : NULL;
  if (swarf_stock_overlaps(s->stock, &c, 0.25 * s->cfg.voxel, &hit, where, &e) != SWARF_OK) {
    swarf_sim_fail(s, SWARF_ERR_INTERNAL, m->line, m->column, "%s", e.message);
    return 1;
  }
  if (swarf_sim_slab_hit(s, &hit, where) != 0) return 1;
  if (hit) {
    swarf_alarm a = {
        SWARF_ALARM_NO_TOOL, m->line, m->column, 0, NAN, {where[0], where[1], where[2]}, 0, 0};
    swarf_sim_raise(s, &a);
  }
  return 0;
}

/* A batch is flushed early once its cuts' bounds span this many stock blocks
 * of 8^3 voxels: the removal keeps ~32 bytes per (block, cut) pair for a
 * pass, and a rotary move of a long tool spans thousands of blocks at fine
 * voxels. The impeller's first 1,500 lines at 0.1 mm, one thread (CPU s, peak):
 * no bound 7.6 s / 607 MB, 1.2e7 8.0 / 538, 5e6 9.3 / 338, 2e6 11.2 / 265
 * (batches of 128 moves: 340 MB on the whole program). */
#define BATCH_BLOCKS 8e6

/* The blocks of 8^3 voxels cut c's bounds span, padded as the stock pads them
 * (the band and a voxel each side; an estimate from above). */
static double cut_blocks(const swarf_sim *s, const swarf_stock_cut *c) {
  const double v = s->cfg.voxel, pad = (s->cfg.half_width + 1) * v;
  double n = 1.0;
  for (int k = 0; k < 3; k++)
    n *= floor((c->hi[k] - c->lo[k] + 2.0 * pad) / (8.0 * v)) + 2.0;
  return n;
}

/* Poses stamp_step apart along the path of the cutter's farthest point. */
static void set_stamps(swarf_sim *s, swarf_sim_stamp *sc, const swarf_motion *m) {
  const swarf_cutter *c = &s->tool->cutter;
  double n = ceil((m->length + m->turn * hypot(0.5 * c->diameter, c->length)) / s->cfg.stamp_step);
  sc->cutter = c;
  sc->motion = m;
  sc->n = n < 1 ? 1 : n > 1e6 ? 1000000 : (int)n;
}

int swarf_sim_batch_queue(swarf_sim *s, const swarf_motion *mv) {
  swarf_motion *m = &s->motions[s->n];
  swarf_sweep *w = &s->sweeps[s->n];
  swarf_stock_cut *c = &s->cuts[s->n];
  *m = *mv;
  swarf_sweep_init_voxel(w, &s->tool->cutter, m, s->cfg.voxel);
  swarf_sweep_bounds(w, c->lo, c->hi);
  const int reach = boxes_overlap(c->lo, c->hi, s->pad_lo, s->pad_hi);
  if (s->surveyor != NULL) { /* a survey (mpi/slab.c): the work only */
    if (reach) swarf_sim_slab_survey(s, c);
    return 0;
  }
  c->sdf = sweep_sdf;
  c->ctx = w;
  c->range = m->kind == SWARF_MOTION_RIGID ? sweep_range : NULL; /* rotary: pruned searches */
  c->range_plane = m->kind == SWARF_MOTION_RIGID ? sweep_range_plane : NULL; /* and local planes */
  s->supports[s->n] = m->kind == SWARF_MOTION_RIGID ? NULL : sweep_support;  /* 3-axis planes */
  /* shank, holder, fixtures: against the material as the move finds it */
  if (swarf_sim_collide_move(s, m, w, reach ? c : NULL) != 0) return 1;
  if (!reach) return 0;
  if (s->cfg.stamp_step > 0) {
    set_stamps(s, &s->stamps[s->n], m);
    c->sdf = stamp_sdf;
    c->ctx = &s->stamps[s->n];
    c->range = NULL;
    c->range_plane = NULL;
    s->supports[s->n] = NULL;
  }
  /* A rapid is checked against the material as it finds it. Removal only
   * takes material away, so one clear of the stock before the queued moves
   * are removed is clear after them: only a rapid that enters it flushes the
   * batch and is checked again from slot 0. Programs with many rapids keep
   * their batches whole; the alarms are as they were. */
  if (m->rapid && s->n > 0) {
    int hit;
    double where[3];
    if (rapid_hits(s, m, c, &hit, where) != 0) return 1;
    if (hit) return swarf_sim_batch_flush(s) != 0 ? 1 : swarf_sim_batch_queue(s, mv);
  }
  s->rep.cutting_moves++;
  s->cut_id[s->n] = s->cur_id;
  if (m->rapid && s->n == 0 && check_rapid(s, m, c) != 0) return 1;
  s->blocks += cut_blocks(s, c);
  if (++s->n == s->cap || s->blocks > BATCH_BLOCKS) return swarf_sim_batch_flush(s);
  return 0;
}
