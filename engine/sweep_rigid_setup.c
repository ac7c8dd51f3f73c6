/* sweep_rigid_setup.c -- per-move constants of a rigid sweep (sweep_rigid.c):
 * bounds of the speeds |v|, |omega| and of their derivatives, the number of
 * time steps, and the swept volume's bounding box.
 *
 * The bounds come from PROBE poses spread evenly over the move, with safety
 * factors: the motions of rotary machines are trigonometric polynomials of
 * low degree in alpha whose derivatives vary by O(turn) between probes, so
 * 64 probes and a factor 1.25 (1.5 on the derivatives) cover them for any
 * turn a single move makes (tested, tests/engine/test_sweep_rigid.c).
 */
#include <math.h>
#include <string.h>

#include "engine_private.h"

#define PROBE 64
#define MAXN 512

static double norm3(const double a[3]) {
  return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

static double dist3(const double a[3], const double b[3]) {
  const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return norm3(d);
}

/* Widen the box by the cutter's axis segment at the pose (t, U). */
static void include_pose(double *x, const swarf_cutter *c, const double t[3], const double U[9]) {
  for (int k = 0; k < 3; k++) {
    double top = t[k] + c->length * U[3 * k + 2];
    x[RG_LO + k] = fmin(x[RG_LO + k], fmin(t[k], top));
    x[RG_HI + k] = fmax(x[RG_HI + k], fmax(t[k], top));
  }
}

void swarf_sweep_rigid_init(swarf_sweep *s, double voxel) {
  const swarf_cutter *c = s->cutter;
  double *x = s->aux, t[3], U[9], v[3], w[3], pv[3] = {0}, pw[3] = {0};
  double r = 0.5 * c->diameter, reach = hypot(r, c->length), tol = 0.1 * voxel;
  double V = 0, W = 0, VD = 0, WD = 0, step, travel, pad;
  s->method = SWARF_SWEEP_RIGID;
  for (int k = 0; k < 3; k++)
    x[RG_LO + k] = INFINITY, x[RG_HI + k] = -INFINITY;
  for (int i = 0; i <= PROBE; i++) {
    double a = (double)i / PROBE;
    swarf_motion_eval(s->motion, a, t, U);
    swarf_motion_velocity(s->motion, a, NULL, v, w);
    include_pose(x, c, t, U);
    V = fmax(V, norm3(v));
    W = fmax(W, norm3(w));
    if (i > 0) VD = fmax(VD, dist3(v, pv) * PROBE), WD = fmax(WD, dist3(w, pw) * PROBE);
    memcpy(pv, v, sizeof v);
    memcpy(pw, w, sizeof w);
  }
  x[RG_V] = 1.25 * V + 1e-12;
  x[RG_W] = 1.25 * W;
  x[RG_VD] = 1.5 * VD + 1e-9 * V;
  x[RG_WD] = 1.5 * WD;
  travel = x[RG_V] + x[RG_W] * reach; /* mm per unit alpha, any cutter point */
  step = sqrt(8.0 * r * tol);
  x[RG_N] = fmin(MAXN, fmax(2.0, ceil(travel / step)));
  x[RG_FAR] = 72.0 * voxel;
  pad = r + travel / PROBE;
  for (int k = 0; k < 3; k++)
    x[RG_LO + k] -= pad, x[RG_HI + k] += pad;
}

void swarf_sweep_rigid_bounds(const swarf_sweep *s, double lo[3], double hi[3]) {
  for (int k = 0; k < 3; k++)
    lo[k] = s->aux[RG_LO + k], hi[k] = s->aux[RG_HI + k];
}
