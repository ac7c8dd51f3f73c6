/* SPDX-License-Identifier: MPL-2.0 */
/* bench_charcurve.c -- time per characteristic curve, fast and exact, for QSS
 * and the standard cutters, beside a baseline in the same run: the naive
 * method of sampling f on a latitude-longitude grid of the Gauss sphere
 * (64 latitudes x 360 longitudes) and interpolating its sign changes. The
 * fast path's tolerance is tuned so that a curve has about 64 points; the
 * figures are microseconds per curve scaled to 64 points. The QSS cases also
 * run through the general-QSS path (same surface, full sweep). Not a test.
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */

#include <stdio.h>
#include <time.h>

#include "exactkit.h"

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double zero3[3] = {0, 0, 0};
static volatile double sink;

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

typedef struct {
  const swarf_cutter *cutter; /* or NULL: the QSS h6 */
  double h6[6], v[3], w[3];
  int general; /* the QSS h6 through the general path (Q = diag(a, a, b)) */
} job;

static int fast_curve(const job *j, double tol, swarf_char_curve *cc) {
  const double *h = j->h6;
  if (j->cutter)
    return (swarf_char_curve_compute(cc, j->cutter, zero3, I3, j->v, j->w, tol) == SWARF_OK
                ? (int)cc->ncomp
                : -1);
  if (j->general) {
    swarf_qss_general q = {{h[0], 0, 0, 0, h[0], 0, 0, 0, h[1]}, {h[2], h[3], h[4]}, h[5]};
    return (swarf_char_curve_compute_qss_general(cc, &q, zero3, I3, j->v, j->w, tol) == SWARF_OK
                ? (int)cc->ncomp
                : -1);
  }
  return (swarf_char_curve_compute_qss12(cc, h, zero3, I3, j->v, j->w, tol) == SWARF_OK
              ? (int)cc->ncomp
              : -1);
}

/* The tolerance giving about 64 points (bisection on its logarithm). */
static double tune(const job *j, swarf_char_curve *cc) {
  double lo = -12.0, hi = 1.0;
  for (int it = 0; it < 40; it++) {
    double mid = 0.5 * (lo + hi);
    fast_curve(j, pow(10.0, mid), cc);
    if (cc->len > 64)
      lo = mid;
    else
      hi = mid;
  }
  return pow(10.0, hi);
}

static double time_fast(const job *j, size_t *npts) {
  swarf_char_curve cc;
  double tol, t0, best = INFINITY;
  swarf_char_curve_init(&cc);
  int n;
  tol = tune(j, &cc);
  t0 = now();
  fast_curve(j, tol, &cc);
  n = (int)fmin(2000.0, fmax(20.0, 0.02 / (now() - t0))); /* about 20 ms a repetition */
  for (int rep = 0; rep < 5; rep++) {
    t0 = now();
    for (int i = 0; i < n; i++)
      fast_curve(j, tol, &cc);
    best = fmin(best, (now() - t0) / n);
  }
  *npts = cc.len;
  swarf_char_curve_clear(&cc);
  return best * 1e6 * 64.0 / (double)*npts;
}

/* Naive baseline: sign changes of f over the grid (QSS of eq. 12 or cutter). */
static double time_naive(const job *j) {
  double t0 = now(), acc = 0.0;
  int reps = 50, found = 0;
  for (int r = 0; r < reps; r++)
    for (int a = 0; a < 64; a++) {
      double z = -1.0 + (a + 0.5) / 32.0, sz = sqrt(1.0 - z * z), dphi, prev = 0.0;
      if (j->cutter)
        swarf_cutter_profile(j->cutter, z, &acc, &dphi);
      else
        dphi = 2.0 * (j->h6[1] - j->h6[0]) * z + j->h6[4];
      for (int b = 0; b <= 360; b++) {
        double th = b * (6.283185307179586 / 360.0), x = sz * cos(th), y = sz * sin(th);
        double f = (j->v[0] + dphi * j->w[1]) * x + (j->v[1] - dphi * j->w[0]) * y + j->v[2] * z;
        if (b > 0 && (f > 0.0) != (prev > 0.0)) found++, acc += f / (f - prev);
        prev = f;
      }
    }
  sink = acc + found;
  return (now() - t0) / reps * 1e6;
}

