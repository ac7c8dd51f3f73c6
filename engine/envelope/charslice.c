/* SPDX-License-Identifier: MPL-2.0 */
/* charslice.c -- the per-slice closed form of the characteristic curve of a
 * body of revolution (shared/docs/ENVELOPE.md, Fact 2) and its branch points.
 *
 * At n_z = z the characteristic condition is linear in (n_x, n_y):
 *   A x + B y + C = 0,  A = v_x + phi'(z) omega_y,  B = v_y - phi'(z) omega_x,  C = v_z z,
 * met on the circle x^2 + y^2 = 1 - z^2 where Delta = (1 - z^2)(A^2 + B^2) - C^2 >= 0.
 * The code scales A and B by sqrt(1 - z^2) (finite at the poles even where
 * phi' is not) and runs over the Gauss image with the polar angle, plus the
 * side ruling of a cutter as an interval of its own (engine_private.h).
 * Branch points: a QSS's quartic here (charpoly.c), a cutter's quadratic
 * forms in charcutter.c. Pure functions of caller-owned values.
 */
#include <math.h>
#include <stddef.h>

#include "engine_private.h"

static const double half_pi = 1.57079632679489661923;

void swarf_char_profile_cutter(swarf_char_profile *pr, const swarf_cutter *c) {
  if (!c->fast) { /* a profile cutter: its first piece (the others by piece) */
    swarf_char_profile_piece(pr, &c->piece[0]);
    return;
  }
  pr->is_qss = 0;
  pr->npart = 0;
  pr->a = swarf_cutter_core(c);
  pr->R = c->corner_radius;
  pr->L = c->length;
  pr->q2 = pr->q1 = pr->q0 = 0.0;
  pr->plateau = pr->L - 2.0 * pr->R > 0.0 ? 1.0 : 0.0;
  pr->sigma_end = 2.0 * half_pi + pr->plateau;
  pr->scale = pr->L > 0.5 * c->diameter ? pr->L : 0.5 * c->diameter;
}

void swarf_char_profile_qss(swarf_char_profile *pr, const swarf_qss *q) {
  pr->is_qss = 1;
  pr->npart = 0;
  pr->a = pr->R = pr->L = 0.0;
  pr->q2 = q->b - q->a;
  pr->q1 = q->e;
  pr->q0 = q->a + q->f;
  pr->plateau = 0.0;
  pr->sigma_end = 2.0 * half_pi;
  pr->scale = 3.0 * fabs(pr->q2) + 2.0 * fabs(pr->q1) + fabs(pr->q0);
  if (!(pr->scale > 0.0)) pr->scale = 1.0;
}

static int add_part(swarf_char_profile *pr, const swarf_char_part *q) {
  if (pr->npart == SWARF_CHAR_MAX_PARTS) return -1;
  pr->part[pr->npart++] = *q;
  return 0;
}

/* A vertex (r, z) carrying the normals from th0 to th1 (nothing if none). */
static void add_vertex(swarf_char_profile *pr, double *sigma, double r, double z, double th0,
                       double th1) {
  swarf_char_part q = {0, *sigma, *sigma + (th1 - th0), th0, th1, r, z, 0.0, 0, 0, 0, 0};
  if (!(th1 > th0 + 1e-12)) return;
  if (add_part(pr, &q) == 0) *sigma = q.s1;
}

/* Walk a hull's outline (profile.c: bottom to top, counterclockwise): arcs
 * are smooth parts, corners vertices, sloped and vertical lines plateaus;
 * the flat faces are the poles. */
