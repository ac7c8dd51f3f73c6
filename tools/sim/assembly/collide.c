/* SPDX-License-Identifier: MPL-2.0 */
/* collide.c -- collisions: the tool's non-cutting parts (shank, holder)
 * entering the material, and any part (cutter included) entering a fixture.
 *
 * A part is a body of revolution at heights [z0, z1] above the tip. Its
 * swept volume along a move is the same body's sweep along the motion
 * shifted by z0 along the tool axis (swarf_sim_shift_motion). The material
 * "still there when the move runs" is the stock of the last removal pass
 * minus the sweeps queued since (not removed yet) and minus this move's own
 * cutter sweep (the flutes clear the way of a shank that follows them into
 * their hole): swarf_stock_penetrates takes them as volumes cut away, so no
 * batch is flushed for the check.
 *
 * A part collides when it penetrates by more than half a voxel
 * (swarf_stock_penetrates: the two signed depths add up to more). The depth
 * reported is how far the part would have to be lifted along the tool axis
 * to clear the material (bisection on the lift, to voxel/8), plus that
 * half voxel: for a holder face entering a flat face d mm, d.
 *
 * Cost: a part is only looked at when its sweep's bounds reach the material
 * box (or the fixture's); the check of a move is one read-only pass over the
 * blocks of the part's bounds, and the bisection runs only on a hit, once per
 * source line and kind (the alarm is reported once per line).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sim_private.h"

/* CPU seconds of this thread (the check runs in the caller's thread): what
 * the check costs, whatever else the machine is doing. */
static double seconds_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

int swarf_sim_shift_motion(const swarf_motion *m, double dz, swarf_motion *out) {
  *out = *m;
  if (m->kind == SWARF_MOTION_RIGID && m->tcp) return -1; /* not a shift of the path */
  out->p0[2] += dz;
  out->p1[2] += dz;
  out->center[2] += dz;
  return 0;
}

/* ---- One part along one move ---------------------------------------------- */

typedef struct {
  swarf_cutter body;
  swarf_motion motion;
  swarf_sweep sweep;
  double lo[3], hi[3];
} part_sweep;

/* The sweep of a body of revolution from z0 to z1 above the tip (diameters
 * d0 at z0, d1 at z1), lifted by `lift` along the tool axis, along m. A
 * cylinder on a motion that can be shifted is a flat cutter on the shifted
 * motion (the closed forms); anything else (a cone, a motion in TCP mode) a
 * profile body at its height (engine.h: swarf_cutter_add_frustum) on m
 * itself. -1 if the body cannot be built. */
static int part_sweep_init(part_sweep *ps, double z0, double z1, double d0, double d1, double lift,
                           const swarf_motion *m, double voxel) {
  swarf_error err;
  if (d0 == d1 && swarf_sim_shift_motion(m, z0 + lift, &ps->motion) == 0) {
    if (swarf_cutter_init(&ps->body, SWARF_CUTTER_FLAT, d0, 0, z1 - z0, &err) != SWARF_OK)
      return -1;
  } else {
    ps->motion = *m;
    swarf_cutter_begin(&ps->body);
    if (swarf_cutter_add_frustum(&ps->body, z0 + lift, 0.5 * d0, z1 + lift, 0.5 * d1, &err) !=
            SWARF_OK ||
        swarf_cutter_finish(&ps->body, &err) != SWARF_OK)
      return -1;
  }
  swarf_sweep_init_voxel(&ps->sweep, &ps->body, &ps->motion, voxel);
  swarf_sweep_bounds(&ps->sweep, ps->lo, ps->hi);
  return 0;
}

/* The cutter's own sweep, lifted along the tool axis (by shifting the
 * motion; -1 when the motion cannot be shifted and lift is not 0). */
static int cutter_sweep_init(part_sweep *ps, const swarf_cutter *c, double lift,
                             const swarf_motion *m, double voxel) {
  if (lift == 0)
    ps->motion = *m;
  else if (swarf_sim_shift_motion(m, lift, &ps->motion) != 0)
    return -1;
  ps->body = *c;
  swarf_sweep_init_voxel(&ps->sweep, &ps->body, &ps->motion, voxel);
  swarf_sweep_bounds(&ps->sweep, ps->lo, ps->hi);
  return 0;
}

