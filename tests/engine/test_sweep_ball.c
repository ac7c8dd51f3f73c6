/* SPDX-License-Identifier: MPL-2.0 */
/* test_sweep_ball.c -- the ball end mill's rotary path (sweep_rigid_ball.c:
 * characteristic circles at the time steps, a refinement certified by
 * convexity) against two independent values at random points:
 *   - the truth: the exact cutter sdf minimised over poses 100 times finer
 *     than the production time steps, plus golden-section polish;
 *   - the general certified search (swarf_sweep_rigid_body_sdf with the
 *     cutter's sdf as a body: sweep_rigid.c, which the path falls back to).
 * Moves: short 5-axis moves from the LinuxCNC impeller (xyzac-trt, TCP, ball
 * D4 L30) and a longer one of the same kind, and adversarial ones: large turns (TCP, and the tip
 * held in joint mode while A turns 90 degrees), points at the ball's centre path, points where the
 * shank is nearest; short moves of the head machines in joint mode and of the dual table. Also the
 * window contract of swarf_sweep_sdf_range (also with windows that close just
 * above the value: the lower bounds that end a call early must stay below
 * it) and the instant returned. Each case states how many points the path
 * certified itself (the rest fell back).
 * Flat and bull end mills take the path of the capsule of radius D/2 about
 * their axis from the corner radius up (it holds them and shares their side),
 * then their own value at its instant: the same checks, on the impeller's
 * moves, with points about the bottom and corners as well as the side.
 * The local planes (swarf_sweep_range_plane) at each point, for the radii the
 * removal asks (a 2^3 cube's and a 4^3 octant's voxels from their centre):
 * the value as the range's, and the sweep at points within the radius (the
 * cube's corners and faces at that distance, and random ones inside) never
 * below the plane; how often a plane is given, and how often it bounds a
 * point better than the 1-Lipschitz bound d - |q - p| does.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "engine_private.h"
#include "testkit.h"

#define TOL 1.001e-6 /* the certified accuracy, mm */

static int planes_given, planes_asked; /* over the impeller's moves (test_impeller) */

static double body(const void *ctx, const double q[3], double grad[3]) {
  return swarf_cutter_sdf_grad((const swarf_cutter *)ctx, q, grad);
}

/* The general certified search alone (what the path falls back to). */
static double general(const swarf_sweep *s, const double p[3]) {
  return swarf_sweep_rigid_body_sdf(s, body, s->cutter, p, NULL);
}

static swarf_motion make(const char *machine, const double s6[6], const double e6[6]) {
  swarf_motion m;
  CHECK(tk_machine_move(machine, s6, e6, &m) == SWARF_OK, "motion on %s", machine);
  return m;
}

/* World point of the cutter-frame point x at the instance alpha. */
static void place(const swarf_motion *m, double a, const double x[3], double p[3]) {
  double t[3], U[9];
  swarf_motion_eval(m, a, t, U);
  for (int k = 0; k < 3; k++)
    p[k] = t[k] + U[3 * k] * x[0] + U[3 * k + 1] * x[1] + U[3 * k + 2] * x[2];
}

typedef enum { NEAR_SURFACE, NEAR_CENTRE, NEAR_SHANK } where;

/* A random point: within `band` mm of a random instance's ball, within
 * 0.01 mm of the ball's centre, or within `band` of the shank's side. */
static void point(tk_rng *r, const swarf_cutter *c, const swarf_motion *m, where w, double band,
                  double p[3]) {
  double x[3], n[3], R = 0.5 * c->diameter, a = tk_uniform(r, 0.0, 1.0);
  if (w == NEAR_SURFACE) { /* the ball's part of the surface (the top is the shank's end) */
    double off = tk_uniform(r, -band, band);
    tk_unit(r, n);
    n[2] = -fabs(n[2]);
    swarf_cutter_point(c, n, x);
    for (int k = 0; k < 3; k++)
      x[k] += off * n[k];
  } else if (w == NEAR_CENTRE) {
    tk_unit(r, n);
    for (int k = 0; k < 3; k++)
      x[k] = tk_uniform(r, 0.0, 0.01) * n[k];
    x[2] += R;
  } else {
    double th = tk_uniform(r, 0.0, 2 * tk_pi), rho = R + tk_uniform(r, -band, band);
    x[0] = rho * cos(th), x[1] = rho * sin(th), x[2] = tk_uniform(r, R, c->length - R);
  }
  place(m, a, x, p);
}

