/* SPDX-License-Identifier: MPL-2.0 */
/* test_sweep_rigid.c -- swept volumes under rotation (sweep_rigid.c) against
 * an independent truth: the exact cutter sdf minimised over poses 100 times
 * finer than the production time steps (plus golden-section polish), at
 * points near the envelope. Errors are stated in voxels of VOXEL mm, beside
 * stamping (the cutter at the production's own poses, nothing between).
 *   - rotary only: a ball held still while A turns 90 degrees (a torus
 *     section; checked against the torus in closed form too);
 *   - 4th-axis helix: X and A together (joint kinematics, xyza);
 *   - 5-axis: A and C change together (xyzac-trt, TCP and joint mode), B and
 *     C (xyzbc-trt; the head machines xyzbc-hh and xyzbc-ht in joint mode),
 *     A and B (xyzab-tdr);
 *   - the nearest points lie on the characteristic curves of their time;
 *   - the pruned search (swarf_sweep_sdf_range, what the stock calls) against
 *     the full certified one, a short move as the impeller's.
 * All through the general search (SWARF_SWEEP_GENERAL=1): the ball end
 * mill's own path is test_sweep_ball's.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "engine_private.h" /* the sweep's typed data */
#include "swarf_reference.h"
#include "testkit.h"

#define VOXEL 0.1
#define NPTS 800

/* Stamping: the cutter at the n + 1 production poses only. */
static double stamp(const swarf_cutter *c, const swarf_motion *m, const double p[3], int n) {
  double best = INFINITY;
  for (int i = 0; i <= n; i++)
    best = fmin(best, tk_rigid_instance(c, m, p, (double)i / n));
  return best;
}

/* A point within 2 voxels of the surface of a random instance. */
static void near_point(tk_rng *r, const swarf_cutter *c, const swarf_motion *m, double p[3]) {
  double n[3], x[3], t[3], U[9], a = tk_uniform(r, 0.0, 1.0), off = tk_uniform(r, -2, 2) * VOXEL;
  tk_unit(r, n);
  swarf_cutter_point(c, n, x);
  for (int k = 0; k < 3; k++)
    x[k] += off * n[k];
  swarf_motion_eval(m, a, t, U);
  for (int k = 0; k < 3; k++)
    p[k] = t[k] + U[3 * k] * x[0] + U[3 * k + 1] * x[1] + U[3 * k + 2] * x[2];
}

typedef struct {
  double max_err, max_stamp, mean_stamp;
  int steps;
} errors;

static errors compare(const char *name, const swarf_cutter *c, const swarf_motion *m, int seed) {
  swarf_sweep s;
  tk_rng r = {0x9e3779b97f4a7c15ull * (unsigned)seed + 1};
  errors e = {0, 0, 0, 0};
  swarf_sweep_init_voxel(&s, c, m, VOXEL);
  e.steps = swarf_sweep_cdata(&s)->u.rigid.n;
  for (int i = 0; i < NPTS; i++) {
    double p[3], a, lo[3], hi[3];
    near_point(&r, c, m, p);
    double d = swarf_sweep_sdf(&s, p, &a), tr = tk_rigid_truth(c, m, p, 100 * e.steps);
    double st = stamp(c, m, p, e.steps);
    e.max_err = fmax(e.max_err, fabs(d - tr) / VOXEL);
    e.max_stamp = fmax(e.max_stamp, fabs(st - tr) / VOXEL);
    e.mean_stamp += fabs(st - tr) / VOXEL / NPTS;
    swarf_sweep_bounds(&s, lo, hi);
    for (int k = 0; k < 3; k++)
      CHECK(p[k] > lo[k] - 2 * VOXEL && p[k] < hi[k] + 2 * VOXEL, "%s: point in bounds", name);
  }
  printf("%-28s %3d steps: max error %.2e voxel; stamping at the same poses: max %.3f, mean %.3f "
         "voxel\n",
         name, e.steps, e.max_err, e.max_stamp, e.mean_stamp);
  CHECK(e.max_err < 0.01, "%s: max error %g voxel (aim 0.1)", name, e.max_err);
  CHECK(e.max_stamp > 5 * e.max_err && e.max_stamp > 0.05, "%s: stamping worse (%g vs %g)", name,
        e.max_stamp, e.max_err);
  return e;
}

static swarf_motion make(const char *machine, const double s6[6], const double e6[6]) {
  swarf_motion m;
  CHECK(tk_machine_move(machine, s6, e6, &m) == SWARF_OK, "motion on %s", machine);
  CHECK(m.kind == SWARF_MOTION_RIGID, "%s: rigid", machine);
  return m;
}

