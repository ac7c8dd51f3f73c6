/* SPDX-License-Identifier: MPL-2.0 */
/* test_sweep_qss.c -- the rigid sweep (sweep_rigid.c) of a body that is not
 * a cutter: the paper's convex QSS of revolution h(N) = N_x^2 + N_y^2 +
 * 3/2 N_z^2 on the paper's Example 2 motion (ENVELOPE.md, Fact 3: U(alpha) =
 * rotation by +alpha about (2,1,2)/3, t(alpha) = alpha (1,1,0)), alpha in
 * [0, 2 atan 2] (half-angle tangent B in [0, 2]).
 *   - the body's sdf d(q) = max over unit N of (q.N - h(N)) against its
 *     closed-form surface points x_h(N) (engine.h);
 *   - the production motion against the rational half-angle poses
 *     (sin = 2B/(1+B^2), cos = (1-B^2)/(1+B^2)) and Fact 3's v at B = 2;
 *   - near-surface points: the sweep against the truth, the minimum of d over
 *     poses 100 times finer in B (half-angle poses) plus golden-section
 *     polish; stamping at the production's own poses beside it;
 *   - nearest points on the characteristic curves of
 *     swarf_char_curve_compute_qss;
 *   - removed volume in a stock: the sweep against 100x finer stamps.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "engine_private.h" /* the sweep's typed data */
#include "stock.h"
#include "testkit.h"

#define VOXEL 0.05    /* mm: the point tests */
#define VOXEL_VOL 0.1 /* mm: the stock */
#define NPTS 200
#define NCHAR 1500  /* candidate points for the characteristic check */
#define FINE 100    /* truth poses per production step */
#define FINE_VOL 10 /* truth stamps per production step, for the volume */
#define BMAX 2.0    /* alpha = 2 atan 2 */

static const swarf_qss qss = {1.0, 1.5, 0.0, 0.0};
static const double axis[3] = {2.0 / 3.0, 1.0 / 3.0, 2.0 / 3.0};

/* f(th) = q.N - h(N) on the meridian N = (sin th rho^, cos th) of q, from s = sin th, c = cos th.
 */
static double meridian_sc(double rho, double z, double s, double c, double *df, double *ddf) {
  if (df) *df = rho * c - z * s + s * c;
  if (ddf) *ddf = -rho * s - z * c + c * c - s * s;
  return rho * s + z * c - 1.0 - 0.5 * c * c;
}

static double meridian(double rho, double z, double th, double *df, double *ddf) {
  return meridian_sc(rho, z, sin(th), cos(th), df, ddf);
}

static double sn[25], cs[25]; /* sin, cos of the samples: meridian_init() (before any thread) */

static void meridian_init(void) {
  for (int k = 0; k <= 24; k++)
    sn[k] = sin(tk_pi * k / 24), cs[k] = cos(tk_pi * k / 24);
}

/* The maximiser over th in [0, pi]: best of 25 samples, then safeguarded Newton. */
static double meridian_max(double rho, double z) {
  double best = -INFINITY, th = 0.0, lo, hi;
  for (int k = 0; k <= 24; k++) {
    double f = meridian_sc(rho, z, sn[k], cs[k], NULL, NULL);
    if (f > best) best = f, th = tk_pi * k / 24;
  }
  lo = fmax(0.0, th - tk_pi / 24), hi = fmin(tk_pi, th + tk_pi / 24);
  for (int it = 0; it < 60; it++) {
    double df, ddf, next;
    meridian(rho, z, th, &df, &ddf);
    if (df > 0)
      lo = th;
    else
      hi = th;
    next = ddf < 0 ? th - df / ddf : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (fabs(next - th) < 1e-15 || hi - lo < 1e-15) break;
    th = next;
  }
  return th;
}

/* The body's signed distance, exact inside and outside (convex body). */
static double qss_sdf(const void *ctx, const double q[3], double grad[3]) {
  double rho = hypot(q[0], q[1]), th = meridian_max(rho, q[2]), g[3];
  double cx = rho > 0 ? q[0] / rho : 1.0, cy = rho > 0 ? q[1] / rho : 0.0;
  g[0] = sin(th) * cx, g[1] = sin(th) * cy, g[2] = cos(th);
  if (grad) memcpy(grad, g, sizeof g);
  return meridian(rho, q[2], th, NULL, NULL);
}

/* Surface point x_h(n) = phi(z) n + phi'(z) (e_z - z n), phi = (b-a) z^2 + e z + a + f. */
static void qss_point(const double n[3], double x[3]) {
  double z = n[2], phi = (qss.b - qss.a) * z * z + qss.e * z + qss.a + qss.f;
  double dphi = 2 * (qss.b - qss.a) * z + qss.e;
  for (int k = 0; k < 3; k++)
    x[k] = phi * n[k] + dphi * ((k == 2) - z * n[k]);
}