/* Exact: f, Delta, certified roots, ELM, and 64 exact slice points. */
static double time_exact(const long h[6], const long w[3], const long td[3], long bn, long bd,
                         int *kind) {
  fmpq hq[6], wq[3], tq[3];
  fmpq_t B, z;
  fmpz_t rz;
  swarf_xquad q;
  swarf_xmotion m;
  swarf_qr n[2][3];
  double t0, best = INFINITY;
  ek_vec_init(hq, 6), ek_vec_init(wq, 3), ek_vec_init(tq, 3), fmpq_init(B), fmpq_init(z);
  fmpz_init(rz);
  ek_vec_si(hq, h, 6), ek_vec_si(wq, w, 3), ek_vec_si(tq, td, 3), fmpq_set_si(B, bn, bd);
  for (int b = 0; b < 2; b++)
    for (int k = 0; k < 3; k++)
      swarf_qr_init(&n[b][k]);
  swarf_xquad_init(&q), swarf_xmotion_init(&m);
  swarf_xquad_set_revolution(&q, hq);
  swarf_xmotion_set(&m, wq, tq, B);
  for (int rep = 0; rep < 3; rep++) {
    t0 = now();
    for (int i = 0; i < 20; i++) {
      swarf_envelope_exact E;
      swarf_envelope_exact_init(&E);
      swarf_envelope_exact_compute(&E, &q, m.v, m.omega);
      *kind = E.kind;
      for (int c = 0; c < E.ncomp; c++)
        for (int s = 0; s < 32; s++) {
          double zd = E.comp_lo[c] + (E.comp_hi[c] - E.comp_lo[c]) * (s + 0.5) / 32;
          fmpq_set_si(z, lround(zd * 1024), 1024);
          swarf_envelope_exact_slice(&E, z, rz, n);
        }
      swarf_envelope_exact_clear(&E);
    }
    best = fmin(best, (now() - t0) / 20);
  }
  for (int b = 0; b < 2; b++)
    for (int k = 0; k < 3; k++)
      swarf_qr_clear(&n[b][k]);
  swarf_xquad_clear(&q), swarf_xmotion_clear(&m);
  ek_vec_clear(hq, 6), ek_vec_clear(wq, 3), ek_vec_clear(tq, 3), fmpq_clear(B), fmpq_clear(z);
  fmpz_clear(rz);
  return best * 1e6;
}

static void row(const char *name, const job *j) {
  size_t npts;
  double fast = time_fast(j, &npts), naive = time_naive(j);
  printf("%-28s fast %8.2f us/64 pts (%3zu pts)   naive grid %8.1f us   speed-up %6.1fx\n", name,
         fast, npts, naive, naive / fast);
}

int main(void) {
  swarf_cutter flat, ball, bull;
  const double s = sin(0.3), c = cos(0.3);
  job ex2 = {NULL, {1, -1, 0, 0, 0, 0}, {1, -0.6, 0.8}, {2.0 / 3, 1.0 / 3, 2.0 / 3}, 0};
  job cvx = {NULL, {1, 1.5, 0, 0, 0, 0}, {0.3, 1, 0.2}, {0, s, c}, 0};
  job jf = {&flat, {0}, {1, 0.2, -0.1}, {0.05 * s, 0, 0.05 * c}, 0};
  job jb = jf, jr = jf, gex2 = ex2, gcvx = cvx;
  int kind = -1;
  static const long h2[6] = {1, -1, 0, 0, 0, 0}, w2[3] = {2, 1, 2}, t2[3] = {1, 1, 0};
  static const long h3[6] = {2, 3, 1, -1, 1, 5}, w3[3] = {2, 3, 6}, t3[3] = {3, -1, 2};
  swarf_cutter_init(&flat, SWARF_CUTTER_FLAT, 6.0, 0.0, 20.0, NULL);
  swarf_cutter_init(&ball, SWARF_CUTTER_BALL, 6.0, 0.0, 20.0, NULL);
  swarf_cutter_init(&bull, SWARF_CUTTER_BULL, 6.0, 1.0, 20.0, NULL);
  jb.cutter = &ball, jr.cutter = &bull;
  gex2.general = gcvx.general = 1;
  printf("characteristic curves: fast path vs a naive 64 x 360 grid of f (same run)\n");
  row("QSS Example 2", &ex2);
  row("QSS convex, screw", &cvx);
  row("QSS Example 2, general path", &gex2);
  row("QSS convex, general path", &gcvx);
  row("flat D6 L20, ramp + tilt", &jf);
  row("ball D6 L20, ramp + tilt", &jb);
  row("bull D6 R1 L20, ramp + tilt", &jr);
  printf("exact path (f, Delta + certified roots, ELM, 64 exact slice points):\n");
  printf("%-28s exact %8.1f us/curve (case %d)\n", "QSS Example 2",
         time_exact(h2, w2, t2, 2, 1, &kind), kind);
  printf("%-28s exact %8.1f us/curve (case %d)\n", "QSS off-axis, B = 3/7",
         time_exact(h3, w3, t3, 3, 7, &kind), kind);
  flint_cleanup();
  return 0;
}