/* Ball of radius 2 with its tip held at machine (0, 0, 10) while A turns 0 -> 90
 * degrees: in the workpiece its centre runs on the circle of radius 12 about X
 * in the quadrant y, z >= 0. Below the tip (rho < 10) the ball is the nearest
 * part: the sdf is the torus's, sqrt((rho - 12)^2 + x^2) - 2. */
static void test_rotary_only(void) {
  swarf_cutter c;
  swarf_sweep s;
  const double s6[6] = {0, 0, 10, 0, 0, 0}, e6[6] = {0, 0, 10, 90, 0, 0};
  swarf_motion m = make("xyza", s6, e6);
  tk_rng r = {12345};
  double worst = 0.0;
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 4.0, 0, 12.0, NULL);
  compare("rotary only, ball (torus)", &c, &m, 1);
  swarf_sweep_init_voxel(&s, &c, &m, VOXEL);
  for (int i = 0; i < 400; i++) {
    double th = tk_uniform(&r, 0.05, 1.52), rho = tk_uniform(&r, 9.0, 9.9),
           x = tk_uniform(&r, -1, 1);
    double p[3] = {x, rho * sin(th), rho * cos(th)};
    double d = swarf_sweep_sdf(&s, p, NULL), torus = hypot(rho - 12.0, x) - 2.0;
    worst = fmax(worst, fabs(d - torus));
  }
  printf("rotary only vs closed-form torus: max error %.2e voxel\n", worst / VOXEL);
  CHECK(worst < 1e-4, "torus section: %g mm", worst);
}

static void test_helix_4th(void) {
  swarf_cutter c;
  const double s6[6] = {-6, 0, 8, 0, 0, 0}, e6[6] = {6, 0, 8, 120, 0, 0};
  swarf_motion m = make("xyza,pivot=1,-1", s6, e6);
  swarf_cutter_init(&c, SWARF_CUTTER_FLAT, 3.0, 0, 10.0, NULL);
  compare("4th-axis helix, flat", &c, &m, 2);
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 3.0, 0, 10.0, NULL);
  compare("4th-axis helix, ball", &c, &m, 3);
}

static void test_five_axis(void) {
  swarf_cutter c;
  const double s6[6] = {1, 2, 3, 10, 0, -30}, e6[6] = {4, 0, 2, 40, 0, 60};
  swarf_motion m = make("xyzac-trt", s6, e6);
  swarf_cutter_init(&c, SWARF_CUTTER_BULL, 6.0, 1.0, 20.0, NULL);
  compare("5-axis A+C, TCP, bull", &c, &m, 4);
  m = make("xyzac-trt,mode=joint,pivot=0,5,-20", s6, e6);
  compare("5-axis A+C, joint, bull", &c, &m, 5);
  const double b0[6] = {1, 2, 3, 0, 10, -30}, b1[6] = {4, 0, 2, 0, -35, 45};
  m = make("xyzbc-trt", b0, b1);
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 4.0, 0, 16.0, NULL);
  compare("5-axis B+C, TCP, ball", &c, &m, 6);
  /* the machines whose head tilts (the cutter turns about the head's pivot in
   * joint mode) and the dual table */
  m = make("xyzbc-hh,mode=joint,head=25", b0, b1);
  compare("head-head B+C, joint, ball", &c, &m, 7);
  m = make("xyzbc-ht,mode=joint,pivot=2,-3,head=25", b0, b1);
  swarf_cutter_init(&c, SWARF_CUTTER_BULL, 6.0, 1.0, 20.0, NULL);
  compare("head-table B+C, joint, bull", &c, &m, 8);
  const double a0[6] = {1, 2, 3, 10, 20, 0}, a1[6] = {4, 0, 2, 55, -25, 0};
  m = make("xyzab-tdr", a0, a1);
  compare("dual table A+B, TCP, bull", &c, &m, 9);
}

/* Outside points whose nearest instance is inside the move: the nearest
 * surface point lies on the characteristic curve of that time. */
