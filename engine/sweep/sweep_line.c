/* SPDX-License-Identifier: MPL-2.0 */
/* sweep_line.c -- swept volumes of straight moves, in closed form.
 *
 * The cutter is C + B(R) with C the cylinder {r <= a, z in [R, L - R]}, so
 * its sweep along the segment S is (C + S) + B(R) and the sdf is the distance
 * to C + S minus R. C + S is:
 *   slot   (horizontal S): a stadium prism        -> 2D box formula, exact;
 *   plunge (vertical S):   a longer cylinder      -> 2D box formula, exact;
 *   ramp, ball (a = 0):    a planar parallelogram -> piecewise quadratic, exact;
 *   ramp, a > 0: disk(a) + parallelogram: the distance is the minimum over the
 *     tip offset u of a convex C1 function, found by safeguarded Newton; exact
 *     outside; inside, the depth of the deepest single instance (a lower bound
 *     of the true depth, exact near the surface to second order).
 * The per-method data (engine_private.h) is set by swarf_sweep_line_init.
 */
#include <math.h>

#include "engine_private.h"

static double clamp(double x, double lo, double hi) {
  return x < lo ? lo : x > hi ? hi : x;
}

/* fmin and fmax for numbers (no NaN reaches them): inline, where libm's are calls. */
static double min2(double a, double b) {
  return b < a ? b : a;
}
static double max2(double a, double b) {
  return b > a ? b : a;
}

static void plunge_init(swarf_sweep *s, const double p0[3], const double p1[3]) {
  const swarf_cutter *c = s->cutter;
  swarf_sweep_data *sd = swarf_sweep_data_of(s);
  swarf_sweep_plunge *x = &sd->u.plunge;
  double zlo = fmin(p0[2], p1[2]), zhi = fmax(p0[2], p1[2]), dz = p1[2] - p0[2];
  sd->method = SWARF_SWEEP_PLUNGE;
  x->x = p0[0];
  x->y = p0[1];
  x->mid = 0.5 * (zlo + zhi + c->length);
  x->half = 0.5 * (zhi - zlo + c->length) - c->corner_radius;
  x->z0 = p0[2];
  x->inv_dz = dz != 0.0 ? 1.0 / dz : 0.0;
  x->zlo = zlo;
  x->zhi = zhi;
}

static void slot_init(swarf_sweep *s, const double p0[3], const double d[3], double U) {
  swarf_sweep_data *sd = swarf_sweep_data_of(s);
  swarf_sweep_slot *x = &sd->u.slot;
  sd->method = SWARF_SWEEP_SLOT;
  for (int k = 0; k < 3; k++)
    x->p0[k] = p0[k];
  x->d[0] = d[0];
  x->d[1] = d[1];
  x->inv_len2 = 1.0 / (U * U);
}

void swarf_sweep_line_init(swarf_sweep *s, const double p0[3], const double p1[3]) {
  const swarf_cutter *c = s->cutter;
  swarf_sweep_data *sd = swarf_sweep_data_of(s);
  swarf_sweep_ramp *x = &sd->u.ramp;
  double d[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  double U = sqrt(d[0] * d[0] + d[1] * d[1]);
  if (d[0] == 0.0 && d[1] == 0.0) {
    plunge_init(s, p0, p1);
    return;
  }
  if (d[2] == 0.0) {
    slot_init(s, p0, d, U);
    return;
  }
  sd->method = swarf_cutter_core(c) > 0.0 ? SWARF_SWEEP_RAMP : SWARF_SWEEP_RAMP_BALL;
  for (int k = 0; k < 3; k++)
    x->p0[k] = p0[k];
  x->core_mid = 0.5 * c->length;
  x->core_half = 0.5 * c->length - c->corner_radius;
  x->e[0] = d[0] / U;
  x->e[1] = d[1] / U;
  x->len = U;
  x->k = d[2] / U;
  x->core = swarf_cutter_core(c);
  x->w = 1.0 / (1.0 + x->k * x->k);
}

double swarf_sweep_slot_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  const swarf_sweep_slot *x = &swarf_sweep_cdata(s)->u.slot;
  double wx = p[0] - x->p0[0], wy = p[1] - x->p0[1];
  double t = clamp((wx * x->d[0] + wy * x->d[1]) * x->inv_len2, 0.0, 1.0);
  double ex = wx - t * x->d[0], ey = wy - t * x->d[1];
  if (alpha != NULL) *alpha = t;
  return swarf_cutter_sdf_rz(s->cutter, sqrt(ex * ex + ey * ey), p[2] - x->p0[2]);
}

