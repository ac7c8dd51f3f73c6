/* SPDX-License-Identifier: MPL-2.0 */
/* test_charqssgen.c -- the fast characteristic curve of a GENERAL QSS
 * (swarf_char_curve_compute_qss_general) against independent references:
 *   1. random general QSS and motions: every point satisfies f = g = 0 and
 *      v_h(n) . n = 0 (f evaluated from its definition, eq. 11); every point
 *      of a dense independent sampling (z-slices about the fixed z axis,
 *      sign changes of f on a fine longitude grid, bisected) lies within tol
 *      of the polylines (chord error, and no component missed);
 *   2. rational QSS of revolution, turned by a rational rotation R into a
 *      general-looking QSS (full Q, b): the component count equals the exact
 *      path's (envelope_exact.h, certified roots of Delta); and, unrotated,
 *      the polylines agree with swarf_char_curve_compute_qss12 (same curve).
 */
#include <stdlib.h>

#include "check.h"
#include "exactkit.h"

#define CASES_GEN 400
#define CASES_DENSE 60
#define CASES_REV 600
#define TOL 1e-3
#define NEAR 1e-6

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double zero3[3] = {0, 0, 0};

static void grad_h(const swarf_qss_general *q, const double n[3], double g[3]) {
  for (int i = 0; i < 3; i++)
    g[i] = q->b[i] + (q->Q[3 * i] + q->Q[i]) * n[0] + (q->Q[3 * i + 1] + q->Q[3 + i]) * n[1] +
           (q->Q[3 * i + 2] + q->Q[6 + i]) * n[2];
}

/* f(n) = (v + omega x grad h) . n, from the definition. */
static double f_def(const swarf_qss_general *q, const double v[3], const double w[3],
                    const double n[3]) {
  double g[3], c[3];
  grad_h(q, n, g);
  tk_cross(w, g, c);
  return (v[0] + c[0]) * n[0] + (v[1] + c[1]) * n[1] + (v[2] + c[2]) * n[2];
}

static void random_qss(tk_rng *r, swarf_qss_general *q) {
  for (int i = 0; i < 9; i++)
    q->Q[i] = round(tk_uniform(r, -5, 5) * 4) / 4;
  for (int i = 0; i < 3; i++)
    q->b[i] = round(tk_uniform(r, -3, 3) * 4) / 4;
  q->c = round(tk_uniform(r, 0, 10) * 4) / 4;
}

static void random_motion(tk_rng *r, double v[3], double w[3]) {
  for (int i = 0; i < 3; i++)
    v[i] = round(tk_uniform(r, -4, 4) * 3) / 3, w[i] = round(tk_uniform(r, -2, 2) * 3) / 3;
}

/* Worst relative residual of f, g, v_h . n over the curve's points. */
static double worst_residual(const swarf_char_curve *cc, const swarf_qss_general *q,
                             const double v[3], const double w[3]) {
  double scale = tk_dot(v, v) + 1.0, worst = 0.0;
  for (int i = 0; i < 9; i++)
    scale += 3.0 * fabs(q->Q[i]) * sqrt(tk_dot(w, w));
  for (size_t i = 0; i < cc->len; i++) {
    const swarf_char_point *p = &cc->pts[i];
    double vx[3], f = f_def(q, v, w, p->n), g = tk_dot(p->n, p->n) - 1.0, vh;
    tk_cross(w, p->x, vx);
    vh = (v[0] + vx[0]) * p->n[0] + (v[1] + vx[1]) * p->n[1] + (v[2] + vx[2]) * p->n[2];
    worst = fmax(worst, fmax(fabs(f) / scale, fmax(fabs(g), fabs(vh) / scale)));
  }
  return worst;
}

static void surface(const swarf_qss_general *q, const double n[3], double x[3]) {
  double g[3], h = q->c, gn;
  grad_h(q, n, g);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      h += n[i] * q->Q[3 * i + j] * n[j];
  h += tk_dot(q->b, n);
  gn = tk_dot(g, n);
  for (int i = 0; i < 3; i++)
    x[i] = h * n[i] + g[i] - gn * n[i];
}

static double dist_to_curve(const swarf_char_curve *cc, const double x[3]) {
  double best = INFINITY;
  for (size_t k = 0; k < cc->ncomp; k++)
    for (size_t i = cc->start[k]; i + 1 < cc->start[k + 1]; i++)
      best = fmin(best, tk_seg_dist(x, cc->pts[i].x, cc->pts[i + 1].x));
  return best;
}

static void slice_normal(double z, double th, double n[3]) {
  double r = sqrt(1.0 - z * z);
  n[0] = r * cos(th), n[1] = r * sin(th), n[2] = z;
}

