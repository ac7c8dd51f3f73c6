/* SPDX-License-Identifier: MPL-2.0 */
/* test_charcurve.c -- characteristic curves against independent truths:
 * the paper's Example 2 (ENVELOPE.md Fact 3: branch points, one component,
 * the slice z0 = 1/2 and its point P of eq. 20, the surface points of eq. 4);
 * for cutters under pure translation the great circle n . v = 0 mapped by
 * x_h (with the ruling and face segments), chord error under tol both ways;
 * with rotation, the characteristic condition (v + omega x x) . n = 0 on every
 * point and the chord error against the slice closed form (swarf_char_gauss_slice
 * densely in z, mapped by swarf_cutter_point); the degenerate motions. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "testkit.h"

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double zero3[3] = {0, 0, 0};

static void check_layout(const swarf_char_curve *cc, int ncomp, const char *what) {
  CHECK((int)cc->ncomp == ncomp, "%s: %d components (got %zu)", what, ncomp, cc->ncomp);
  CHECK(cc->start[0] == 0 && cc->start[cc->ncomp] == cc->len, "%s: start[] covers pts", what);
  for (size_t k = 0; k < cc->ncomp; k++) {
    const swarf_char_point *a = &cc->pts[cc->start[k]], *b = &cc->pts[cc->start[k + 1] - 1];
    CHECK(cc->start[k + 1] - cc->start[k] >= 4, "%s: component %zu has points", what, k);
    CHECK(tk_dist(a->x, b->x) == 0.0, "%s: component %zu is closed", what, k);
  }
}

static void test_example2(void) {
  /* h = x^2 + y^2 - z^2 (a = 1, b = -1): phi(z) = -2 z^2 + 1, phi'(z) = -4 z. */
  const swarf_qss q = {1.0, -1.0, 0.0, 0.0};
  const double v[3] = {1.0, -0.6, 0.8}, w[3] = {2.0 / 3, 1.0 / 3, 2.0 / 3};
  double z[8], n[2][3], zmin = 1, zmax = -1, fmax_ = 0;
  swarf_char_curve cc;
  int nb = swarf_char_branch_points_qss(&q, v, w, z, 8);
  CHECK(nb == 2, "Example 2: two real branch points (got %d)", nb);
  CHECK_NEAR(z[0], -0.980159130274109, 1e-12, "z1");
  CHECK_NEAR(z[1], 0.918957355604119, 1e-12, "z2");
  printf("Example 2 branch points: %.17g %.17g\n", z[0], z[1]);
  CHECK(swarf_char_gauss_slice(-2.0, v, w, 0.5, n) == 2, "slice z0 = 1/2 has two points");
  /* A profile's infinite slope at a pole (swarf_cutter_profile at z = +-1):
   * no point, never NaN normals (the sanitized suite met them here: UBSan,
   * NaN converted to an integer in this test's reference grid). */
  CHECK(swarf_char_gauss_slice(INFINITY, v, w, 1.0, n) == 0,
        "infinite slope at the pole: no point");
  CHECK(swarf_char_gauss_slice(-INFINITY, v, w, -1.0, n) == 0, "infinite slope, other pole");
  CHECK(swarf_char_gauss_slice(NAN, v, w, 0.5, n) == 0, "NaN slope: no point");
  for (int k = 0; k < 2; k++) {
    CHECK_NEAR(5 * n[k][0] + 11 * n[k][1] + 6, 0.0, 1e-14, "5x + 11y + 6 = 0");
    CHECK_NEAR(n[k][0] * n[k][0] + n[k][1] * n[k][1], 0.75, 1e-14, "x^2 + y^2 = 3/4");
  }
  {
    double px = -15.0 / 73 + 77.0 / 292 * sqrt(6.0), py = -33.0 / 73 - 35.0 / 292 * sqrt(6.0);
    double d0 = hypot(n[0][0] - px, n[0][1] - py), d1 = hypot(n[1][0] - px, n[1][1] - py);
    CHECK(fmin(d0, d1) < 1e-14, "P of eq. 20 is one of them (%.3g)", fmin(d0, d1));
  }
  swarf_char_curve_init(&cc);
  CHECK((swarf_char_curve_compute_qss(&cc, &q, zero3, I3, v, w, 1e-4) == SWARF_OK ? (int)cc.ncomp
                                                                                  : -1) == 1,
        "one component");
  check_layout(&cc, 1, "Example 2");
  for (size_t i = 0; i < cc.len; i++) {
    const double *m = cc.pts[i].n, *x = cc.pts[i].x;
    double f = 15 * m[0] - 20 * m[0] * m[2] - 9 * m[1] + 40 * m[1] * m[2] + 12 * m[2]; /* eq. 19 */
    double r2 = m[0] * m[0] + m[1] * m[1], xx = m[0] * (-r2 + m[2] * m[2] + 2);
    fmax_ = fmax(fmax_, fabs(f));
    zmin = fmin(zmin, m[2]);
    zmax = fmax(zmax, m[2]);
    CHECK_NEAR(tk_dot(m, m), 1.0, 1e-14, "|n| = 1");
    CHECK_NEAR(x[0], xx, 1e-13, "eq. 4 x");
    CHECK_NEAR(x[2], 2 * m[2] * m[2] * m[2] - 3 * m[2], 1e-13, "Z = 2z^3 - 3z");
  }
  CHECK(fmax_ < 1e-12, "eq. 19: |15 f| <= %.3g", fmax_);
  CHECK(fabs(zmin - z[0]) < 1e-12 && fabs(zmax - z[1]) < 1e-12, "the curve spans [z1, z2]");
  printf("Example 2: %zu points, max |15 f| = %.3g\n", cc.len, fmax_);
  swarf_char_curve_clear(&cc);
}

