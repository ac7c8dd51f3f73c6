/* SPDX-License-Identifier: MPL-2.0 */
/* charcutter.c -- the branch points of a cutter's characteristic curve (the
 * roots of Fact 2's Delta for flat, ball and bull-nose profiles), certified
 * in double-double arithmetic.
 *
 * On a smooth piece of the profile, phi(z) = a sqrt(1 - z^2) + R + c z with
 * c = R below the side ruling and c = L - R above it. With z = -cos(theta),
 * (co, s) = (cos theta, sin theta), the slice values of charslice.c are
 *   At = a w_y co + (v_x + c w_y) s,  Bt = -a w_x co + (v_y - c w_x) s,  C = -v_z co,
 * so Delta = At^2 + Bt^2 - C^2 = al co^2 + 2 be co s + ga s^2 is a quadratic
 * form in (co, s): its zeros on the piece are (at most two) directions,
 * real exactly when D = be^2 - al ga > 0. The coefficients and D are formed
 * in double-double (error-free products through fma) with a bound on the
 * rounding error, so the sign of D is certain unless |D| is below ~1e-30 of
 * its scale: pairs of branch points closer than ~1e-14 merge into a double
 * root (no sign change). On the side ruling Delta = At^2 + Bt^2 >= 0. Which
 * candidate roots are sign changes is decided by certified signs of Delta
 * between them. Pure functions of caller-owned values.
 */
#include <math.h>

#include "engine_private.h"

#define HALF_PI 1.57079632679489661923
#define PI 3.14159265358979323846
#define ERR_K 64.0 /* generous multiple of u^2 for the double-double error bounds */
#define U2 (1.1102230246251565e-16 * 1.1102230246251565e-16)

typedef struct {
  double hi, lo;
} dd;

static dd two_sum(double a, double b) {
  double s = a + b, bb = s - a;
  return (dd){s, (a - (s - bb)) + (b - bb)};
}

static dd quick_two_sum(double a, double b) {
  double s = a + b;
  return (dd){s, b - (s - a)};
}

static dd two_prod(double a, double b) {
  double p = a * b;
  return (dd){p, fma(a, b, -p)};
}

static dd dd_add(dd a, dd b) {
  dd s = two_sum(a.hi, b.hi), t = two_sum(a.lo, b.lo);
  s = quick_two_sum(s.hi, s.lo + t.hi);
  return quick_two_sum(s.hi, s.lo + t.lo);
}

static dd dd_neg(dd a) {
  return (dd){-a.hi, -a.lo};
}

static dd dd_mul(dd a, dd b) {
  dd p = two_prod(a.hi, b.hi);
  return quick_two_sum(p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi));
}

static dd dd_sqrt(dd a) {
  double x = sqrt(a.hi);
  dd r = dd_add(a, dd_neg(two_prod(x, x)));
  return quick_two_sum(x, r.hi / (2.0 * x));
}

/* The form of one smooth piece, with magnitude bounds for the error terms. */
typedef struct {
  dd al, be, ga;
  double mal, mbe, mga; /* bounds on |al|, |be|, |ga| without cancellation */
} form;

static void form_set(form *f, double a, double c, const double v[3], const double w[3]) {
  dd p1 = two_prod(a, w[1]), p2 = two_prod(-a, w[0]);
  dd q1 = dd_add((dd){v[0], 0.0}, two_prod(c, w[1]));
  dd q2 = dd_add((dd){v[1], 0.0}, two_prod(-c, w[0]));
  double mp = fabs(p1.hi) + fabs(p2.hi), mq = fabs(q1.hi) + fabs(q2.hi);
  f->al = dd_add(dd_add(dd_mul(p1, p1), dd_mul(p2, p2)), dd_neg(two_prod(v[2], v[2])));
  f->be = dd_add(dd_mul(p1, q1), dd_mul(p2, q2));
  f->ga = dd_add(dd_mul(q1, q1), dd_mul(q2, q2));
  f->mal = 1.01 * (mp * mp + v[2] * v[2]);
  f->mbe = 1.01 * mp * mq;
  f->mga = 1.01 * mq * mq;
}

/* The sign of the form at the direction (co, s): +1, -1, or 0 when the
 * rounding error bound does not decide it. */
static int form_sign(const form *f, double co, double s) {
  dd q = dd_add(dd_add(dd_mul(f->al, two_prod(co, co)), dd_mul(f->be, two_prod(2.0 * co, s))),
                dd_mul(f->ga, two_prod(s, s)));
  double err = ERR_K * U2 * (f->mal * co * co + 2.0 * f->mbe * fabs(co * s) + f->mga * s * s);
  double val = q.hi + q.lo;
  return val > err ? 1 : val < -err ? -1 : 0;
}