/* Dense independent sampling; returns the worst distance to the polylines. */
static double dense_error(const swarf_char_curve *cc, const swarf_qss_general *q, const double v[3],
                          const double w[3], int *npts) {
  double worst = 0.0;
  for (int iz = 1; iz < 300; iz++) {
    double z = -1.0 + 2.0 * iz / 300.0, n[3], f0, th0 = 0.0;
    slice_normal(z, th0, n);
    f0 = f_def(q, v, w, n);
    for (int it = 1; it <= 2048; it++) {
      double th1 = 2.0 * tk_pi * it / 2048, f1, lo = th0, hi = th1, x[3];
      slice_normal(z, th1, n);
      f1 = f_def(q, v, w, n);
      if ((f0 > 0) != (f1 > 0)) {
        for (int b = 0; b < 60; b++) {
          double mid = 0.5 * (lo + hi), fm;
          slice_normal(z, mid, n);
          fm = f_def(q, v, w, n);
          if ((fm > 0) == (f0 > 0))
            lo = mid;
          else
            hi = mid;
        }
        slice_normal(z, 0.5 * (lo + hi), n);
        surface(q, n, x);
        worst = fmax(worst, dist_to_curve(cc, x));
        (*npts)++;
      }
      th0 = th1, f0 = f1;
    }
  }
  return worst;
}

static void test_general(void) {
  tk_rng rng = {0x5eed9e17ULL};
  swarf_char_curve cc;
  int fails = 0, pts = 0, bad_res = 0, bad_chord = 0, dense_pts = 0, hist[5] = {0};
  double worst_res = 0.0, worst_chord = 0.0;
  swarf_char_curve_init(&cc);
  for (int it = 0; it < CASES_GEN; it++) {
    swarf_qss_general q;
    double v[3], w[3], res;
    int n;
    random_qss(&rng, &q);
    random_motion(&rng, v, w);
    n = (swarf_char_curve_compute_qss_general(&cc, &q, zero3, I3, v, w, TOL) == SWARF_OK
             ? (int)cc.ncomp
             : -1);
    if (n < 0) {
      fails++;
      continue;
    }
    hist[n < 4 ? n : 4]++;
    pts += (int)cc.len;
    res = worst_residual(&cc, &q, v, w);
    worst_res = fmax(worst_res, res);
    bad_res += res > 1e-12;
    if (it < CASES_DENSE) {
      double e = dense_error(&cc, &q, v, w, &dense_pts);
      worst_chord = fmax(worst_chord, e);
      if (e > TOL) {
        bad_chord++;
        fprintf(stderr, "case %d: %d components, dense point %.3g mm off\n", it, n, e);
        if (getenv("GDBG")) {
          for (int k = 0; k < 9; k++)
            fprintf(stderr, "%.17g,", q.Q[k]);
          for (int k = 0; k < 3; k++)
            fprintf(stderr, "%.17g,", q.b[k]);
          fprintf(stderr, "%.17g | %g %g %g | %g %g %g\n", q.c, v[0], v[1], v[2], w[0], w[1], w[2]);
        }
      }
    }
  }
  printf("general: %d cases, %d points, components 0/1/2/3/4+: %d %d %d %d %d\n", CASES_GEN, pts,
         hist[0], hist[1], hist[2], hist[3], hist[4]);
  printf("general: worst residual %.3g, worst dense distance %.3g mm (tol %g, %d dense points)\n",
         worst_res, worst_chord, TOL, dense_pts);
  CHECK(fails == 0, "%d cases failed", fails);
  CHECK(bad_res == 0, "%d cases with points off f = g = v_h.n = 0", bad_res);
  CHECK(bad_chord == 0, "%d cases with chord error above tol", bad_chord);
  CHECK(hist[1] + hist[2] + hist[3] + hist[4] > CASES_GEN / 2, "most cases have a curve");
  swarf_char_curve_clear(&cc);
}

/* Rational rotation from the Cayley map of (p, q, r): R = ((1-s) I + 2 u u^T + 2 [u]x)/(1+s). */
static void cayley(const double u[3], double R[9]) {
  double s = tk_dot(u, u), W[9] = {0, -u[2], u[1], u[2], 0, -u[0], -u[1], u[0], 0};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      R[3 * i + j] = ((i == j) * (1.0 - s) + 2.0 * u[i] * u[j] + 2.0 * W[3 * i + j]) / (1.0 + s);
}

static void mat_vec(const double R[9], const double x[3], double y[3]) {
  for (int i = 0; i < 3; i++)
    y[i] = R[3 * i] * x[0] + R[3 * i + 1] * x[1] + R[3 * i + 2] * x[2];
}

/* The revolution QSS h6 turned by R: Q' = R diag(a, a, b) R^T, b' = R (c, d, e). */
static void turned_qss(const double h6[6], const double R[9], swarf_qss_general *q) {
  double D[3] = {h6[0], h6[0], h6[1]}, lin[3] = {h6[2], h6[3], h6[4]};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double a = 0.0;
      for (int k = 0; k < 3; k++)
        a += R[3 * i + k] * D[k] * R[3 * j + k];
      q->Q[3 * i + j] = a;
    }
  mat_vec(R, lin, q->b);
  q->c = h6[5];
}