static int boxes_meet(const double alo[3], const double ahi[3], const double blo[3],
                      const double bhi[3]) {
  for (int k = 0; k < 3; k++)
    if (ahi[k] < blo[k] || alo[k] > bhi[k]) return 0;
  return 1;
}

static double sweep_sdf(const void *ctx, double x, double y, double z) {
  const double p[3] = {x, y, z};
  return swarf_sweep_sdf((const swarf_sweep *)ctx, p, NULL);
}

/* What one check looks at: the body, where it starts, the grid it enters
 * and the sweeps clearing that grid's material. */
typedef struct {
  swarf_sim *s;
  const swarf_stock *grid;
  double z0, z1, d0, d1;      /* the body (part_sweep_init) ... */
  const swarf_cutter *cutter; /* ... or, when not NULL, the cutter itself */
  const swarf_motion *m;
  const swarf_stock_cut *clear; /* the volumes cut away but not removed yet */
  int nclear;
  double lmax; /* a lift that certainly clears the grid's box */
} part_check;

/* Does the part, lifted by `lift`, penetrate the grid by more than half a
 * voxel? 1 yes, 0 no, -1 failed (after swarf_sim_fail), -2 it cannot be
 * lifted on this motion. */
static int penetrates_at(const part_check *pc, double lift, double where[3]) {
  part_sweep ps;
  swarf_error err;
  int hit = 0;
  if (pc->cutter != NULL) {
    if (cutter_sweep_init(&ps, pc->cutter, lift, pc->m, pc->s->cfg.voxel) != 0) return -2;
  } else if (part_sweep_init(&ps, pc->z0, pc->z1, pc->d0, pc->d1, lift, pc->m, pc->s->cfg.voxel) !=
             0) {
    return -2;
  }
  swarf_stock_cut cut = {{ps.lo[0], ps.lo[1], ps.lo[2]},
                         {ps.hi[0], ps.hi[1], ps.hi[2]},
                         sweep_sdf,
                         &ps.sweep,
                         NULL,
                         NULL};
  const double h = 0.5 * swarf_stock_voxel(pc->grid);
  if (swarf_stock_penetrates(pc->grid, &cut, pc->clear, (size_t)pc->nclear, h, &hit, where, &err) !=
      SWARF_OK) {
    swarf_sim_fail(pc->s, err.status, pc->m->line, pc->m->column, "%s", err.message);
    return -1;
  }
  /* the material is split among processes (slab.c); fixtures are whole */
  if (pc->grid == pc->s->stock && swarf_sim_slab_hit(pc->s, &hit, where) != 0) return -1;
  return hit;
}

/* The lift that clears a part found penetrating at lift 0, plus half a
 * voxel; NaN when it cannot be measured (-2 above) or after a failure.
 * Bisection between 0 (in) and lmax (a lift that clears the grid's box for
 * sure) to voxel/8: each step not in is a pass over the part's blocks. */
static double clearing_depth(const part_check *pc) {
  const double v = swarf_stock_voxel(pc->grid), h = 0.5 * v;
  double lo = 0, hi = pc->lmax, where[3];
  while (hi - lo > v / 8) {
    const double mid = 0.5 * (lo + hi);
    const int r = penetrates_at(pc, mid, where);
    if (r < 0) return NAN;
    if (r)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi) + h;
}

/* A lift that certainly clears the box [lo, hi] of a part whose sweep's
 * bounds are plo..phi: straight up past the box's top when the tool axis is
 * the z axis throughout, else the box's diagonal plus the part's extent. */
static double lift_bound(const swarf_motion *m, const double lo[3], const double hi[3],
                         const double plo[3], const double phi[3]) {
  if (m->kind != SWARF_MOTION_RIGID) return fmax(hi[2] - plo[2], 0) + 1e-3;
  return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
              (hi[2] - lo[2]) * (hi[2] - lo[2])) +
         (phi[0] - plo[0]) + (phi[1] - plo[1]) + (phi[2] - plo[2]);
}

/* The depth, unless the config's limit of measured collisions of that kind
 * is reached (then NaN: "not measured"). */
static double measured_depth(const part_check *pc, swarf_alarm_kind kind) {
  swarf_sim_collide *c = &pc->s->col;
  const long limit = pc->s->cfg.collision_depths;
  if (limit > 0 && c->measured[kind] >= limit) return NAN;
  c->measured[kind]++;
  return clearing_depth(pc);
}