/* The half-angle pose: U = rotation by alpha = 2 atan B about `axis`, t = alpha (1,1,0). */
static void pose_b(double B, double t[3], double U[9]) {
  double c = (1 - B * B) / (1 + B * B), s = 2 * B / (1 + B * B), al = 2 * atan(B);
  const double *k = axis;
  const double K[9] = {0, -k[2], k[1], k[2], 0, -k[0], -k[1], k[0], 0};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      U[3 * i + j] = (i == j) * c + s * K[3 * i + j] + (1 - c) * k[i] * k[j];
  t[0] = t[1] = al, t[2] = 0.0;
}

/* d at p of the body at pose (t, U); q and the world normal if asked. */
static double at_pose(const double t[3], const double U[9], const double p[3], double nw[3]) {
  double d[3], q[3], g[3], v;
  for (int k = 0; k < 3; k++)
    d[k] = p[k] - t[k];
  for (int k = 0; k < 3; k++)
    q[k] = U[k] * d[0] + U[3 + k] * d[1] + U[6 + k] * d[2];
  v = qss_sdf(NULL, q, g);
  if (nw)
    for (int k = 0; k < 3; k++)
      nw[k] = U[3 * k] * g[0] + U[3 * k + 1] * g[1] + U[3 * k + 2] * g[2];
  return v;
}

static double at_b(double B, const double p[3]) {
  double t[3], U[9];
  pose_b(B, t, U);
  return at_pose(t, U, p, NULL);
}

/* The production motion: a RIGID TCP line turning one table axis (testkit.h). */
static swarf_motion example2(void) {
  return tk_example2(BMAX);
}

static void test_body_sdf(void) {
  tk_rng r = {42};
  double worst = 0.0, worst_g = 0.0;
  for (int i = 0; i < 2000; i++) {
    double n[3], x[3], p[3], g[3], s = tk_uniform(&r, -0.02, 0.5);
    tk_unit(&r, n);
    qss_point(n, x);
    for (int k = 0; k < 3; k++)
      p[k] = x[k] + s * n[k];
    worst = fmax(worst, fabs(qss_sdf(NULL, p, g) - s));
    worst_g = fmax(worst_g, tk_dist(g, n));
  }
  printf("QSS body sdf vs x_h(N) + s N: max error %.2e mm, normal %.2e\n", worst, worst_g);
  CHECK(worst < 1e-10, "body sdf: %g mm", worst);
  CHECK(worst_g < 1e-6, "body sdf gradient: %g", worst_g);
}

static void test_motion(const swarf_motion *m) {
  double t[3], U[9], tb[3], Ub[9], v[3], w[3], A = 2 * atan(BMAX), err = 0.0;
  const double v19[3] = {1.0, -0.6, 0.8};
  for (int i = 0; i <= 8; i++) {
    double B = BMAX * i / 8, a = 2 * atan(B) / A;
    swarf_motion_eval(m, a, t, U);
    pose_b(B, tb, Ub);
    err = fmax(err, tk_dist(t, tb));
    for (int k = 0; k < 9; k++)
      err = fmax(err, fabs(U[k] - Ub[k]));
  }
  swarf_motion_velocity(m, 1.0, NULL, v, w);
  for (int k = 0; k < 3; k++)
    v[k] /= A, w[k] /= A;
  printf("Example 2 motion vs half-angle poses: max difference %.2e\n", err);
  CHECK(err < 1e-12, "motion vs half-angle poses: %g", err);
  CHECK(tk_dist(v, v19) < 1e-12, "v at B = 2 is (1, -3/5, 4/5) (Fact 3): %g", tk_dist(v, v19));
  CHECK(tk_dist(w, axis) < 1e-12, "omega = (2,1,2)/3: %g", tk_dist(w, axis));
}

/* Golden section in B on [lo, hi]. */
static double golden_b(const double p[3], double lo, double hi) {
  const double g = 0.6180339887498949;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), f1 = at_b(x1, p), f2 = at_b(x2, p);
  for (int it = 0; it < 60; it++) {
    if (f1 < f2)
      hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = at_b(x1, p);
    else
      lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = at_b(x2, p);
  }
  return fmin(f1, f2);
}

/* The truth: n + 1 half-angle poses evenly spaced in B, then golden section
 * around every sampled local minimum within 0.01 mm of the best (between
 * poses 1/n apart the distance changes by far less). */