double swarf_sweep_plunge_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  const swarf_sweep_plunge *x = &swarf_sweep_cdata(s)->u.plunge;
  const swarf_cutter *c = s->cutter;
  double ex = p[0] - x->x, ey = p[1] - x->y, r = sqrt(ex * ex + ey * ey);
  double d = swarf_box2(r - swarf_cutter_core(c), fabs(p[2] - x->mid) - x->half) - c->corner_radius;
  /* Every instance level with p is nearest to a point beside the side: pick
   * the one whose lower rim is at p's height (the rims are the curve). */
  double lift = d > 0.0 ? c->corner_radius : 0.5 * c->length;
  if (alpha != NULL) *alpha = (clamp(p[2] - lift, x->zlo, x->zhi) - x->z0) * x->inv_dz;
  return d;
}

/* p in the ramp's frame: along e (xi), across (eta), height above the tip
 * minus the core middle (zp). */
typedef struct {
  double xi, eta, zp, k, hh, a, U;
} ramp_point;

static void ramp_frame(const swarf_sweep *s, const double p[3], ramp_point *rp) {
  const swarf_sweep_ramp *x = &swarf_sweep_cdata(s)->u.ramp;
  double wx = p[0] - x->p0[0], wy = p[1] - x->p0[1];
  rp->xi = wx * x->e[0] + wy * x->e[1];
  rp->eta = wy * x->e[0] - wx * x->e[1];
  rp->zp = p[2] - x->p0[2] - x->core_mid;
  rp->k = x->k;
  rp->hh = x->core_half;
  rp->a = x->core;
  rp->U = x->len;
}

/* Ball cutter: squared distance to the parallelogram at tip offset u. */
static double ball_q(const ramp_point *rp, double u) {
  double dx = u - rp->xi, dz = fabs(rp->zp - rp->k * u) - rp->hh;
  dz = dz > 0.0 ? dz : 0.0;
  return dx * dx + rp->eta * rp->eta + dz * dz;
}

/* The ball ramp's sdf at p (frame in rp), its nearest tip offset in *ubest. */
static double ramp_ball_eval(const swarf_sweep *s, const double p[3], ramp_point *rp_out,
                             double *ubest_out) {
  ramp_point rp;
  double cand[3], best = INFINITY, ubest = 0.0, w;
  ramp_frame(s, p, &rp);
  w = swarf_sweep_cdata(s)->u.ramp.w;
  cand[0] = rp.xi;                                /* inside the height band */
  cand[1] = (rp.xi + rp.k * (rp.zp - rp.hh)) * w; /* above it */
  cand[2] = (rp.xi + rp.k * (rp.zp + rp.hh)) * w; /* below it */
  for (int i = 0; i < 3; i++) {
    double u = clamp(cand[i], 0.0, rp.U), q = ball_q(&rp, u);
    if (q < best) {
      best = q;
      ubest = u;
    }
  }
  *rp_out = rp;
  *ubest_out = ubest;
  return sqrt(best) - s->cutter->corner_radius;
}

double swarf_sweep_ramp_ball_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  ramp_point rp;
  double u, d = ramp_ball_eval(s, p, &rp, &u);
  if (alpha != NULL) *alpha = u / rp.U;
  return d;
}

/* Flat or bull ramp: is some instance's core within reach, i.e. does an
 * offset u in [0, U] have r(u) <= a and |zp - k u| <= hh? */