/* Worst distance of a's surface points (turned by R^T) to b's polylines. */
static double curve_gap(const swarf_char_curve *a, const double R[9], const swarf_char_curve *b) {
  double worst = 0.0;
  for (size_t i = 0; i < a->len; i++) {
    double x[3];
    for (int k = 0; k < 3; k++)
      x[k] = R[k] * a->pts[i].x[0] + R[3 + k] * a->pts[i].x[1] + R[6 + k] * a->pts[i].x[2];
    worst = fmax(worst, dist_to_curve(b, x));
  }
  return worst;
}

static int exact_ok(const swarf_envelope_exact *E) {
  double prev = -2.0;
  if (E->kind != SWARF_ENV_CURVE && E->kind != SWARF_ENV_GREAT_CIRCLE) return 0;
  for (int i = 0; i < E->nroots; i++) {
    double zi = arf_get_d(arb_midref(E->roots[i].z), ARF_RND_NEAR);
    if (E->roots[i].multiplicity % 2 == 0 || fabs(fabs(zi) - 1.0) < NEAR || zi - prev < NEAR)
      return 0;
    prev = zi;
  }
  return 1;
}

static void test_revolution(void) {
  tk_rng rng = {0x70901093ULL};
  swarf_char_curve cg, cr;
  int compared = 0, bad = 0, bad_gap = 0, gap_compared = 0;
  double worst_gap = 0.0;
  swarf_char_curve_init(&cg), swarf_char_curve_init(&cr);
  for (int it = 0; it < CASES_REV; it++) {
    fmpq h6[6];
    swarf_xquad xq;
    swarf_xmotion m;
    swarf_envelope_exact E;
    swarf_qss_general q;
    double hd[6], v[3], w[3], R[9], u[3], vr[3], wr[3];
    int turn = it % 2, n;
    ek_vec_init(h6, 6);
    swarf_xquad_init(&xq), swarf_xmotion_init(&m), swarf_envelope_exact_init(&E);
    ek_random_case(&rng, h6, &m, it % 3 == 0);
    swarf_xquad_set_revolution(&xq, h6);
    swarf_envelope_exact_compute(&E, &xq, m.v, m.omega);
    ek_vec_get_d(hd, h6, 6), ek_vec_get_d(v, m.v, 3), ek_vec_get_d(w, m.omega, 3);
    for (int k = 0; k < 3; k++)
      u[k] = turn ? (double)ek_int(&rng, -3, 3) / (double)ek_int(&rng, 1, 4) : 0.0;
    cayley(u, R);
    if (exact_ok(&E)) {
      turned_qss(hd, R, &q);
      mat_vec(R, v, vr), mat_vec(R, w, wr);
      n = (swarf_char_curve_compute_qss_general(&cg, &q, zero3, I3, vr, wr, TOL) == SWARF_OK
               ? (int)cg.ncomp
               : -1);
      compared++;
      if (n != E.ncomp) {
        bad++;
        fprintf(stderr, "case %d: exact %d components, general fast path %d\n", it, E.ncomp, n);
      }
      if (!turn && n == E.ncomp) {
        double g = INFINITY;
        if ((swarf_char_curve_compute_qss12(&cr, hd, zero3, I3, v, w, TOL) == SWARF_OK
                 ? (int)cr.ncomp
                 : -1) == n)
          g = fmax(curve_gap(&cg, R, &cr), curve_gap(&cr, I3, &cg));
        worst_gap = fmax(worst_gap, g);
        gap_compared++;
        bad_gap += g > 2.0 * TOL;
        if (g > 2.0 * TOL)
          fprintf(stderr, "case %d: general curve %.3g mm from compute_qss12\n", it, g);
      }
    }
    swarf_xquad_clear(&xq), swarf_xmotion_clear(&m), swarf_envelope_exact_clear(&E);
    ek_vec_clear(h6, 6);
  }
  printf("revolution: %d compared with the exact count, worst gap to compute_qss12 %.3g mm\n",
         compared, worst_gap);
  CHECK(compared > CASES_REV / 2, "most cases compared (%d)", compared);
  CHECK(bad == 0, "component counts differ in %d cases", bad);
  printf("revolution: %d unrotated curves compared with compute_qss12, %d more than 2 tol off\n",
         gap_compared, bad_gap);
  CHECK(gap_compared > CASES_REV / 4, "most unrotated cases compared (%d)", gap_compared);
  CHECK(bad_gap == 0, "%d curves differ from compute_qss12 by more than 2 tol", bad_gap);
  swarf_char_curve_clear(&cg), swarf_char_curve_clear(&cr);
}

int main(void) {
  test_general();
  test_revolution();
  flint_cleanup();
  return check_done();
}
