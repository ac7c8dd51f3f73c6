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

static void form_set(form *f, const swarf_char_profile *pr, double c, const double v[3],
                     const double w[3]) {
  dd p1 = two_prod(pr->a, w[1]), p2 = two_prod(-pr->a, w[0]);
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
  form_set(f, pr, k == 0 ? pr->R : pr->L - pr->R, v, w);
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

/* Candidate roots of piece k as sigma values (unsorted); returns the count. */
static int piece_candidates(const swarf_char_profile *pr, int k, const double v[3],
                            const double w[3], double *out) {
  form f;
  double lo, hi, shift, err, r, dir[2][2];
  dd D, sq, rr;
  int n = 0;
  piece_form(pr, k, v, w, &f, &lo, &hi, &shift);
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
