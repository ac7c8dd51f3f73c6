/* SPDX-License-Identifier: MPL-2.0 */
/* sweep.c -- the volume swept by a cutter over one move: choice of the
 * evaluator, bounds, dispatch, and the move's characteristic curves.
 *
 * A swarf_sweep is a value that points at a cutter and a motion owned by the
 * caller; init picks the evaluator (engine_private.h lists them) and stores
 * its per-move constants, typed per method (swarf_sweep_data). The evaluators live in sweep_line.c,
 * sweep_helix.c and (motions with rotation) sweep_rigid.c.
 */
#include <math.h>
#include <string.h>

#include "engine_private.h"

void swarf_sweep_init(swarf_sweep *s, const swarf_cutter *c, const swarf_motion *m) {
  swarf_sweep_init_voxel(s, c, m, 0.1);
}

void swarf_sweep_init_voxel(swarf_sweep *s, const swarf_cutter *c, const swarf_motion *m,
                            double voxel) {
  memset(s, 0, sizeof *s);
  s->cutter = c;
  s->motion = m;
  if (c == NULL || m == NULL) return;
  if (!c->fast)
    swarf_sweep_profile_init(s, voxel > 0 ? voxel : 0.1);
  else if (m->kind == SWARF_MOTION_RIGID)
    swarf_sweep_rigid_init(s, voxel > 0 ? voxel : 0.1);
  else if (m->kind == SWARF_MOTION_LINE)
    swarf_sweep_line_init(s, m->p0, m->p1);
  else
    swarf_sweep_helix_init(s);
}

void swarf_sweep_bounds(const swarf_sweep *s, double lo[3], double hi[3]) {
  double r = 0.5 * s->cutter->diameter;
  int method = swarf_sweep_cdata(s)->method;
  if (method == SWARF_SWEEP_RIGID || method == SWARF_SWEEP_P_RIGID ||
      method == SWARF_SWEEP_P_GENERAL) {
    swarf_sweep_rigid_bounds(s, lo, hi);
    return;
  }
  swarf_motion_bounds(s->motion, lo, hi);
  for (int k = 0; k < 2; k++) {
    lo[k] -= r;
    hi[k] += r;
  }
  lo[2] += s->cutter->zmin;
  hi[2] += s->cutter->length;
}

double swarf_sweep_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  int method = swarf_sweep_cdata(s)->method;
  if (method >= SWARF_SWEEP_P_SLOT) return swarf_sweep_profile_sdf(s, p, alpha);
  switch (method) {
  case SWARF_SWEEP_SLOT:
    return swarf_sweep_slot_sdf(s, p, alpha);
  case SWARF_SWEEP_RAMP_BALL:
    return swarf_sweep_ramp_ball_sdf(s, p, alpha);
  case SWARF_SWEEP_RAMP:
    return swarf_sweep_ramp_sdf(s, p, alpha);
  case SWARF_SWEEP_ARC:
    return swarf_sweep_arc_sdf(s, p, alpha);
  case SWARF_SWEEP_RING:
    return swarf_sweep_ring_sdf(s, p, alpha);
  case SWARF_SWEEP_HELIX:
    return swarf_sweep_helix_sdf(s, p, alpha);
  case SWARF_SWEEP_RIGID:
    return swarf_sweep_rigid_sdf(s, p, alpha);
  default: /* SWARF_SWEEP_PLUNGE */
    return swarf_sweep_plunge_sdf(s, p, alpha);
  }
}

double swarf_sweep_sdf_range(const swarf_sweep *s, const double p[3], double lo, double hi) {
  if (swarf_sweep_cdata(s)->method == SWARF_SWEEP_RIGID)
    return swarf_sweep_rigid_sdf_range(s, p, lo, hi);
  return swarf_sweep_sdf(s, p, NULL);
}

int swarf_sweep_range_plane(const swarf_sweep *s, const double p[3], double lo, double hi, double r,
                            double *d, double *pd, double g[3]) {
  if (swarf_sweep_cdata(s)->method == SWARF_SWEEP_RIGID)
    return swarf_sweep_rigid_range_plane(s, p, lo, hi, r, d, pd, g);
  *d = swarf_sweep_sdf(s, p, NULL);
  return 0;
}

int swarf_sweep_support(const swarf_sweep *s, const double p[3], double *d, double g[3]) {
  int method = swarf_sweep_cdata(s)->method;
  if (method == SWARF_SWEEP_SLOT || method == SWARF_SWEEP_RAMP || method == SWARF_SWEEP_RAMP_BALL ||
      method == SWARF_SWEEP_PLUNGE)
    return swarf_sweep_line_support(s, p, d, g);
  *d = swarf_sweep_sdf(s, p, NULL);
  return 0;
}

swarf_status swarf_sweep_char_curve(const swarf_sweep *s, double alpha, double tol,
                                    swarf_char_curve *cc) {
  double t[3], U[9], tdot[3], v[3], omega[3];
  if (s == NULL || s->cutter == NULL || s->motion == NULL || cc == NULL) return SWARF_ERR_ARG;
  swarf_motion_eval(s->motion, alpha, t, U);
  swarf_motion_velocity(s->motion, alpha, tdot, v, omega);
  return swarf_char_curve_compute(cc, s->cutter, t, U, v, omega, tol);
}
