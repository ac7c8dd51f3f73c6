/* SPDX-License-Identifier: MPL-2.0 */
/* sweep_profile.c -- swept volumes of profile cutters (every cutter but the
 * flat/ball/bull closed forms): a union of convex pieces, each swept on its
 * own, the sdf the minimum over the pieces (exact outside; inside the
 * deepest piece-instance, never deeper than the truth).
 *
 * Per convex piece K (a convex body of revolution, so its 2-D sdf grows with
 * the distance to the axis at every height):
 *   slot   (horizontal line): the nearest instance is the one level with p
 *          at the horizontal distance u from the path: S_K(u, z); exact.
 *   plunge (vertical line): K + [0, dz] e_z is the hull with its upper chain
 *          raised by dz (profile.c); exact. A QSS piece: as a ramp.
 *   ramp   (other line): g(a) = S_K(p - t(a)) is convex in a (a convex
 *          function of an affine map): regula falsi on g' with the tangent
 *          lines at the bracket ends as a certified lower bound, to 1e-10 mm.
 *   arcs about a vertical axis: sweep_helix.c (the same monotonicity).
 *   helix: sweep_sampled.c per piece (semiconvex: g'' >= -|t''|).
 *   rigid: sweep_rigid.c per piece.
 * A non-convex QSS piece has none of these: sweep_general.c for any motion.
 * Lines keep swarf_sweep_pline (engine_private.h). Pure functions.
 */
#include <math.h>
#include <string.h>

#include "engine_private.h"

#define RAMP_EPS 1e-10 /* certified accuracy of the ramp's 1-D minimum, mm */
#define RAMP_ITERS 80

static int has_general(const swarf_cutter *c) {
  for (int i = 0; i < c->npieces; i++)
    if (!c->piece[i].convex) return 1;
  return 0;
}

static void line_init(swarf_sweep *s, const double p0[3], const double p1[3]) {
  swarf_sweep_data *sd = swarf_sweep_data_of(s);
  swarf_sweep_pline *x = &sd->u.pline;
  double d[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, h2 = d[0] * d[0] + d[1] * d[1];
  for (int k = 0; k < 3; k++)
    x->p0[k] = p0[k], x->d[k] = d[k];
  x->inv_h2 = h2 > 0.0 ? 1.0 / h2 : 0.0;
  sd->method = h2 == 0.0     ? SWARF_SWEEP_P_PLUNGE
               : d[2] == 0.0 ? SWARF_SWEEP_P_SLOT
                             : SWARF_SWEEP_P_RAMP;
}

void swarf_sweep_profile_init(swarf_sweep *s, double voxel) {
  const swarf_motion *m = s->motion;
  if (has_general(s->cutter)) {
    swarf_sweep_rigid_init(s, voxel);
    swarf_sweep_data_of(s)->method = SWARF_SWEEP_P_GENERAL;
  } else if (m->kind == SWARF_MOTION_RIGID) {
    swarf_sweep_rigid_init(s, voxel);
    swarf_sweep_data_of(s)->method = SWARF_SWEEP_P_RIGID;
  } else if (m->kind == SWARF_MOTION_LINE) {
    line_init(s, m->p0, m->p1);
  } else {
    swarf_sweep_helix_init(s);
    swarf_sweep_data *sd = swarf_sweep_data_of(s);
    if (sd->method == SWARF_SWEEP_HELIX)
      sd->method = SWARF_SWEEP_P_HELIX;
    else if (sd->method != SWARF_SWEEP_ARC && sd->method != SWARF_SWEEP_RING)
      line_init(s, m->p0, m->p1); /* a degenerate arc */
  }
}

static double piece_body(const void *ctx, const double q[3], double grad[3]) {
  return swarf_profile_piece_sdf_grad((const swarf_profile_piece *)ctx, q, grad);
}

/* ---- lines ------------------------------------------------------------------ */

static double slot_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  const swarf_sweep_pline *x = &swarf_sweep_cdata(s)->u.pline;
  double wx = p[0] - x->p0[0], wy = p[1] - x->p0[1];
  double t = (wx * x->d[0] + wy * x->d[1]) * x->inv_h2, ex, ey;
  t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
  ex = wx - t * x->d[0], ey = wy - t * x->d[1];
  if (alpha != NULL) *alpha = t;
  return swarf_cutter_sdf2(s->cutter, sqrt(ex * ex + ey * ey), p[2] - x->p0[2], NULL);
}

typedef struct {
  double a, g, dg;
} lsample;

static lsample ramp_at(const swarf_profile_piece *pc, const double q0[3], const double d[3],
                       double a) {
  double q[3] = {q0[0] - a * d[0], q0[1] - a * d[1], q0[2] - a * d[2]}, gr[3];
  lsample r;
  r.a = a;
  r.g = swarf_profile_piece_sdf_grad(pc, q, gr);
  r.dg = -(gr[0] * d[0] + gr[1] * d[1] + gr[2] * d[2]);
  return r;
}

/* Lower bound of the convex g on [lo.a, hi.a] (lo.dg < 0 < hi.dg): where
 * the tangent lines at the two ends meet. */