/* Distance from p to the polyline pts[i0, i1) (world points). */
static double poly_dist(const swarf_char_curve *cc, const double p[3]) {
  double best = INFINITY;
  for (size_t k = 0; k < cc->ncomp; k++)
    for (size_t i = cc->start[k]; i + 1 < cc->start[k + 1]; i++)
      best = fmin(best, tk_seg_dist(p, cc->pts[i].x, cc->pts[i + 1].x));
  return best;
}

/* ---- The true curve of a pure translation, as a dense point set ---------- */

#define REF_STEP 1e-4 /* spacing of reference points, mm */
#define CELL 0.01     /* grid cell, mm */

typedef struct {
  double (*p)[3];
  unsigned long long *key;
  size_t n, cap;
} refset;

static void ref_push(refset *r, const double x[3]) {
  if (r->n == r->cap) {
    r->cap = r->cap ? 2 * r->cap : 1 << 16;
    r->p = realloc(r->p, r->cap * sizeof *r->p);
  }
  for (int k = 0; k < 3; k++)
    r->p[r->n][k] = x[k];
  r->n++;
}

static void great_circle(const double v[3], double th, double m[3]) {
  double u[3], e1[3], e2[3], l = sqrt(tk_dot(v, v));
  for (int k = 0; k < 3; k++)
    u[k] = v[k] / l;
  e1[0] = -u[1], e1[1] = u[0], e1[2] = 0;
  if (hypot(e1[0], e1[1]) < 1e-9) e1[0] = 1, e1[1] = 0;
  l = sqrt(tk_dot(e1, e1));
  for (int k = 0; k < 3; k++)
    e1[k] /= l;
  tk_cross(u, e1, e2);
  for (int k = 0; k < 3; k++)
    m[k] = cos(th) * e1[k] + sin(th) * e2[k];
}

/* Points after x0 up to x1 (angles t0, t1) spaced <= REF_STEP: split the
 * angle while the points move; a gap that survives 45 splits is a ruling or
 * face segment of x_h's kink, straight: fill it. */