static double truth(const double p[3], int n) {
  static double g[100001];
  double best = INFINITY;
  for (int i = 0; i <= n; i++) {
    double t[3], U[9];
    pose_b(BMAX * i / n, t, U);
    g[i] = tk_dist(p, t) - 1.5; /* a lower bound (|x_h| <= 3/2): exact only if it could win */
    if (g[i] < best) g[i] = at_pose(t, U, p, NULL), best = fmin(best, g[i]);
  }
  for (int i = 0; i <= n; i++) {
    double prev = i > 0 ? g[i - 1] : INFINITY, next = i < n ? g[i + 1] : INFINITY;
    if (g[i] <= prev && g[i] <= next && g[i] < best + 0.01)
      best =
          fmin(best, golden_b(p, BMAX * (i > 0 ? i - 1 : 0) / n, BMAX * (i < n ? i + 1 : n) / n));
  }
  return best;
}

static double stamp(const swarf_motion *m, const double p[3], int n) {
  double best = INFINITY, t[3], U[9];
  for (int i = 0; i <= n; i++) {
    swarf_motion_eval(m, (double)i / n, t, U);
    best = fmin(best, at_pose(t, U, p, NULL));
  }
  return best;
}

/* A point within 2 voxels of the surface of a random half-angle instance. */
static void near_point(tk_rng *r, double p[3]) {
  double n[3], x[3], t[3], U[9], off = tk_uniform(r, -2, 2) * VOXEL;
  tk_unit(r, n);
  qss_point(n, x);
  pose_b(tk_uniform(r, 0, BMAX), t, U);
  for (int k = 0; k < 3; k++)
    p[k] = t[k] + U[3 * k] * (x[0] + off * n[0]) + U[3 * k + 1] * (x[1] + off * n[1]) +
           U[3 * k + 2] * (x[2] + off * n[2]);
}

/* Distance from the nearest surface point of the instance at a to that time's
 * characteristic curve; -1 when the curve is empty. */
static double char_distance(const swarf_motion *m, const double p[3], double d, double a) {
  swarf_char_curve cc;
  double t[3], U[9], v[3], w[3], nw[3], x[3], best = INFINITY;
  swarf_motion_eval(m, a, t, U);
  swarf_motion_velocity(m, a, NULL, v, w);
  at_pose(t, U, p, nw);
  for (int k = 0; k < 3; k++)
    x[k] = p[k] - d * nw[k];
  swarf_char_curve_init(&cc);
  if ((swarf_char_curve_compute_qss(&cc, &qss, t, U, v, w, 1e-3) == SWARF_OK ? (int)cc.ncomp
                                                                             : -1) <= 0)
    best = -1;
  for (size_t j = 0; best >= 0 && j + 1 < cc.len; j++)
    best = fmin(best, tk_seg_dist(x, cc.pts[j].w, cc.pts[j + 1].w));
  swarf_char_curve_clear(&cc);
  return best;
}

static void test_points(const swarf_sweep *s, const swarf_motion *m) {
  tk_rng r = {2024};
  int n = swarf_sweep_cdata(s)->u.rigid.n;
  double max_err = 0, mean_err = 0, max_st = 0, mean_st = 0;
  for (int i = 0; i < NPTS; i++) {
    double p[3];
    near_point(&r, p);
    double d = swarf_sweep_rigid_body_sdf(s, qss_sdf, NULL, p, NULL), tr = truth(p, FINE * n);
    double st = stamp(m, p, n), e = fabs(d - tr) / VOXEL;
    max_err = fmax(max_err, e), mean_err += e / NPTS;
    max_st = fmax(max_st, fabs(st - tr) / VOXEL), mean_st += fabs(st - tr) / VOXEL / NPTS;
  }
  printf("QSS on Example 2, %d steps, %d points: max error %.2e voxel (mean %.2e); stamping at the "
         "same poses: max %.3f, mean %.3f voxel\n",
         n, NPTS, max_err, mean_err, max_st, mean_st);
  CHECK(max_err < 0.01, "QSS sweep: max error %g voxel", max_err);
  CHECK(max_st > 5 * max_err && max_st > 0.05, "stamping worse (%g vs %g)", max_st, max_err);
}

/* Outside points whose nearest instance is inside the move: the nearest
 * surface point lies on the characteristic curve of that time. */
static void test_on_characteristic(const swarf_sweep *s, const swarf_motion *m) {
  tk_rng r = {99};
  int used = 0;
  double worst = 0;
  for (int i = 0; i < NCHAR; i++) {
    double p[3], a, d;
    near_point(&r, p);
    d = swarf_sweep_rigid_body_sdf(s, qss_sdf, NULL, p, &a);
    if (d < 0.2 * VOXEL || a < 0.02 || a > 0.98) continue;
    double cd = char_distance(m, p, d, a);
    CHECK(cd >= 0, "a characteristic curve at alpha %g", a);
    worst = fmax(worst, cd), used++;
  }
  printf("nearest points on the QSS characteristic curves: %d points, max distance %.2e mm\n", used,
         worst);
  CHECK(used > 50, "enough points on characteristic curves (%d)", used);
  CHECK(worst < 0.01, "nearest points on the characteristic curve: %g mm", worst);
}