static double tangent_bound(const lsample *lo, const lsample *hi) {
  double den = lo->dg - hi->dg, x;
  if (!(den < 0.0)) return fmin(lo->g, hi->g);
  x = (hi->g - hi->dg * (hi->a - lo->a) - lo->g) / den;
  x = x < 0.0 ? 0.0 : x > hi->a - lo->a ? hi->a - lo->a : x;
  return lo->g + lo->dg * x;
}

/* min over a in [0, 1] of S_K(q0 - a d) for a convex piece K, or a value
 * >= upper when it cannot be below upper. */
static double ramp_piece(const swarf_profile_piece *pc, const double q0[3], const double d[3],
                         double upper, double *alpha) {
  lsample lo = ramp_at(pc, q0, d, 0.0), hi, best;
  double flo, fhi;
  int side = 0;
  if (lo.dg >= 0.0) return *alpha = 0.0, lo.g;
  hi = ramp_at(pc, q0, d, 1.0);
  if (hi.dg <= 0.0) return *alpha = 1.0, hi.g;
  best = lo.g <= hi.g ? lo : hi;
  flo = lo.dg, fhi = hi.dg;
  for (int it = 0; it < RAMP_ITERS; it++) {
    double lb = tangent_bound(&lo, &hi), a;
    lsample m;
    if (lb >= upper || best.g - lb <= RAMP_EPS || hi.a - lo.a <= 1e-15) break;
    a = (lo.a * fhi - hi.a * flo) / (fhi - flo);
    if (!(a > lo.a && a < hi.a)) a = 0.5 * (lo.a + hi.a);
    m = ramp_at(pc, q0, d, a);
    if (m.g < best.g) best = m;
    if (m.dg == 0.0) break;
    if (m.dg < 0.0) {
      lo = m, flo = m.dg;
      if (side < 0) fhi *= 0.5;
      side = -1;
    } else {
      hi = m, fhi = m.dg;
      if (side > 0) flo *= 0.5;
      side = 1;
    }
  }
  *alpha = best.a;
  return best.g;
}

static double ramp_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  const swarf_cutter *c = s->cutter;
  const swarf_sweep_pline *x = &swarf_sweep_cdata(s)->u.pline;
  double q0[3] = {p[0] - x->p0[0], p[1] - x->p0[1], p[2] - x->p0[2]}, best = INFINITY, ab = 0;
  for (int i = 0; i < c->npieces; i++) {
    double a, g = ramp_piece(&c->piece[i], q0, x->d, best, &a);
    if (g < best) best = g, ab = a;
  }
  if (alpha != NULL) *alpha = ab;
  return best;
}

/* Vertical: hulls swept up (exact closed form), QSS pieces minimised. */
static double plunge_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  const swarf_cutter *c = s->cutter;
  const swarf_sweep_pline *x = &swarf_sweep_cdata(s)->u.pline;
  double dz = x->d[2], zlo = x->p0[2] + fmin(dz, 0.0), r, best = INFINITY;
  if (alpha != NULL) return ramp_sdf(s, p, alpha); /* the nearest instance wanted too */
  r = hypot(p[0] - x->p0[0], p[1] - x->p0[1]);
  for (int i = 0; i < c->npieces; i++) {
    const swarf_profile_piece *pc = &c->piece[i];
    double g, a;
    if (pc->kind == SWARF_PIECE_HULL) {
      g = swarf_profile_hull_sdf(pc, r, p[2] - zlo, fabs(dz), NULL);
    } else {
      double q0[3] = {p[0] - x->p0[0], p[1] - x->p0[1], p[2] - x->p0[2]};
      g = ramp_piece(pc, q0, x->d, best, &a);
    }
    if (g < best) best = g;
  }
  return best;
}

/* ---- helices and rigid motions: per piece, pruned by the best so far ------ */

static double helix_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  const swarf_cutter *c = s->cutter;
  double best = INFINITY, ab = 0.0;
  for (int i = 0; i < c->npieces; i++) {
    double a = 0.0, g = swarf_sweep_helix_body_sdf(s, piece_body, &c->piece[i], p, best, &a);
    if (g < best) best = g, ab = a;
  }
  if (alpha != NULL) *alpha = ab;
  return best;
}

static double rigid_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  const swarf_cutter *c = s->cutter;
  double best = INFINITY, ab = 0.0;
  for (int i = 0; i < c->npieces; i++) {
    double a = 0.0, g = swarf_sweep_rigid_body_below(s, piece_body, &c->piece[i], p, best, &a);
    if (g < best) best = g, ab = a;
  }
  if (alpha != NULL) *alpha = ab;
  return best;
}

double swarf_sweep_profile_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  switch (swarf_sweep_cdata(s)->method) {
  case SWARF_SWEEP_P_SLOT:
    return slot_sdf(s, p, alpha);
  case SWARF_SWEEP_P_PLUNGE:
    return plunge_sdf(s, p, alpha);
  case SWARF_SWEEP_P_RAMP:
    return ramp_sdf(s, p, alpha);
  case SWARF_SWEEP_P_HELIX:
    return helix_sdf(s, p, alpha);
  case SWARF_SWEEP_P_GENERAL:
    return swarf_sweep_general_sdf(s, p, alpha);
  default: /* SWARF_SWEEP_P_RIGID */
    return rigid_sdf(s, p, alpha);
  }
}