static int ramp_inside(const ramp_point *rp) {
  double lo = 0.0, hi = rp->U, s2 = rp->a * rp->a - rp->eta * rp->eta, b0, b1;
  if (s2 < 0.0) return 0;
  s2 = sqrt(s2);
  lo = max2(lo, rp->xi - s2);
  hi = min2(hi, rp->xi + s2);
  b0 = (rp->zp - rp->hh) / rp->k;
  b1 = (rp->zp + rp->hh) / rp->k;
  lo = max2(lo, min2(b0, b1));
  hi = min2(hi, max2(b0, b1));
  return lo <= hi;
}

/* Signed core distance of the instance at u inside the sweep: the larger of
 * the radial and height slab distances. */
static double ramp_m(const ramp_point *rp, double u) {
  double dx = u - rp->xi, r = sqrt(dx * dx + rp->eta * rp->eta) - rp->a;
  double dz = fabs(rp->zp - rp->k * u) - rp->hh;
  return r > dz ? r : dz;
}

/* Where r(u) - a meets the line c0 + c1 u (up to two offsets). */
static int ramp_cross(const ramp_point *rp, double c0, double c1, double u[2]) {
  double b0 = rp->a + c0, qa = 1.0 - c1 * c1, qb = -2.0 * (rp->xi + b0 * c1);
  double qc = rp->xi * rp->xi + rp->eta * rp->eta - b0 * b0, disc;
  if (fabs(qa) < 1e-12) {
    if (qb == 0.0) return 0;
    u[0] = -qc / qb;
    return 1;
  }
  disc = qb * qb - 4.0 * qa * qc;
  if (disc < 0.0) return 0;
  disc = sqrt(disc);
  u[0] = (-qb - disc) / (2.0 * qa);
  u[1] = (-qb + disc) / (2.0 * qa);
  return 2;
}

/* Inside: the minimum over u of the convex max(r - a, |zp - k u| - hh) is at
 * an end, at the minimum of a piece, or where two pieces cross. */
static double ramp_depth(const ramp_point *rp, double *ubest) {
  double cand[8], best = INFINITY, uz = rp->zp / rp->k;
  int n = 0;
  /* Where a piece's minimum over the move dominates there, it is the minimum
   * (the other piece only adds): the radial one at xi clamped to the move (r
   * grows away from it, in floating point too: the rounding is monotone; on
   * a short move most points inside lie beyond an end), the height one at
   * zp / k (-hh). */
  {
    const double ur = clamp(rp->xi, 0.0, rp->U), dx = ur - rp->xi;
    const double rad = sqrt(dx * dx + rp->eta * rp->eta) - rp->a;
    if (rad >= fabs(rp->zp - rp->k * ur) - rp->hh) {
      *ubest = ur;
      return rad;
    }
  }
  if (uz >= 0.0 && uz <= rp->U) {
    double dx = uz - rp->xi;
    if (sqrt(dx * dx + rp->eta * rp->eta) - rp->a <= -rp->hh) {
      *ubest = uz;
      return ramp_m(rp, uz);
    }
  }
  cand[n++] = 0.0;
  cand[n++] = rp->U;
  cand[n++] = rp->xi;
  cand[n++] = uz;
  n += ramp_cross(rp, rp->zp - rp->hh, -rp->k, cand + n);
  n += ramp_cross(rp, -rp->zp - rp->hh, rp->k, cand + n);
  for (int i = 0; i < n; i++) {
    /* A candidate beyond an end is that end, already tried (and kept on a tie). */
    if (i >= 2 && !(cand[i] > 0.0 && cand[i] < rp->U)) continue;
    double u = clamp(cand[i], 0.0, rp->U), m = ramp_m(rp, u);
    if (m < best) {
      best = m;
      *ubest = u;
    }
  }
  return best;
}

/* Outside: q(u) = dist(p, instance core at u)^2 and its first two
 * derivatives; q is convex and C1. */
static double ramp_q(const ramp_point *rp, double u, double *dq, double *d2q) {
  double dx = u - rp->xi, r = sqrt(dx * dx + rp->eta * rp->eta), rho = r - rp->a;
  double z = rp->zp - rp->k * u, dz = fabs(z) - rp->hh, q = 0.0;
  *dq = *d2q = 0.0;
  if (rho > 0.0) {
    q += rho * rho;
    *dq += 2.0 * rho * dx / r;
    *d2q += 2.0 * (dx * dx / (r * r) + rho * rp->eta * rp->eta / (r * r * r));
  }
  if (dz > 0.0) {
    q += dz * dz;
    *dq -= 2.0 * dz * rp->k * (z > 0.0 ? 1.0 : -1.0);
    *d2q += 2.0 * rp->k * rp->k;
  }
  return q;
}