void swarf_char_profile_piece(swarf_char_profile *pr, const swarf_profile_piece *pc) {
  double sigma = 0.0, th = 0.0, lr = 0.0, lz = 0.0;
  if (pc->kind == SWARF_PIECE_QSS) {
    swarf_qss q = pc->qss;
    swarf_char_profile_qss(pr, &q);
    return;
  }
  pr->is_qss = 0;
  pr->npart = 0;
  pr->a = pr->R = pr->L = 0.0;
  pr->q2 = pr->q1 = pr->q0 = 0.0;
  pr->plateau = 0.0;
  for (int i = 0; i < pc->nel; i++) {
    const swarf_profile_elem *e = &pc->el[i];
    if (e->rad > 0.0) {
      double t0 = atan2(e->z0 - e->cz, e->r0 - e->cr) + half_pi;
      double t1 = atan2(e->z1 - e->cz, e->r1 - e->cr) + half_pi;
      swarf_char_part q = {0, 0, 0, t0, t1, e->cr, e->cz, e->rad, 0, 0, 0, 0};
      add_vertex(pr, &sigma, e->r0, e->z0, th, t0);
      q.s0 = sigma, q.s1 = sigma + (t1 - t0);
      if (t1 > t0 && add_part(pr, &q) == 0) sigma = q.s1;
      th = fmax(th, t1);
    } else {
      double dr = e->r1 - e->r0, dz = e->z1 - e->z0, len = sqrt(dr * dr + dz * dz), tl;
      if (!(len > 0.0)) continue;
      tl = atan2(-dr, dz) + half_pi;                  /* outward normal (dz, -dr) */
      if (tl < 1e-12 || tl > 2.0 * half_pi - 1e-12) { /* a flat face: a pole */
        if (tl > half_pi)
          add_vertex(pr, &sigma, e->r0, e->z0, th, 2.0 * half_pi), th = 2.0 * half_pi;
      } else {
        swarf_char_part q = {1, 0, 0, tl, tl, 0, 0, 0, e->r0, e->z0, e->r1, e->z1};
        add_vertex(pr, &sigma, e->r0, e->z0, th, tl);
        q.s0 = sigma, q.s1 = sigma + 1.0;
        if (add_part(pr, &q) == 0) sigma = q.s1, pr->plateau += 1.0;
        th = tl;
      }
    }
    lr = e->r1, lz = e->z1;
  }
  add_vertex(pr, &sigma, lr, lz, th, 2.0 * half_pi);
  pr->sigma_end = sigma;
  pr->scale = fmax(fmax(fabs(pc->zhi), fabs(pc->zlo)), pc->rmax);
  if (!(pr->scale > 0.0)) pr->scale = 1.0;
}

/* The parts' geometry at sigma (see slice_geometry). */
static double parts_geometry(const swarf_char_profile *pr, double sigma, swarf_char_slice *sl) {
  const swarf_char_part *q;
  int k = 0;
  while (k + 1 < pr->npart && sigma > pr->part[k].s1)
    k++;
  q = &pr->part[k];
  if (q->plateau) {
    double tau = q->s1 > q->s0 ? (sigma - q->s0) / (q->s1 - q->s0) : 0.0;
    tau = tau < 0.0 ? 0.0 : tau > 1.0 ? 1.0 : tau;
    sl->z = -cos(q->th0), sl->sz = sin(q->th0);
    sl->a = q->r0 + tau * (q->r1 - q->r0), sl->R = 0.0;
    sl->c = q->z0 + tau * (q->z1 - q->z0);
  } else {
    double theta = q->th0 + (sigma - q->s0);
    sl->z = -cos(theta), sl->sz = sin(theta);
    sl->a = q->a, sl->R = q->R, sl->c = q->c;
  }
  if (sl->sz < 0.0) sl->sz = 0.0;
  return -sl->a * sl->z + sl->c * sl->sz;
}

/* z, sqrt(1 - z^2), the ruling height c and P = phi'(z) sqrt(1 - z^2). */
static double slice_geometry(const swarf_char_profile *pr, double sigma, swarf_char_slice *sl) {
  double theta = sigma;
  if (pr->npart > 0) return parts_geometry(pr, sigma, sl);
  sl->a = pr->a, sl->R = pr->R;
  sl->c = pr->R;
  if (pr->plateau > 0.0 && sigma > half_pi) {
    if (sigma < half_pi + pr->plateau) {
      sl->z = 0.0;
      sl->sz = 1.0;
      sl->c = pr->R + (sigma - half_pi) / pr->plateau * (pr->L - 2.0 * pr->R);
      return sl->c;
    }
    theta = sigma - pr->plateau;
    sl->c = pr->L - pr->R;
  } else if (!pr->is_qss && sigma > half_pi) {
    sl->c = pr->L - pr->R;
  }
  sl->z = -cos(theta);
  sl->sz = sin(theta);
  if (sl->sz < 0.0) sl->sz = 0.0;
  if (pr->is_qss) return (2.0 * pr->q2 * sl->z + pr->q1) * sl->sz;
  return -pr->a * sl->z + sl->c * sl->sz;
}