static void ref_span(refset *r, const swarf_cutter *c, const double v[3], double t0,
                     const double x0[3], double t1, const double x1[3], int depth) {
  double tm = 0.5 * (t0 + t1), m[3], xm[3];
  if (tk_dist(x0, x1) <= REF_STEP) {
    ref_push(r, x1);
    return;
  }
  if (depth >= 45) {
    int n = (int)ceil(tk_dist(x0, x1) / REF_STEP);
    for (int j = 1; j <= n; j++) {
      double y[3];
      for (int k = 0; k < 3; k++)
        y[k] = x0[k] + (x1[k] - x0[k]) * j / n;
      ref_push(r, y);
    }
    return;
  }
  great_circle(v, tm, m);
  swarf_cutter_point(c, m, xm);
  ref_span(r, c, v, t0, x0, tm, xm, depth + 1);
  ref_span(r, c, v, tm, xm, t1, x1, depth + 1);
}

static unsigned long long cell_key(const double x[3], int dx, int dy, int dz) {
  long long i = (long long)floor(x[0] / CELL) + dx + (1 << 20);
  long long j = (long long)floor(x[1] / CELL) + dy + (1 << 20);
  long long k = (long long)floor(x[2] / CELL) + dz + (1 << 20);
  return ((unsigned long long)i << 42) | ((unsigned long long)j << 21) | (unsigned long long)k;
}

static refset *sort_ref;
static int by_key(const void *a, const void *b) {
  unsigned long long ka = sort_ref->key[*(const size_t *)a], kb = sort_ref->key[*(const size_t *)b];
  return ka < kb ? -1 : ka > kb;
}

/* Sort the points by grid cell for ref_dist. */
static void ref_index(refset *r) {
  size_t *idx;
  double(*p)[3];
  r->key = malloc(r->n * sizeof *r->key);
  idx = malloc(r->n * sizeof *idx);
  p = malloc(r->n * sizeof *p);
  for (size_t i = 0; i < r->n; i++)
    r->key[i] = cell_key(r->p[i], 0, 0, 0), idx[i] = i;
  sort_ref = r;
  qsort(idx, r->n, sizeof *idx, by_key);
  for (size_t i = 0; i < r->n; i++)
    memcpy(p[i], r->p[idx[i]], sizeof p[i]);
  for (size_t i = 0; i < r->n; i++)
    r->key[i] = cell_key(p[i], 0, 0, 0);
  free(r->p);
  free(idx);
  r->p = p;
}

static void ref_build(refset *r, const swarf_cutter *c, const double v[3]) {
  double x0[3], m[3];
  memset(r, 0, sizeof *r);
  for (int i = 0; i < 64; i++) {
    double t0 = 2 * tk_pi * i / 64 + 1e-7, t1 = 2 * tk_pi * (i + 1) / 64 + 1e-7, x1[3];
    great_circle(v, t0, m);
    swarf_cutter_point(c, m, x0);
    if (i == 0) ref_push(r, x0);
    great_circle(v, t1, m);
    swarf_cutter_point(c, m, x1);
    ref_span(r, c, v, t0, x0, t1, x1, 0);
  }
  ref_index(r);
}

/* Distance to the nearest reference point, if within one cell; else 1. */
static double ref_dist(const refset *r, const double x[3]) {
  double best = 1.0;
  for (int dx = -1; dx <= 1; dx++)
    for (int dy = -1; dy <= 1; dy++)
      for (int dz = -1; dz <= 1; dz++) {
        unsigned long long k = cell_key(x, dx, dy, dz);
        size_t lo = 0, hi = r->n;
        while (lo < hi) {
          size_t mid = (lo + hi) / 2;
          if (r->key[mid] < k)
            lo = mid + 1;
          else
            hi = mid;
        }
        for (size_t i = lo; i < r->n && r->key[i] == k; i++)
          best = fmin(best, tk_dist(x, r->p[i]));
      }
  return best;
}