/* Piece k (0: below the ruling, 1: above): its form, theta range and the
 * sigma of its theta = 0 point. */
static void piece_form(const swarf_char_profile *pr, int k, const double v[3], const double w[3],
                       form *f, double *th_lo, double *th_hi, double *shift) {
  form_set(f, pr->a, k == 0 ? pr->R : pr->L - pr->R, v, w);
  *th_lo = k == 0 ? 0.0 : HALF_PI;
  *th_hi = k == 0 ? HALF_PI : PI;
  *shift = k == 0 ? 0.0 : pr->plateau;
}

/* The angle in [lo, hi] of the line through (co, s) and -(co, s), or -1. */
static double line_angle(double co, double s, double lo, double hi) {
  double th;
  if (s < 0.0 || (s == 0.0 && co < 0.0)) co = -co, s = -s;
  th = atan2(s, co);
  if (th >= lo && th <= hi) return th;
  if (th + PI >= lo && th + PI <= hi) return th + PI;
  return -1.0;
}

/* Candidate roots of a form on theta in [lo, hi] as sigma = theta + shift. */
static int form_candidates(const form *fp, double lo, double hi, double shift, double *out) {
  form f = *fp;
  double err, r, dir[2][2];
  dd D, sq, rr;
  int n = 0;
  D = dd_add(dd_mul(f.be, f.be), dd_neg(dd_mul(f.al, f.ga)));
  err = ERR_K * U2 * (f.mbe * f.mbe + f.mal * f.mga);
  if (!(D.hi + D.lo > err)) return 0; /* no real root, or a double one */
  sq = dd_sqrt(D);
  rr = f.be.hi >= 0.0 ? dd_neg(dd_add(f.be, sq)) : dd_add(sq, dd_neg(f.be));
  r = rr.hi + rr.lo; /* -be - sign(be) sqrt(D): no cancellation */
  dir[0][0] = r, dir[0][1] = f.al.hi + f.al.lo;
  dir[1][0] = f.ga.hi + f.ga.lo, dir[1][1] = r;
  for (int i = 0; i < 2; i++) {
    double th = line_angle(dir[i][0], dir[i][1], lo, hi);
    if (th >= 0.0) out[n++] = th + shift;
  }
  return n;
}

/* Candidate roots of piece k as sigma values (unsorted); returns the count. */
static int piece_candidates(const swarf_char_profile *pr, int k, const double v[3],
                            const double w[3], double *out) {
  form f;
  double lo, hi, shift;
  piece_form(pr, k, v, w, &f, &lo, &hi, &shift);
  return form_candidates(&f, lo, hi, shift, out);
}

int swarf_char_cutter_delta_positive(const swarf_char_profile *pr, const double v[3],
                                     const double omega[3], double sigma) {
  form f;
  double lo, hi, shift, th;
  int k = sigma <= HALF_PI ? 0 : sigma >= HALF_PI + pr->plateau ? 1 : -1, sg;
  if (k < 0) return 1; /* the side ruling: At^2 + Bt^2 */
  piece_form(pr, k, v, omega, &f, &lo, &hi, &shift);
  th = sigma - shift;
  sg = form_sign(&f, cos(th), sin(th));
  if (sg == 0)
    sg = form_sign(&f, cos(0.5 * (th + (k == 0 ? lo : hi))), sin(0.5 * (th + (k == 0 ? lo : hi))));
  return sg >= 0;
}

static void sort_small(double *x, int n) {
  for (int i = 1; i < n; i++)
    for (int j = i; j > 0 && x[j] < x[j - 1]; j--) {
      double t = x[j];
      x[j] = x[j - 1];
      x[j - 1] = t;
    }
}

int swarf_char_cutter_delta_roots(const swarf_char_profile *pr, const double v[3],
                                  const double omega[3], double *roots, int max) {
  double br[8];
  int nb = 0, count = 0, prev = -1;
  nb += piece_candidates(pr, 0, v, omega, br + nb);
  nb += piece_candidates(pr, 1, v, omega, br + nb);
  br[nb++] = HALF_PI;
  br[nb++] = HALF_PI + pr->plateau;
  br[nb++] = pr->sigma_end;
  sort_small(br, nb);
  /* Run over the intervals between breakpoints; a change of sign between two
   * non-empty neighbours is a root at the breakpoint between them. */
  for (int i = 0; i < nb; i++) {
    double lo = i == 0 ? 0.0 : br[i - 1], mid = 0.5 * (lo + br[i]);
    int cur;
    if (!(br[i] > lo)) continue;
    cur = swarf_char_cutter_delta_positive(pr, v, omega, mid);
    if (prev >= 0 && cur != prev) {
      if (count < max) roots[count] = lo;
      count++;
    }
    prev = cur;
  }
  return count;
}