/* ---- The material --------------------------------------------------------- */

/* This move's sweep and the queued ones whose bounds meet [lo, hi], newest
 * first (the likeliest to have cleared the part's way: the check stops at
 * the first that did). */
static int clearing_sweeps(swarf_sim *s, const swarf_stock_cut *own, const double lo[3],
                           const double hi[3]) {
  swarf_sim_collide *c = &s->col;
  int n = 0;
  if (own != NULL && boxes_meet(own->lo, own->hi, lo, hi)) c->clear[n++] = *own;
  for (int i = s->n - 1; i >= 0; i--)
    if (boxes_meet(s->cuts[i].lo, s->cuts[i].hi, lo, hi)) c->clear[n++] = s->cuts[i];
  return n;
}

static void raise_collision(swarf_sim *s, const swarf_motion *m, swarf_alarm_kind kind, int index,
                            int part, double depth, const double where[3]) {
  swarf_alarm a;
  memset(&a, 0, sizeof a);
  a.kind = kind;
  a.line = m->line;
  a.column = m->column;
  a.tool = s->tool->number;
  a.depth = depth;
  memcpy(a.at, where, sizeof a.at);
  a.index = index;
  a.part = part;
  s->rep.collisions++;
  swarf_sim_raise(s, &a);
}

/* The shank or the holder's pieces (parts[0..n) of one kind) against the
 * material; one alarm with the deepest piece. */
static int material_kind(swarf_sim *s, const swarf_motion *m, const swarf_stock_cut *own,
                         const swarf_sim_part *parts, int n, swarf_alarm_kind kind) {
  swarf_sim_collide *c = &s->col;
  double deepest = -1, at[3] = {NAN, NAN, NAN};
  int found = 0;
  for (int i = 0; i < n; i++) {
    const swarf_sim_part *q = &parts[i];
    part_sweep ps;
    double where[3];
    if (q->kind != kind) continue;
    if (part_sweep_init(&ps, q->z0, q->z1, q->d0, q->d1, 0, m, s->cfg.voxel) != 0 ||
        !boxes_meet(ps.lo, ps.hi, s->pad_lo, s->pad_hi))
      continue;
    c->checked++;
    part_check pc = {s,
                     s->stock,
                     q->z0,
                     q->z1,
                     q->d0,
                     q->d1,
                     NULL,
                     m,
                     c->clear,
                     clearing_sweeps(s, own, ps.lo, ps.hi),
                     lift_bound(m, s->pad_lo, s->pad_hi, ps.lo, ps.hi)};
    int r = penetrates_at(&pc, 0, where);
    if (r == -1) return 1;
    if (r != 1) continue;
    double d = measured_depth(&pc, kind);
    if (s->err.status != SWARF_OK) return 1;
    if (!found || d > deepest || isnan(d)) deepest = d, memcpy(at, where, sizeof at);
    found = 1;
  }
  if (!found) return 0;
  c->last_line[kind == SWARF_ALARM_SHANK ? 0 : 1] = m->line;
  raise_collision(s, m, kind, 0, kind == SWARF_ALARM_SHANK ? 1 : 2, deepest, at);
  return 0;
}

/* ---- Fixtures ------------------------------------------------------------- */

/* A part (part: 1 shank, 2 holder; q) or the cutter (part 0, cutter)
 * against fixture f. */
static int fixture_part(swarf_sim *s, const swarf_motion *m, int f, const swarf_sim_part *q,
                        const swarf_cutter *cutter, int part) {
  swarf_sim_collide *c = &s->col;
  const swarf_sim_fixture *fx = &s->cfg.fixtures[f];
  part_sweep ps;
  double where[3];
  if (c->fixture_line[f][part] == m->line) return 0;
  int built = cutter != NULL ? cutter_sweep_init(&ps, cutter, 0, m, s->cfg.voxel)
                             : part_sweep_init(&ps, q->z0, q->z1, q->d0, q->d1, 0, m, s->cfg.voxel);
  if (built != 0 || !boxes_meet(ps.lo, ps.hi, fx->lo, fx->hi)) return 0;
  c->checked++;
  part_check pc = {s,
                   c->fixture[f],
                   0,
                   0,
                   0,
                   0,
                   cutter,
                   m,
                   NULL,
                   0,
                   lift_bound(m, fx->lo, fx->hi, ps.lo, ps.hi)};
  if (q != NULL) pc.z0 = q->z0, pc.z1 = q->z1, pc.d0 = q->d0, pc.d1 = q->d1;
  int r = penetrates_at(&pc, 0, where);
  if (r == -1) return 1;
  if (r != 1) return 0;
  double d = measured_depth(&pc, SWARF_ALARM_FIXTURE);
  if (s->err.status != SWARF_OK) return 1;
  c->fixture_line[f][part] = m->line;
  raise_collision(s, m, SWARF_ALARM_FIXTURE, f + 1, part, d, where);
  return 0;
}