static void test_translation(const swarf_cutter *c, const double v[3], const char *what) {
  const double tol = 1e-3;
  swarf_char_curve cc;
  refset ref;
  double worst_on = 0, worst_nv = 0, worst_cover = 0, worst_chord = 0;
  ref_build(&ref, c, v);
  swarf_char_curve_init(&cc);
  CHECK((swarf_char_curve_compute(&cc, c, zero3, I3, v, zero3, tol) == SWARF_OK ? (int)cc.ncomp
                                                                                : -1) >= 1,
        "%s: a curve", what);
  for (size_t i = 0; i < cc.len; i++) {
    worst_nv = fmax(worst_nv, fabs(tk_dot(cc.pts[i].n, v)) / sqrt(tk_dot(v, v)));
    worst_on = fmax(worst_on, fabs(swarf_cutter_sdf(c, cc.pts[i].x)));
    CHECK_NEAR(tk_dot(cc.pts[i].n, cc.pts[i].n), 1.0, 1e-14, "|n| = 1");
  }
  for (size_t i = 0; i < ref.n; i += 7)
    worst_cover = fmax(worst_cover, poly_dist(&cc, ref.p[i]));
  for (size_t k = 0; k < cc.ncomp; k++)
    for (size_t i = cc.start[k]; i + 1 < cc.start[k + 1]; i++)
      for (int j = 1; j < 16; j++) {
        double m[3];
        for (int d = 0; d < 3; d++)
          m[d] = cc.pts[i].x[d] + (cc.pts[i + 1].x[d] - cc.pts[i].x[d]) * j / 16.0;
        worst_chord = fmax(worst_chord, ref_dist(&ref, m));
      }
  CHECK(worst_nv < 1e-12, "%s: n . v = 0 (%.3g)", what, worst_nv);
  CHECK(worst_on < 1e-12, "%s: points on the cutter (%.3g)", what, worst_on);
  CHECK(worst_cover < tol, "%s: the curve within tol of the polyline (%.3g)", what, worst_cover);
  CHECK(worst_chord < tol + REF_STEP, "%s: chord error (%.3g)", what, worst_chord);
  printf("%-28s %5zu points, %zu comp, |n.v| %.1e, on %.1e, cover %.2e, chord %.2e (tol %g)\n",
         what, cc.len, cc.ncomp, worst_nv, worst_on, worst_cover, worst_chord, tol);
  swarf_char_curve_clear(&cc);
  free(ref.p);
  free(ref.key);
}

/* ---- The true curve of any motion, slice by slice ------------------------- */

/* Surface point of branch k (0: s = +1) at slice z, or -1 off the curve. */
static int slice_point(const swarf_cutter *c, const double v[3], const double w[3], double z, int k,
                       double x[3]) {
  double phi, dphi, n[2][3], r;
  swarf_cutter_profile(c, z, &phi, &dphi);
  if (swarf_char_gauss_slice(dphi, v, w, z, n) == 0) return -1;
  r = sqrt(tk_dot(n[k], n[k]));
  for (int d = 0; d < 3; d++)
    n[k][d] /= r;
  swarf_cutter_point(c, n[k], x);
  return 0;
}

/* Reference points of branch k between slices z0 and z1 spaced <= REF_STEP
 * (bisection in z; next to a branch point it goes 45 levels deep). */
static void slice_span(refset *r, const swarf_cutter *c, const double v[3], const double w[3],
                       int k, double z0, int ok0, const double x0[3], double z1, int ok1,
                       const double x1[3], int depth) {
  double zm = 0.5 * (z0 + z1), xm[3];
  int okm;
  if ((ok0 && ok1 && tk_dist(x0, x1) <= REF_STEP) || depth >= 45 || (!ok0 && !ok1 && depth > 6))
    return;
  okm = slice_point(c, v, w, zm, k, xm) == 0;
  if (okm) ref_push(r, xm);
  slice_span(r, c, v, w, k, z0, ok0, x0, zm, okm, xm, depth + 1);
  slice_span(r, c, v, w, k, zm, okm, xm, z1, ok1, x1, depth + 1);
}