void swarf_char_slice_eval(const swarf_char_profile *pr, const double v[3], const double omega[3],
                           double sigma, swarf_char_slice *sl) {
  double P = slice_geometry(pr, sigma, sl);
  sl->At = v[0] * sl->sz + P * omega[1];
  sl->Bt = v[1] * sl->sz - P * omega[0];
  sl->C = v[2] * sl->z;
  sl->delta = sl->At * sl->At + sl->Bt * sl->Bt - sl->C * sl->C;
}

static void surface_point(const swarf_char_profile *pr, const swarf_char_slice *sl,
                          const double u[2], const double n[3], double x[3]) {
  if (pr->is_qss) {
    double z = n[2], phi = (pr->q2 * z + pr->q1) * z + pr->q0, dphi = 2.0 * pr->q2 * z + pr->q1;
    x[0] = phi * n[0] - dphi * z * n[0];
    x[1] = phi * n[1] - dphi * z * n[1];
    x[2] = phi * n[2] + dphi * (1.0 - z * n[2]);
    return;
  }
  x[0] = sl->a * u[0] + sl->R * n[0];
  x[1] = sl->a * u[1] + sl->R * n[1];
  x[2] = sl->c + sl->R * n[2];
}

int swarf_char_slice_point(const swarf_char_profile *pr, const swarf_char_slice *sl, double s,
                           double n[3], double x[3]) {
  double q = sl->At * sl->At + sl->Bt * sl->Bt, u[2] = {1.0, 0.0};
  if (q > 0.0) {
    double d = sl->delta > 0.0 ? sqrt(sl->delta) : 0.0, m;
    if (sl->delta < -1e-12 * q) return -1;
    u[0] = (-sl->At * sl->C + s * sl->Bt * d) / q;
    u[1] = (-sl->Bt * sl->C - s * sl->At * d) / q;
    m = sqrt(u[0] * u[0] + u[1] * u[1]);
    u[0] /= m;
    u[1] /= m;
  } else if (!(sl->sz == 0.0 && (pr->is_qss || sl->a == 0.0)) || sl->C != 0.0) {
    return -1; /* the rim direction is not determined here: caller nudges */
  }
  n[0] = sl->sz * u[0];
  n[1] = sl->sz * u[1];
  n[2] = sl->z;
  surface_point(pr, sl, u, n, x);
  return 0;
}

/* Delta >= 0: a zero at a pole (the curve through the pole) starts a run
 * there instead of making a root next to it. */
static int delta_positive(const swarf_char_profile *pr, const double v[3], const double omega[3],
                          double sigma) {
  swarf_char_slice sl;
  swarf_char_slice_eval(pr, v, omega, sigma, &sl);
  return sl.delta >= 0.0;
}

/* Bisect a sign change of Delta in [lo, hi] to adjacent doubles; returns the
 * end on the side where Delta >= 0. */
static double delta_bisect(const swarf_char_profile *pr, const double v[3], const double omega[3],
                           double lo, double hi) {
  int plo = delta_positive(pr, v, omega, lo);
  for (;;) {
    double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    if (delta_positive(pr, v, omega, mid) == plo)
      lo = mid;
    else
      hi = mid;
  }
  return plo ? lo : hi;
}

/* A QSS: Delta(z) = (1 - z^2)(A^2 + B^2) - C^2 is a quartic with A, B, C
 * linear in z; its sign changes come from swarf_char_poly_roots (no narrow
 * gap between two roots can hide between samples), then each is re-bisected
 * in sigma on the slice's own Delta so that both agree on which side is >= 0. */