/* The window contract of swarf_sweep_sdf_range against the truth d: within
 * TOL inside (lo, hi); at most lo and not below d - TOL under it; at least
 * hi - TOL above it. */
static void check_windows(const swarf_sweep *s, const double p[3], double d, const char *name) {
  const double off[5] = {-0.3, -0.05, 0.0, 0.05, 0.3};
  for (int w = 0; w < 5; w++) {
    double lo = d + off[w] - 0.1, hi = d + off[w] + 0.1, v = swarf_sweep_sdf_range(s, p, lo, hi);
    if (d >= lo && d < hi)
      CHECK(fabs(v - d) <= TOL, "%s: range in window: %.9g vs %.9g", name, v, d);
    else if (d < lo)
      CHECK(v <= lo + TOL && v >= d - TOL, "%s: below lo %g: %.9g (d %.9g)", name, lo, v, d);
    else
      CHECK(v >= hi - TOL, "%s: above hi %g: %.9g (d %.9g)", name, hi, v, d);
  }
}

typedef struct {
  int asked, given, probes, better;
} plane_stats;

/* The local planes at p (value d) for the cube's and the octant's radius. */
static void check_planes(const swarf_sweep *s, const double p[3], double d, double voxel, tk_rng *r,
                         const char *name, plane_stats *st) {
  const double radii[2] = {0.5 * sqrt(3.0) * voxel, 1.5 * sqrt(3.0) * voxel};
  for (int k = 0; k < 2; k++) {
    double v, pd = NAN, g[3] = {NAN, NAN, NAN}, rad = radii[k];
    const double lo = k ? -INFINITY : d - 0.5, hi = k ? INFINITY : d + 0.5;
    int has = swarf_sweep_range_plane(s, p, lo, hi, rad, &v, &pd, g);
    st->asked++;
    CHECK(fabs(v - d) <= TOL, "%s: range_plane's value %.9g vs %.9g", name, v, d);
    if (has != 1) continue;
    st->given++;
    CHECK(pd <= v && isfinite(g[0] + g[1] + g[2]), "%s: plane offset %.9g at most the value %.9g",
          name, pd, v);
    for (int j = 0; j < 24; j++) {
      double u[3], q[3], dist;
      if (j < 8) /* the corners of the cube inscribed in the sphere */
        for (int a = 0; a < 3; a++)
          u[a] = (j >> a & 1 ? 1.0 : -1.0) / sqrt(3.0);
      else if (j < 14) /* its faces' directions */
        for (int a = 0; a < 3; a++)
          u[a] = a == (j - 8) / 2 ? ((j - 8) & 1 ? 1.0 : -1.0) : 0.0;
      else { /* inside */
        tk_unit(r, u);
        dist = tk_uniform(r, 0.0, 1.0);
        for (int a = 0; a < 3; a++)
          u[a] *= dist;
      }
      for (int a = 0; a < 3; a++)
        q[a] = p[a] + rad * u[a];
      const double sq = swarf_sweep_sdf(s, q, NULL),
                   off = rad * sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      const double plane = pd + rad * (g[0] * u[0] + g[1] * u[1] + g[2] * u[2]);
      CHECK(sq >= plane - TOL, "%s: the sweep %.9g below its plane %.9g at %.3g mm (r %.3g)", name,
            sq, plane, off, rad);
      st->probes++;
      if (plane > d - off) st->better++;
    }
  }
}

/* npts points of kind w about the move: the sweep (ball path where it
 * certifies, else the general search), the general search alone and the
 * path's own answer against the truth. Returns how many the path took. */