static int is_start(const swarf_char_curve *cc, size_t i) {
  for (size_t k = 0; k <= cc->ncomp; k++)
    if (cc->start[k] == i) return 1;
  return 0;
}

/* Chord error of the curve of a motion with rotation on the sphere pieces
 * (segments with both ends off the ruling and off the flat faces, where the
 * curve is one z-slice point per branch). */
static double rotation_chord(const swarf_cutter *c, const double v[3], const double w[3],
                             const swarf_char_curve *cc) {
  refset ref;
  double worst = 0.0;
  memset(&ref, 0, sizeof ref);
  for (int k = 0; k < 2; k++)
    for (int i = 0; i < 512; i++) {
      double z0 = -1.0 + i / 256.0, z1 = -1.0 + (i + 1) / 256.0, x0[3], x1[3];
      int ok0 = slice_point(c, v, w, z0, k, x0) == 0, ok1 = slice_point(c, v, w, z1, k, x1) == 0;
      if (ok0) ref_push(&ref, x0);
      slice_span(&ref, c, v, w, k, z0, ok0, x0, z1, ok1, x1, 0);
    }
  ref_index(&ref);
  for (size_t i = 0; i + 1 < cc->len; i++) {
    const swarf_char_point *p = &cc->pts[i], *q = &cc->pts[i + 1];
    if (is_start(cc, i + 1)) continue;
    if (fabs(p->n[2]) < 1e-9 || fabs(q->n[2]) < 1e-9 || fabs(p->n[2]) == 1.0 ||
        fabs(q->n[2]) == 1.0 || tk_dist(p->x, q->x) == 0.0)
      continue;
    for (int j = 1; j < 16; j++) {
      double m[3];
      for (int d = 0; d < 3; d++)
        m[d] = p->x[d] + (q->x[d] - p->x[d]) * j / 16.0;
      worst = fmax(worst, ref_dist(&ref, m));
    }
  }
  free(ref.p);
  free(ref.key);
  return worst;
}

/* chord: also check the chord error (not where a whole latitude circle is
 * characteristic, A = B = C = 0: the polyline steps across it). */