/* ---- removed volume in a stock ---------------------------------------------- */

typedef struct {
  const swarf_sweep *s;
  const swarf_motion *m;
  double t[3], U[9]; /* one pose (stamps) */
} vol_ctx;

static double sweep_cut(const void *ctx, double x, double y, double z) {
  const double p[3] = {x, y, z};
  return swarf_sweep_rigid_body_sdf(((const vol_ctx *)ctx)->s, qss_sdf, NULL, p, NULL);
}

static double pose_cut(const void *ctx, double x, double y, double z) {
  const vol_ctx *c = ctx;
  const double p[3] = {x, y, z};
  return at_pose(c->t, c->U, p, NULL);
}

/* Removed volume (mm^3) of the stamps at n + 1 poses: half-angle in B
 * (half = 1) or the production's (half = 0). */
static double stamped_volume(const double lo[3], const double hi[3], const swarf_motion *m, int n,
                             int half) {
  static vol_ctx ctx[20001];
  static swarf_stock_cut cuts[20001];
  swarf_stock *st = NULL;
  swarf_stock_new_box(lo, hi, VOXEL_VOL, 3, &st, NULL);
  double v0 = swarf_stock_volume(st), v;
  for (int i = 0; i <= n; i++) {
    if (half)
      pose_b(BMAX * i / n, ctx[i].t, ctx[i].U);
    else
      swarf_motion_eval(m, (double)i / n, ctx[i].t, ctx[i].U);
    for (int k = 0; k < 3; k++)
      cuts[i].lo[k] = ctx[i].t[k] - 1.51, cuts[i].hi[k] = ctx[i].t[k] + 1.51;
    cuts[i].sdf = pose_cut, cuts[i].ctx = &ctx[i];
  }
  CHECK(swarf_stock_remove_batch(st, cuts, (size_t)n + 1, NULL) == SWARF_OK, "stamps removed");
  v = swarf_stock_volume(st);
  swarf_stock_free(st);
  return v0 - v;
}

static void test_volume(const swarf_motion *m) {
  swarf_sweep s;
  swarf_cutter c;
  double lo[3], hi[3], v0, vs, vt, vp;
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 3.0, 0, 3.0, NULL);
  swarf_sweep_init_voxel(&s, &c, m, VOXEL_VOL);
  swarf_sweep_bounds(&s, lo, hi);
  for (int k = 0; k < 3; k++)
    lo[k] -= 0.5, hi[k] += 0.5;
  int n = swarf_sweep_cdata(&s)->u.rigid.n;
  vol_ctx ctx = {&s, m, {0}, {0}};
  swarf_stock *st = NULL;
  swarf_stock_new_box(lo, hi, VOXEL_VOL, 3, &st, NULL);
  CHECK(st != NULL, "stock");
  v0 = swarf_stock_volume(st);
  CHECK(swarf_stock_remove(st, lo, hi, sweep_cut, &ctx, NULL) == SWARF_OK, "sweep removed");
  vs = v0 - swarf_stock_volume(st);
  swarf_stock_free(st);
  vt = stamped_volume(lo, hi, m, FINE_VOL * n, 1);
  vp = stamped_volume(lo, hi, m, n, 0);
  printf("removed volume at %.2f mm voxels: sweep %.4f mm^3, truth (%d half-angle stamps) %.4f, "
         "error %+.2e (%.1e voxel^3); stamping at the %d production poses %+.4f mm^3\n",
         VOXEL_VOL, vs, FINE_VOL * n + 1, vt, vs - vt, (vs - vt) / pow(VOXEL_VOL, 3), n + 1,
         vp - vt);
  CHECK(fabs(vs - vt) < 2e-4 * vt, "swept volume %g vs truth %g", vs, vt);
  CHECK(fabs(vp - vt) > 10 * fabs(vs - vt), "stamping's volume worse (%g vs %g)", vp - vt, vs - vt);
}

int main(void) {
  swarf_motion m = example2();
  swarf_sweep s;
  swarf_cutter c; /* sizes only: a ball of radius 1.5 encloses the body (|x_h| <= 3/2) */
  meridian_init();
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 3.0, 0, 3.0, NULL);
  swarf_sweep_init_voxel(&s, &c, &m, VOXEL);
  test_body_sdf();
  test_motion(&m);
  test_points(&s, &m);
  test_on_characteristic(&s, &m);
  test_volume(&m);
  return check_done();
}