static int fixtures(swarf_sim *s, const swarf_motion *m, const swarf_sim_part *parts, int n) {
  for (int f = 0; f < s->cfg.nfixtures; f++) {
    if (fixture_part(s, m, f, NULL, &s->tool->cutter, 0) != 0) return 1;
    for (int i = 0; i < n; i++)
      if (fixture_part(s, m, f, &parts[i], NULL, parts[i].kind == SWARF_ALARM_SHANK ? 1 : 2))
        return 1;
  }
  return 0;
}

/* ---- The driver's calls --------------------------------------------------- */

/* Fixture f's level set at the stock's voxel: its box, or its STL mesh
 * (whose bounds become the fixture's lo, hi); the path is dropped after (the
 * caller's string is borrowed only until swarf_sim_new returns). */
static int fixture_init(swarf_sim *s, int f) {
  swarf_sim_fixture *fx = &s->cfg.fixtures[f];
  double voxel = swarf_stock_voxel(s->stock);
  int hw = swarf_stock_half_width(s->stock);
  swarf_error e;
  swarf_status st = fx->stl != NULL
                        ? swarf_stock_read_stl(fx->stl, NULL, voxel, hw, &s->col.fixture[f], &e)
                        : swarf_stock_new_box(fx->lo, fx->hi, voxel, hw, &s->col.fixture[f], &e);
  if (st != SWARF_OK) {
    char msg[sizeof e.message];
    swarf_error_format(&e, msg, sizeof msg); /* the STL's name, then what */
    swarf_sim_fail(s, e.status, 0, 0, "fixture %d: %s", f + 1, msg);
    return 1;
  }
  if (fx->stl != NULL) swarf_stock_bounds(s->col.fixture[f], fx->lo, fx->hi);
  fx->stl = NULL;
  return 0;
}

int swarf_sim_collide_init(swarf_sim *s) {
  swarf_sim_collide *c = &s->col;
  memset(c, 0, sizeof *c);
  c->last_line[0] = c->last_line[1] = -1;
  for (int f = 0; f < SWARF_SIM_MAX_FIXTURES; f++)
    for (int p = 0; p < 3; p++)
      c->fixture_line[f][p] = -1;
  c->clear = malloc(sizeof *c->clear * (size_t)(s->cap + 1));
  if (c->clear == NULL) return -1;
  for (int f = 0; f < s->cfg.nfixtures; f++)
    if (fixture_init(s, f) != 0) return 1;
  return 0;
}

void swarf_sim_collide_clear(swarf_sim *s) {
  free(s->col.clear);
  for (int f = 0; f < SWARF_SIM_MAX_FIXTURES; f++)
    swarf_stock_free(s->col.fixture[f]);
  memset(&s->col, 0, sizeof s->col);
}

int swarf_sim_collide_move(swarf_sim *s, const swarf_motion *m, const swarf_sweep *w,
                           const swarf_stock_cut *own) {
  swarf_sim_part parts[SWARF_SIM_MAX_PARTS];
  int n = swarf_sim_tool_parts(s->tool, parts), rc = 0;
  (void)w;
  if (n == 0 && s->cfg.nfixtures == 0) return 0; /* nothing to check (nor a clock to read) */
  const double t0 = seconds_now();
  if (n > 0 && s->col.last_line[0] != m->line)
    rc = material_kind(s, m, own, parts, n, SWARF_ALARM_SHANK);
  if (rc == 0 && n > 0 && s->col.last_line[1] != m->line)
    rc = material_kind(s, m, own, parts, n, SWARF_ALARM_HOLDER);
  if (rc == 0) rc = fixtures(s, m, parts, n);
  s->rep.collision_s += seconds_now() - t0;
  return rc;
}