static void test_rotation(const swarf_cutter *c, const double v[3], const double w[3],
                          const char *what, int chord_too) {
  swarf_char_curve cc;
  double worst = 0, on = 0, chord, scale = sqrt(tk_dot(v, v)) + sqrt(tk_dot(w, w)) * c->length;
  double t[3] = {1, 2, 3}, U[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
  int n;
  swarf_char_curve_init(&cc);
  n = (swarf_char_curve_compute(&cc, c, t, U, v, w, 1e-3) == SWARF_OK ? (int)cc.ncomp : -1);
  CHECK(n >= 1, "%s: components (%d)", what, n);
  for (size_t i = 0; i < cc.len; i++) {
    const swarf_char_point *p = &cc.pts[i];
    double wx[3], f;
    tk_cross(w, p->x, wx);
    f = tk_dot(v, p->n) + tk_dot(wx, p->n);
    worst = fmax(worst, fabs(f) / scale);
    on = fmax(on, fabs(swarf_cutter_sdf(c, p->x)));
    CHECK(isfinite(p->w[0]) && fabs(p->w[0] - (1 + p->x[1] * -1.0)) < 1e-12 &&
              fabs(p->w[1] - (2 + p->x[0])) < 1e-12 && fabs(p->w[2] - (3 + p->x[2])) < 1e-12,
          "%s: w = t + U x", what);
  }
  CHECK(worst < 1e-12, "%s: (v + omega x x) . n = 0 (%.3g relative)", what, worst);
  CHECK(on < 1e-12, "%s: points on the cutter (%.3g)", what, on);
  chord = chord_too ? rotation_chord(c, v, w, &cc) : 0.0;
  CHECK(chord < 1e-3 + REF_STEP, "%s: chord error (%.3g)", what, chord);
  printf("%-28s %5zu points, %zu comp, |f|/scale %.1e, chord %.2e (tol 0.001)\n", what, cc.len,
         cc.ncomp, worst, chord);
  swarf_char_curve_clear(&cc);
}

static void test_degenerate(const swarf_cutter *c) {
  swarf_char_curve cc;
  const double spin[3] = {0, 0, 2.5}, down[3] = {0, 0, -3};
  swarf_char_curve_init(&cc);
  CHECK((swarf_char_curve_compute(&cc, c, zero3, I3, zero3, zero3, 1e-3) == SWARF_OK ? (int)cc.ncomp
                                                                                     : -1) == 0,
        "still: none");
  CHECK((swarf_char_curve_compute(&cc, c, zero3, I3, zero3, spin, 1e-3) == SWARF_OK ? (int)cc.ncomp
                                                                                    : -1) == 0,
        "spin: none");
  int rims = c->length > c->diameter ? 2 : 1;
  CHECK((swarf_char_curve_compute(&cc, c, zero3, I3, down, spin, 1e-3) == SWARF_OK ? (int)cc.ncomp
                                                                                   : -1) == rims,
        "plunge: rims");
  check_layout(&cc, rims, "plunge rims");
  for (size_t i = 0; i < cc.len; i++) {
    CHECK(fabs(swarf_cutter_sdf(c, cc.pts[i].x)) < 1e-12, "rim on the cutter");
    CHECK(fabs(cc.pts[i].n[2]) < 1e-15, "rim normals horizontal");
  }
  swarf_char_curve_clear(&cc);
}

int main(void) {
  swarf_cutter flat, ball, bull, sphere;
  tk_rng r = {77};
  const double vh[3] = {1, 0.5, 0}, vr[3] = {0.3, -1, 0.4}, vz[3] = {0.2, 0.1, 1};
  test_example2();
  swarf_cutter_init(&flat, SWARF_CUTTER_FLAT, 6.0, 0.0, 20.0, NULL);
  swarf_cutter_init(&ball, SWARF_CUTTER_BALL, 3.175, 0.0, 12.0, NULL);
  swarf_cutter_init(&bull, SWARF_CUTTER_BULL, 10.0, 2.0, 25.0, NULL);
  swarf_cutter_init(&sphere, SWARF_CUTTER_BALL, 4.0, 0.0, 4.0, NULL);
  const swarf_cutter *cs[4] = {&flat, &ball, &bull, &sphere};
  const char *names[4] = {"flat", "ball", "bull", "sphere"};
  for (int i = 0; i < 4; i++) {
    char what[64];
    snprintf(what, sizeof what, "%s horizontal v", names[i]);
    test_translation(cs[i], vh, what);
    snprintf(what, sizeof what, "%s ramp v", names[i]);
    test_translation(cs[i], vr, what);
    snprintf(what, sizeof what, "%s steep v", names[i]);
    test_translation(cs[i], vz, what);
    for (int j = 0; j < 3; j++) {
      double v[3], w[3];
      tk_unit(&r, v);
      tk_unit(&r, w);
      snprintf(what, sizeof what, "%s v + omega #%d", names[i], j);
      test_rotation(cs[i], v, w, what, 1);
    }
    test_degenerate(cs[i]);
  }
  {
    /* A^2 + B^2 = 0 with C = 0 on the ruling (c = 3), and with C != 0 near a pole. */
    const double v1[3] = {0, 3, 0}, w1[3] = {1, 0, 0}, v2[3] = {1, 0, 1}, w2[3] = {0, 1, 0};
    test_rotation(&flat, v1, w1, "flat A=B=C=0 on the ruling", 0);
    test_rotation(&bull, v2, w2, "bull A=B=0 at some z", 1);
  }
  return check_done();
}
