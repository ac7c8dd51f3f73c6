/* SPDX-License-Identifier: MPL-2.0 */
/* sweep_rigid_setup.c -- per-move constants of a rigid sweep (sweep_rigid.c):
 * bounds of the speeds |v|, |omega| and of their derivatives, the number of
 * time steps, and the swept volume's bounding box.
 *
 * The bounds come from PROBE poses spread evenly over the move, with safety
 * factors: the motions of rotary machines are trigonometric polynomials of
 * low degree in alpha whose derivatives vary by O(turn) between probes, so
 * 64 probes and a factor 1.25 (1.5 on the derivatives) cover them for any
 * turn a single move makes (tested, tests/engine/test_sweep_rigid.c).
 * A ball end mill's path (sweep_rigid_ball.c) gets the speed of the ball's
 * centre and its derivative from the same probes, with the same factors (a
 * flat or bull end mill: of its axis point at the corner radius).
 */
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "engine_private.h"
#include "swarf_reference.h"

#define PROBE 64
#define MAXN 512

static double norm3(const double a[3]) {
  return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

static double dist3(const double a[3], const double b[3]) {
  const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return norm3(d);
}

/* u = v + omega x (0, 0, R), the speed of the ball's centre in the cutter's
 * frame, and c' = U u in the workpiece's. */
static void centre_speed(const double U[9], const double v[3], const double w[3], double R,
                         double u[3], double cp[3]) {
  u[0] = v[0] + R * w[1], u[1] = v[1] - R * w[0], u[2] = v[2];
  for (int i = 0; i < 3; i++)
    cp[i] = U[3 * i] * u[0] + U[3 * i + 1] * u[1] + U[3 * i + 2] * u[2];
}

/* The ball path's constants (ball, cv, cvmin, ca, ck) from the
 * centre's speeds at the nprobe + 1 probes (u cutter frame, cp workpiece
 * frame) and the bounds already set. The centre: the ball's, or for a flat
 * or bull end mill (ball = 2) the start of its capsule's axis, the corner
 * radius R above the tip (sweep_rigid_ball.c). */
static void ball_init(swarf_sweep *s, const double (*u)[3], const double (*cp)[3], int nprobe) {
  const swarf_cutter *c = s->cutter;
  swarf_sweep_rigid *x = &swarf_sweep_data_of(s)->u.rigid;
  double R = c->corner_radius, vmax = 0.0, vmin = INFINITY, dmax = 0.0, kmax = 0.0, general;
  const int shape = c->shape;
  x->ball = 0;
  if (!c->fast || !(c->length >= 2.0 * R) || swarf_reference_on(SWARF_REFERENCE_SWEEP_GENERAL) ||
      (shape != SWARF_CUTTER_BALL && shape != SWARF_CUTTER_FLAT && shape != SWARF_CUTTER_BULL))
    return;
  for (int i = 0; i <= nprobe; i++) {
    double sp = norm3(cp[i]);
    vmax = fmax(vmax, sp), vmin = fmin(vmin, sp);
    kmax = fmax(kmax, fabs(u[i][2]));
    if (i > 0) dmax = fmax(dmax, dist3(cp[i], cp[i - 1]) * nprobe);
  }
  /* c'' = U (omega x (v + omega x r) + v' + omega' x r), r = (0, 0, R) */
  general = x->w * (x->v + x->w * R) + x->vd + x->wd * R;
  x->ca = fmin(general, 1.5 * dmax + 1e-9 * vmax);
  x->cv = fmin(x->v + x->w * R, 1.25 * vmax + 1e-12);
  /* between probes: |c''| <= ca, and u' = U^T c'' - omega x u */
  x->cvmin = fmax(vmin - 0.5 * x->ca / nprobe, 0.0);
  x->ck = kmax + 0.5 * (x->ca + x->w * x->cv) / nprobe;
  x->ball = shape == SWARF_CUTTER_BALL ? 1 : 2;
}

/* Widen the box by the cutter's axis segment at the pose (t, U). */
static void include_pose(swarf_sweep_rigid *x, const swarf_cutter *c, const double t[3],
                         const double U[9]) {
  for (int k = 0; k < 3; k++) {
    double top = t[k] + c->length * U[3 * k + 2];
    x->lo[k] = fmin(x->lo[k], fmin(t[k], top));
    x->hi[k] = fmax(x->hi[k], fmax(t[k], top));
  }
}

void swarf_sweep_rigid_init(swarf_sweep *s, double voxel) {
  const swarf_cutter *c = s->cutter;
  swarf_sweep_data *sd = swarf_sweep_data_of(s);
  swarf_sweep_rigid *x = &sd->u.rigid;
  double t[3], U[9], v[3], w[3], pv[3] = {0}, pw[3] = {0}, u[PROBE + 1][3], cp[PROBE + 1][3];
  double r = 0.5 * c->diameter, reach = hypot(r, c->length), tol = 0.1 * voxel;
  double V = 0, W = 0, VD = 0, WD = 0, step, travel, pad;
  static atomic_uint_fast64_t next_id;
  sd->method = SWARF_SWEEP_RIGID;
  x->id = atomic_fetch_add_explicit(&next_id, 1, memory_order_relaxed) + 1;
  for (int k = 0; k < 3; k++)
    x->lo[k] = INFINITY, x->hi[k] = -INFINITY;
  for (int i = 0; i <= PROBE; i++) {
    double a = (double)i / PROBE;
    swarf_motion_eval(s->motion, a, t, U);
    swarf_motion_velocity(s->motion, a, NULL, v, w);
    include_pose(x, c, t, U);
    centre_speed(U, v, w, c->corner_radius, u[i], cp[i]);
    V = fmax(V, norm3(v));
    W = fmax(W, norm3(w));
    if (i > 0) VD = fmax(VD, dist3(v, pv) * PROBE), WD = fmax(WD, dist3(w, pw) * PROBE);
    memcpy(pv, v, sizeof v);
    memcpy(pw, w, sizeof w);
  }
  x->v = 1.25 * V + 1e-12;
  x->w = 1.25 * W;
  x->vd = 1.5 * VD + 1e-9 * V;
  x->wd = 1.5 * WD;
  travel = x->v + x->w * reach; /* mm per unit alpha, any cutter point */
  step = sqrt(8.0 * r * tol);
  x->n = (int)fmin(MAXN, fmax(2.0, ceil(travel / step)));
  x->far = 72.0 * voxel;
  pad = r + travel / PROBE;
  for (int k = 0; k < 3; k++)
    x->lo[k] -= pad, x->hi[k] += pad;
  ball_init(s, (const double(*)[3])u, (const double(*)[3])cp, PROBE);
}

void swarf_sweep_rigid_bounds(const swarf_sweep *s, double lo[3], double hi[3]) {
  const swarf_sweep_rigid *x = &swarf_sweep_cdata(s)->u.rigid;
  for (int k = 0; k < 3; k++)
    lo[k] = x->lo[k], hi[k] = x->hi[k];
}