static int run(const char *name, const swarf_cutter *c, const swarf_motion *m, double voxel,
               where w, int npts, unsigned seed) {
  swarf_sweep s;
  tk_rng r = {0x9e3779b97f4a7c15ull * seed + 7};
  double worst = 0.0, worst_gen = 0.0;
  int n, took = 0;
  plane_stats ps = {0, 0, 0, 0};
  swarf_sweep_init_voxel(&s, c, m, voxel);
  n = swarf_sweep_cdata(&s)->u.rigid.n;
  CHECK(swarf_sweep_cdata(&s)->method == SWARF_SWEEP_RIGID, "%s: rigid sweep", name);
  for (int i = 0; i < npts; i++) {
    double p[3], a = -1.0, v, vb, tr, gen, at;
    point(&r, c, m, w, 2 * voxel, p);
    tr = tk_rigid_truth(c, m, p, 100 * n);
    v = swarf_sweep_sdf(&s, p, &a);
    gen = general(&s, p);
    worst = fmax(worst, fabs(v - tr));
    worst_gen = fmax(worst_gen, fabs(v - gen));
    CHECK(fabs(v - tr) <= TOL, "%s: sweep %.9g vs truth %.9g", name, v, tr);
    CHECK(fabs(v - gen) <= TOL, "%s: sweep %.9g vs general search %.9g", name, v, gen);
    at = tk_rigid_instance(c, m, p, a);
    CHECK(a >= 0.0 && a <= 1.0 && at <= v + 1e-9 && at >= v - TOL,
          "%s: the instant %g holds the value (%.9g vs %.9g)", name, a, at, v);
    if (swarf_sweep_rigid_ball(&s, p, -INFINITY, INFINITY, &vb, NULL) == 0) {
      took++;
      CHECK(fabs(vb - tr) <= TOL, "%s: ball path %.9g vs truth %.9g", name, vb, tr);
    }
    if (i % 4 == 0) check_windows(&s, p, tr, name);
    check_planes(&s, p, tr, voxel, &r, name, &ps);
    /* a window closing just above the value: no lower bound may pass it */
    v = swarf_sweep_sdf_range(&s, p, tr - 1.0, tr + 1e-5);
    CHECK(fabs(v - tr) <= TOL, "%s: range just above the value: %.9g vs %.9g", name, v, tr);
  }
  printf("%-34s %3d steps: %3d of %3d points by the ball path; max |sweep - truth| %.2e mm, "
         "|sweep - general| %.2e mm\n",
         name, n, took, npts, worst, worst_gen);
  printf("%-34s local planes: %d of %d asked, better than the Lipschitz bound at %d of %d "
         "points\n",
         "", ps.given, ps.asked, ps.better, ps.probes);
  planes_given += ps.given, planes_asked += ps.asked;
  return took;
}

/* Short moves of the impeller's first operation (xyzac-trt, TCP). */
static void test_impeller(void) {
  static const double line[5][6] = {{6.302, -11.560, 27.743, -71.841, 0, -35.930},
                                    {6.358, -12.418, 26.178, -71.266, 0, -32.919},
                                    {6.346, -12.607, 25.858, -71.158, 0, -32.304},
                                    {5.476, -14.121, 23.987, -71.566, 0, -28.632},
                                    {4.815, -14.881, 23.162, -71.965, 0, -27.052}};
  swarf_cutter c;
  int took = 0;
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 4.0, 0, 30.0, NULL);
  for (int k = 0; k + 1 < 5; k++) {
    swarf_motion m = make("xyzac-trt", line[k], line[k + 1]);
    char name[64];
    snprintf(name, sizeof name, "impeller move %d", k + 1);
    took += run(name, &c, &m, 0.2, NEAR_SURFACE, 150, 11 + k);
  }
  CHECK(took > 500, "the ball path takes most impeller points (%d of 600)", took);
  CHECK(planes_given > planes_asked / 4, "local planes at the impeller's points: %d of %d",
        planes_given, planes_asked);
  /* a longer move (A 12, C 26 degrees; 55 steps): the ends rarely certify
   * it, the coarse steps (every 7th) mostly do, and the refinement takes the
   * table's steps before poses off it */
  static const double far[6] = {2.0, -16.0, 20.0, -60.0, 0, -10.0};
  swarf_motion m = make("xyzac-trt", line[0], far);
  took = run("longer move, A 12 and C 26 degrees", &c, &m, 0.2, NEAR_SURFACE, 100, 15);
  CHECK(took > 90, "the ball path takes most points of the longer move (%d of 100)", took);
}