static int qss_delta_roots(const swarf_char_profile *pr, const double v[3], const double omega[3],
                           double *roots, int max) {
  double a0 = v[0] + pr->q1 * omega[1], a1 = 2.0 * pr->q2 * omega[1];
  double b0 = v[1] - pr->q1 * omega[0], b1 = -2.0 * pr->q2 * omega[0];
  double s0 = a0 * a0 + b0 * b0, s1 = 2.0 * (a0 * a1 + b0 * b1), s2 = a1 * a1 + b1 * b1;
  double c[5] = {s0, s1, s2 - s0 - v[2] * v[2], -s1, -s2}, z[4];
  int n = swarf_char_poly_roots(c, 4, -1.0, 1.0, z, 4);
  for (int i = 0; i < n && i < max; i++) {
    double sig = acos(-z[i]), eps = 1e-13;
    roots[i] = sig;
    for (int k = 0; k < 60; k++, eps *= 2.0) {
      double lo = fmax(0.0, sig - eps), hi = fmin(pr->sigma_end, sig + eps);
      if (delta_positive(pr, v, omega, lo) != delta_positive(pr, v, omega, hi)) {
        roots[i] = delta_bisect(pr, v, omega, lo, hi);
        break;
      }
    }
  }
  return n;
}

int swarf_char_delta_roots(const swarf_char_profile *pr, const double v[3], const double omega[3],
                           double *roots, int max) {
  if (pr->is_qss) return qss_delta_roots(pr, v, omega, roots, max);
  if (pr->npart > 0) return swarf_char_parts_delta_roots(pr, v, omega, roots, max);
  return swarf_char_cutter_delta_roots(pr, v, omega, roots, max);
}

int swarf_char_delta_positive(const swarf_char_profile *pr, const double v[3],
                              const double omega[3], double sigma) {
  swarf_char_slice sl;
  if (pr->npart > 0) return swarf_char_parts_delta_positive(pr, v, omega, sigma);
  if (!pr->is_qss) return swarf_char_cutter_delta_positive(pr, v, omega, sigma);
  swarf_char_slice_eval(pr, v, omega, sigma, &sl);
  return sl.delta > 0.0;
}

/* n_z at parameter sigma (0 on the ruling). */
static double sigma_to_z(const swarf_char_profile *pr, double sigma) {
  swarf_char_slice sl;
  slice_geometry(pr, sigma, &sl);
  return sl.z;
}

static int branch_points(const swarf_char_profile *pr, const double v[3], const double omega[3],
                         double *z, int max) {
  double roots[64];
  int n = swarf_char_delta_roots(pr, v, omega, roots, 64);
  for (int i = 0; i < n && i < max && i < 64; i++)
    z[i] = sigma_to_z(pr, roots[i]);
  return n;
}

int swarf_char_branch_points(const swarf_cutter *c, const double v[3], const double omega[3],
                             double *z, int max) {
  swarf_char_profile pr;
  swarf_char_profile_cutter(&pr, c);
  return branch_points(&pr, v, omega, z, max);
}

int swarf_char_branch_points_qss(const swarf_qss *q, const double v[3], const double omega[3],
                                 double *z, int max) {
  swarf_char_profile pr;
  swarf_char_profile_qss(&pr, q);
  return branch_points(&pr, v, omega, z, max);
}

int swarf_char_gauss_slice(double dphi, const double v[3], const double omega[3], double z,
                           double n[2][3]) {
  double A = v[0] + dphi * omega[1], B = v[1] - dphi * omega[0], C = v[2] * z;
  double q = A * A + B * B, delta = (1.0 - z * z) * q - C * C, d;
  /* Not finite: the infinite slope of a profile at a pole (swarf_cutter_profile
   * at z = +-1) gives an infinite or NaN q and delta, no point. */
  if (!(q > 0.0) || !isfinite(q) || !(delta >= 0.0)) return 0;
  d = sqrt(delta);
  for (int k = 0; k < 2; k++) {
    double s = k == 0 ? 1.0 : -1.0;
    n[k][0] = (-A * C + s * B * d) / q;
    n[k][1] = (-B * C - s * A * d) / q;
    n[k][2] = z;
  }
  return delta > 0.0 ? 2 : 1;
}
