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
  double t[3], U[9], v[3], w[3], pv[3] = {0}, pw[3] = {0};
  double r = 0.5 * c->diameter, reach = hypot(r, c->length), tol = 0.1 * voxel;
  double V = 0, W = 0, VD = 0, WD = 0, step, travel, pad;
  sd->method = SWARF_SWEEP_RIGID;
  for (int k = 0; k < 3; k++)
    x->lo[k] = INFINITY, x->hi[k] = -INFINITY;
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
}

void swarf_sweep_rigid_bounds(const swarf_sweep *s, double lo[3], double hi[3]) {
  const swarf_sweep_rigid *x = &swarf_sweep_cdata(s)->u.rigid;
  for (int k = 0; k < 3; k++)
    lo[k] = x->lo[k], hi[k] = x->hi[k];
}