static void test_adversarial(void) {
  swarf_cutter c;
  const double t0[6] = {0, 0, 0, 0, 0, 0}, t1[6] = {3, 1, -2, 60, 0, 150};
  const double h0[6] = {0, 0, 10, 0, 0, 0}, h1[6] = {0, 0, 10, 90, 0, 0};
  const double s0[6] = {1, 2, 3, 10, 0, -30}, s1[6] = {4, 0, 2, 40, 0, 60};
  const double imp0[6] = {6.302, -11.560, 27.743, -71.841, 0, -35.930};
  const double imp1[6] = {6.358, -12.418, 26.178, -71.266, 0, -32.919};
  swarf_motion m = make("xyzac-trt", t0, t1);
  int took;
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 6.0, 0, 20.0, NULL);
  run("large turn A+C, TCP", &c, &m, 0.5, NEAR_SURFACE, 60, 21);
  m = make("xyza", h0, h1);
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 4.0, 0, 12.0, NULL);
  run("A 90 degrees, tip held (torus)", &c, &m, 0.5, NEAR_SURFACE, 60, 22);
  m = make("xyzac-trt", s0, s1);
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 4.0, 0, 16.0, NULL);
  run("A+C, points at the centre path", &c, &m, 0.2, NEAR_CENTRE, 60, 23);
  run("A+C, points at the shank", &c, &m, 0.2, NEAR_SHANK, 100, 24);
  m = make("xyzac-trt", imp0, imp1);
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 4.0, 0, 30.0, NULL);
  took = run("impeller move 1, at the centre path", &c, &m, 0.2, NEAR_CENTRE, 60, 25);
  CHECK(took > 50, "the path takes points at the centre path (%d of 60)", took);
  took = run("impeller move 1, at the shank", &c, &m, 0.2, NEAR_SHANK, 100, 26);
  CHECK(took > 80, "the path takes points at the shank (%d of 100)", took);
}

/* The other kinematics (their poses and velocities differ, the path reads
 * only t, U, v, omega): heads that tilt about their pivot in joint mode, the
 * dual table. Short moves, as a finishing program makes them. Beside the
 * shank the dual table's move turns the tool about a point of its axis
 * (the axis points there hardly move across it: no convexity to certify),
 * so those points take the general search, and must still be exact. */
static void test_machines(void) {
  const double b0[6] = {1, 2, 3, 0, 10, -30}, b1[6] = {1.4, 1.8, 2.9, 0, 12, -26};
  const double a0[6] = {1, 2, 3, 10, 20, 0}, a1[6] = {1.3, 2.2, 2.8, 13, 17, 0};
  swarf_cutter c;
  swarf_motion m;
  int took = 0;
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 4.0, 0, 16.0, NULL);
  m = make("xyzbc-hh,mode=joint,head=25", b0, b1);
  took += run("head-head B+C, joint", &c, &m, 0.2, NEAR_SURFACE, 60, 31);
  m = make("xyzbc-ht,mode=joint,pivot=2,-3,head=25", b0, b1);
  took += run("head-table B+C, joint", &c, &m, 0.2, NEAR_SURFACE, 60, 32);
  m = make("xyzab-tdr", a0, a1);
  took += run("dual table A+B, TCP", &c, &m, 0.2, NEAR_SURFACE, 60, 33);
  run("dual table A+B, TCP, at the shank", &c, &m, 0.2, NEAR_SHANK, 60, 34);
  CHECK(took > 150, "the path takes most points on the other machines (%d of 180)", took);
}

/* Flat and bull end mills on the impeller's moves: exact everywhere (the path
 * where the capsule's value is theirs, the general search elsewhere); the
 * path takes most points beside the side and leaves the bottom's. */
static void test_flat_bull(void) {
  static const double a[6] = {6.302, -11.560, 27.743, -71.841, 0, -35.930};
  static const double b[6] = {6.358, -12.418, 26.178, -71.266, 0, -32.919};
  static const double far[6] = {2.0, -16.0, 20.0, -60.0, 0, -10.0};
  const swarf_motion m = make("xyzac-trt", a, b), longer = make("xyzac-trt", a, far);
  const struct {
    const char *name;
    swarf_cutter_shape shape;
    double r;
  } cutters[2] = {{"flat", SWARF_CUTTER_FLAT, 0.0}, {"bull R1", SWARF_CUTTER_BULL, 1.0}};
  for (int k = 0; k < 2; k++) {
    swarf_cutter c;
    char name[64];
    int side;
    swarf_cutter_init(&c, cutters[k].shape, 4.0, cutters[k].r, 30.0, NULL);
    snprintf(name, sizeof name, "impeller move 1, %s", cutters[k].name);
    run(name, &c, &m, 0.2, NEAR_SURFACE, 120, 41 + k);
    snprintf(name, sizeof name, "impeller move 1, %s, at the side", cutters[k].name);
    side = run(name, &c, &m, 0.2, NEAR_SHANK, 100, 43 + k);
    CHECK(side > 80, "%s: the path takes points beside the side (%d of 100)", cutters[k].name,
          side);
    snprintf(name, sizeof name, "longer move, %s", cutters[k].name);
    run(name, &c, &longer, 0.2, NEAR_SURFACE, 60, 45 + k);
  }
}

int main(void) {
  test_impeller();
  test_adversarial();
  test_machines();
  test_flat_bull();
  return check_done();
}