/* Safeguarded Newton on q' over [0, U]; the ends are tried before bisecting
 * toward them. Returns the smallest q met, its offset in *ubest. */
static double ramp_newton(const ramp_point *rp, double *ubest) {
  double lo = 0.0, hi = rp->U, u = clamp(rp->xi, lo, hi), best = INFINITY;
  double tol = 1e-14 * (1.0 + rp->U + fabs(rp->xi));
  int lo_seen = 0, hi_seen = 0;
  for (int it = 0; it < 100; it++) {
    double dq, d2q, q = ramp_q(rp, u, &dq, &d2q), next;
    if (q < best) {
      best = q;
      *ubest = u;
    }
    if (dq == 0.0 || (dq > 0.0 && u <= 0.0) || (dq < 0.0 && u >= rp->U)) break;
    if (dq > 0.0) {
      hi = u;
      hi_seen = 1;
    } else {
      lo = u;
      lo_seen = 1;
    }
    next = d2q > 0.0 ? u - dq / d2q : 0.5 * (lo + hi);
    if (next <= lo) next = lo_seen ? 0.5 * (lo + hi) : lo;
    if (next >= hi) next = hi_seen ? 0.5 * (lo + hi) : hi;
    if (fabs(next - u) <= tol || hi - lo <= tol) break;
    u = next;
  }
  return best;
}

/* The flat or bull ramp's sdf at p (frame in rp), its nearest tip offset in *u. */
static double ramp_eval(const swarf_sweep *s, const double p[3], ramp_point *rp, double *u) {
  double d;
  *u = 0.0;
  ramp_frame(s, p, rp);
  if (ramp_inside(rp))
    d = ramp_depth(rp, u);
  else
    d = sqrt(ramp_newton(rp, u));
  return d - s->cutter->corner_radius;
}

double swarf_sweep_ramp_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  ramp_point rp;
  double u, d = ramp_eval(s, p, &rp, &u);
  if (alpha != NULL) *alpha = u / rp.U;
  return d;
}

/* A unit normal of the cutter's core (radius a, height band) at a point off
 * it by dr radially and dz in height (as the sdf's box: outside where either
 * is > 0, inside at depth -max(dr, dz) otherwise), with radial direction
 * (cx, cy) (unit, or 0 on the axis) and height side sz (+-1), in g; returns
 * the signed distance to the core, or NaN where the normal is not reliable.
 * Outside: the normal at the nearest point (not within 1e-6 mm of the core,
 * where rounding could tilt it). Inside: the gradient of the nearer side, a
 * subgradient of the convex sdf there (either side at a tie); the radial one
 * not within 1e-6 mm of the axis, the height one at mid-height the side sz
 * (|.| at 0 has every slope in [-1, 1]). */
static double core_normal(double dr, double dz, double a, double cx, double cy, double sz,
                          double g[3]) {
  if (dr > 0.0 || dz > 0.0) {
    double gr = dr > 0.0 ? dr : 0.0, gz = dz > 0.0 ? dz : 0.0, dist = sqrt(gr * gr + gz * gz);
    if (!(dist >= 1e-6)) return NAN;
    double inv = 1.0 / dist;
    g[0] = gr * cx * inv;
    g[1] = gr * cy * inv;
    g[2] = gz * sz * inv;
    return dist;
  }
  if (dr >= dz) {
    if (!(dr + a >= 1e-6)) return NAN;
    g[0] = cx, g[1] = cy, g[2] = 0.0;
    return dr;
  }
  g[0] = g[1] = 0.0, g[2] = sz;
  return dz;
}