/* ---- General profiles: smooth parts and plateaus (swarf_char_part) ------- */

static int part_at(const swarf_char_profile *pr, double sigma) {
  int k = 0;
  while (k + 1 < pr->npart && sigma > pr->part[k].s1)
    k++;
  return k;
}

/* A plateau's Delta as a quadratic in P = -r z + zc sz (linear along it). */
static double plateau_delta(const swarf_char_part *q, const double v[3], const double w[3],
                            double tau) {
  double z = -cos(q->th0), sz = sin(q->th0);
  double r = q->r0 + tau * (q->r1 - q->r0), zc = q->z0 + tau * (q->z1 - q->z0),
         P = -r * z + zc * sz;
  double At = v[0] * sz + P * w[1], Bt = v[1] * sz - P * w[0], C = v[2] * z;
  return At * At + Bt * Bt - C * C;
}

static int plateau_candidates(const swarf_char_part *q, const double v[3], const double w[3],
                              double *out) {
  double z = -cos(q->th0), sz = sin(q->th0);
  double P0 = -q->r0 * z + q->z0 * sz, P1 = -q->r1 * z + q->z1 * sz, dP = P1 - P0;
  double A2 = w[0] * w[0] + w[1] * w[1], B1 = sz * (v[0] * w[1] - v[1] * w[0]);
  double C0 = sz * sz * (v[0] * v[0] + v[1] * v[1]) - v[2] * v[2] * z * z, disc, sq;
  int n = 0;
  if (dP == 0.0) return 0;
  if (A2 == 0.0) {
    if (B1 == 0.0) return 0;
    double P = -C0 / (2.0 * B1), tau = (P - P0) / dP;
    if (tau > 0.0 && tau < 1.0) out[n++] = q->s0 + tau * (q->s1 - q->s0);
    return n;
  }
  disc = B1 * B1 - A2 * C0;
  if (!(disc > 0.0)) return 0;
  sq = sqrt(disc);
  for (int i = 0; i < 2; i++) {
    double P = i == 0 ? (-B1 - sq) / A2 : (-B1 + sq) / A2, tau = (P - P0) / dP;
    if (tau > 0.0 && tau < 1.0) out[n++] = q->s0 + tau * (q->s1 - q->s0);
  }
  return n;
}

int swarf_char_parts_delta_positive(const swarf_char_profile *pr, const double v[3],
                                    const double omega[3], double sigma) {
  const swarf_char_part *q = &pr->part[part_at(pr, sigma)];
  form f;
  double th;
  int sg;
  if (q->plateau) {
    double tau = q->s1 > q->s0 ? (sigma - q->s0) / (q->s1 - q->s0) : 0.0;
    return plateau_delta(q, v, omega, tau) >= 0.0;
  }
  form_set(&f, q->a, q->c, v, omega);
  th = q->th0 + (sigma - q->s0);
  sg = form_sign(&f, cos(th), sin(th));
  return sg >= 0;
}

int swarf_char_parts_delta_roots(const swarf_char_profile *pr, const double v[3],
                                 const double omega[3], double *roots, int max) {
  double br[4 * SWARF_CHAR_MAX_PARTS + 2];
  int nb = 0, count = 0, prev = -1;
  for (int k = 0; k < pr->npart; k++) {
    const swarf_char_part *q = &pr->part[k];
    if (q->plateau) {
      nb += plateau_candidates(q, v, omega, br + nb);
    } else {
      form f;
      form_set(&f, q->a, q->c, v, omega);
      nb += form_candidates(&f, q->th0, q->th1, q->s0 - q->th0, br + nb);
    }
    br[nb++] = q->s1;
  }
  sort_small(br, nb);
  for (int i = 0; i < nb; i++) {
    double lo = i == 0 ? 0.0 : br[i - 1], mid = 0.5 * (lo + br[i]);
    int cur;
    if (!(br[i] > lo)) continue;
    cur = swarf_char_parts_delta_positive(pr, v, omega, mid);
    if (prev >= 0 && cur != prev) {
      if (count < max) roots[count] = lo;
      count++;
    }
    prev = cur;
  }
  return count;
}