static void test_on_characteristic(void) {
  swarf_cutter c;
  swarf_sweep s;
  swarf_char_curve cc;
  const double s6[6] = {1, 2, 3, 10, 0, -30}, e6[6] = {4, 0, 2, 40, 0, 60};
  swarf_motion m = make("xyzac-trt", s6, e6);
  tk_rng r = {777};
  double worst = 0.0;
  int used = 0;
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 4.0, 0, 16.0, NULL);
  swarf_sweep_init_voxel(&s, &c, &m, VOXEL);
  swarf_char_curve_init(&cc);
  for (int i = 0; i < 1200; i++) {
    double p[3], a, t[3], U[9], d, x[3], best = INFINITY;
    near_point(&r, &c, &m, p);
    d = swarf_sweep_sdf(&s, p, &a);
    if (d < 0.2 * VOXEL || a < 0.02 || a > 0.98) continue;
    swarf_motion_eval(&m, a, t, U);
    for (int k = 0; k < 3; k++)
      x[k] = p[k];
    /* nearest surface point, world frame: p - d * grad (grad by differences) */
    double gw[3];
    for (int k = 0; k < 3; k++) {
      double pp[3] = {p[0], p[1], p[2]};
      pp[k] += 1e-6;
      gw[k] = (tk_rigid_instance(&c, &m, pp, a) - tk_rigid_instance(&c, &m, p, a)) / 1e-6;
    }
    for (int k = 0; k < 3; k++)
      x[k] = p[k] - d * gw[k];
    if ((swarf_sweep_char_curve(&s, a, 1e-3, &cc) == SWARF_OK ? (int)cc.ncomp : -1) <= 0) continue;
    for (size_t j = 0; j + 1 < cc.len; j++)
      best = fmin(best, tk_seg_dist(x, cc.pts[j].w, cc.pts[j + 1].w));
    worst = fmax(worst, best);
    used++;
  }
  swarf_char_curve_clear(&cc);
  printf("nearest points on the characteristic curves: %d points, max distance %.2e mm\n", used,
         worst);
  CHECK(used > 50, "enough points (%d)", used);
  CHECK(worst < 0.01, "nearest points on the characteristic curve: %g mm", worst);
}

/* swarf_sweep_sdf_range's contract against swarf_sweep_sdf (certified to
 * 1e-6 mm) on a short 5-axis move like the impeller's (0.4 mm, 3 and 5
 * degrees, D4 L30, 0.2 mm voxels), for a ball, a flat and a bull nose: for
 * windows (lo, hi) below, around and above each point's value (up to 3 mm
 * off, where the bound from the move's two ends alone decides): within 2e-6 mm
 * of the sdf inside the window; at most lo (and not below the sdf) under it;
 * at least hi above it. */
static void test_range_cutter(const char *name, swarf_cutter_shape fam, double corner) {
  swarf_cutter c;
  swarf_sweep s;
  const double s6[6] = {10.2, -3.1, 25.0, 20, 0, 40}, e6[6] = {10.5, -2.9, 24.8, 23, 0, 45};
  static const double off[7] = {-3.0, -0.3, -0.05, 0.0, 0.05, 0.3, 3.0};
  swarf_motion m = make("xyzac-trt", s6, e6);
  tk_rng r = {0x2545f4914f6cdd1dull};
  double worst = 0.0;
  int n = 0, above = 0;
  swarf_cutter_init(&c, fam, 4.0, corner, 30.0, NULL);
  swarf_sweep_init_voxel(&s, &c, &m, 0.2);
  for (int i = 0; i < 400; i++) {
    double p[3], d;
    near_point(&r, &c, &m, p);
    for (int k = 0; k < 3; k++)
      p[k] += tk_uniform(&r, -0.6, 0.6);
    d = swarf_sweep_sdf(&s, p, NULL);
    for (int w = 0; w < 7; w++) {
      double lo = d + off[w] - 0.1, hi = d + off[w] + 0.1;
      double v = swarf_sweep_sdf_range(&s, p, lo, hi);
      if (d >= lo && d < hi) {
        worst = fmax(worst, fabs(v - d));
        CHECK(fabs(v - d) <= 2e-6, "%s: range in window: %.9g vs sdf %.9g", name, v, d);
        n++;
      } else if (d < lo) {
        CHECK(v <= lo + 2e-6 && v >= d - 2e-6, "%s: range below lo %g: %.9g (sdf %.9g)", name, lo,
              v, d);
      } else {
        CHECK(v >= hi - 2e-6, "%s: range above hi %g: %.9g (sdf %.9g)", name, hi, v, d);
        above++;
      }
    }
  }
  printf("%s: range search vs full search: %d values in their window, max difference %.2e mm, "
         "%d above\n",
         name, n, worst, above);
  CHECK(n > 400, "%s: windows holding the value: %d", name, n);
}

static void test_range(void) {
  test_range_cutter("ball", SWARF_CUTTER_BALL, 0.0);
  test_range_cutter("flat", SWARF_CUTTER_FLAT, 0.0);
  test_range_cutter("bull", SWARF_CUTTER_BULL, 0.5);
}

int main(void) {
  /* the general search for every cutter (a ball's own path: test_sweep_ball) */
  setenv("SWARF_SWEEP_GENERAL", "1", 1);
  if (!swarf_reference_built())
    printf("note: built without the reference paths: ball end mills take their own path\n");
  test_rotary_only();
  test_helix_4th();
  test_five_axis();
  test_on_characteristic();
  test_range();
  { /* no sweep: NAN, not a NULL dereference */
    const double p[3] = {0, 0, 0};
    CHECK(isnan(swarf_sweep_rigid_sdf(NULL, p, NULL)), "NULL sweep: NAN");
  }
  return check_done();
}