/* The radial unit direction of (x, y), or 0 on the axis. */
static void radial(double x, double y, double *cx, double *cy) {
  double r = sqrt(x * x + y * y);
  *cx = r > 0.0 ? x / r : 0.0;
  *cy = r > 0.0 ? y / r : 0.0;
}

/* A ramp's frame normal (along, across, up) in world axes. */
static void ramp_world(const swarf_sweep *s, double g[3]) {
  const swarf_sweep_ramp *x = &swarf_sweep_cdata(s)->u.ramp;
  double gxi = g[0], geta = g[1];
  g[0] = gxi * x->e[0] - geta * x->e[1];
  g[1] = gxi * x->e[1] + geta * x->e[0];
}

int swarf_sweep_line_support(const swarf_sweep *s, const double p[3], double *d, double g[3]) {
  const swarf_cutter *c = s->cutter;
  const double R = c->corner_radius, hh = 0.5 * c->length - R;
  double cx, cy, dist, n[3];
  switch (swarf_sweep_cdata(s)->method) {
  case SWARF_SWEEP_SLOT: {
    const swarf_sweep_slot *x = &swarf_sweep_cdata(s)->u.slot;
    double wx = p[0] - x->p0[0], wy = p[1] - x->p0[1];
    double t = clamp((wx * x->d[0] + wy * x->d[1]) * x->inv_len2, 0.0, 1.0);
    double ex = wx - t * x->d[0], ey = wy - t * x->d[1], z = p[2] - x->p0[2];
    double r = sqrt(ex * ex + ey * ey);
    *d = swarf_cutter_sdf_rz(c, r, z); /* as swarf_sweep_slot_sdf */
    radial(ex, ey, &cx, &cy);
    dist = core_normal(r - swarf_cutter_core(c), fabs(z - 0.5 * c->length) - hh,
                       swarf_cutter_core(c), cx, cy, z >= 0.5 * c->length ? 1.0 : -1.0, n);
    break;
  }
  case SWARF_SWEEP_PLUNGE: {
    const swarf_sweep_plunge *x = &swarf_sweep_cdata(s)->u.plunge;
    double ex = p[0] - x->x, ey = p[1] - x->y;
    *d = swarf_sweep_plunge_sdf(s, p, NULL);
    radial(ex, ey, &cx, &cy);
    dist =
        core_normal(sqrt(ex * ex + ey * ey) - swarf_cutter_core(c), fabs(p[2] - x->mid) - x->half,
                    swarf_cutter_core(c), cx, cy, p[2] >= x->mid ? 1.0 : -1.0, n);
    break;
  }
  case SWARF_SWEEP_RAMP:
  case SWARF_SWEEP_RAMP_BALL: {
    ramp_point rp;
    double u;
    *d = swarf_sweep_cdata(s)->method == SWARF_SWEEP_RAMP ? ramp_eval(s, p, &rp, &u)
                                                          : ramp_ball_eval(s, p, &rp, &u);
    double z = rp.zp - rp.k * u, dr = sqrt((u - rp.xi) * (u - rp.xi) + rp.eta * rp.eta) - rp.a;
    double dz = fabs(z) - rp.hh;
    /* Inside the core the ramp's value is that of the instance at u (the
     * deepest one), min over u of a convex function of (p, u): the gradient
     * of its radial side bounds it only where moving u cannot lower that side
     * (u = xi, or the end toward xi); its height side is not used. */
    if (dr <= 0.0 && dz <= 0.0 && !(dr >= dz && u == clamp(rp.xi, 0.0, rp.U))) return 0;
    radial(rp.xi - u, rp.eta, &cx, &cy);
    dist = core_normal(dr, dz, rp.a, cx, cy, z >= 0.0 ? 1.0 : -1.0, n);
    ramp_world(s, n);
    break;
  }
  default:
    *d = swarf_sweep_sdf(s, p, NULL);
    return 0;
  }
  /* within rounding: outside, the normal of an instance only nearly nearest
   * could tilt the plane (by up to sqrt(2 err / dist) radians) */
  if (!(fabs(dist - R - *d) <= 1e-13 * (1.0 + fabs(*d)))) return 0;
  for (int k = 0; k < 3; k++)
    g[k] = n[k];
  return 1;
}
