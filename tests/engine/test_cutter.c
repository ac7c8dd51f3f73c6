/* SPDX-License-Identifier: MPL-2.0 */
/* test_cutter.c -- cutters against independent truths: validation; x_h(n) on
 * the surface with outward normal n (numerical gradient of the sdf); h(n)
 * equal to the maximum of x . n over sampled surface points; the ball's
 * analytic support function; the profile's derivative by finite differences;
 * the sdf against a clamp-based distance to the core cylinder. */
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "testkit.h"

static void test_init(void) {
  swarf_cutter c;
  swarf_error why;
  CHECK(swarf_cutter_init(&c, SWARF_CUTTER_FLAT, 6.0, 1.0, 0.0, &why) == SWARF_OK, "flat");
  CHECK(c.corner_radius == 0.0 && c.length == 24.0, "flat: R = 0, default length 4 D");
  CHECK(swarf_cutter_init(&c, SWARF_CUTTER_BALL, 3.175, 0.0, 12.0, &why) == SWARF_OK, "ball");
  CHECK(c.corner_radius == 0.5 * 3.175 && c.length == 12.0, "ball: R = D/2");
  CHECK(swarf_cutter_init(&c, SWARF_CUTTER_BULL, 10.0, 2.0, 25.0, &why) == SWARF_OK, "bull");
  CHECK(c.corner_radius == 2.0, "bull keeps R");
  swarf_error_init(&why);
  CHECK(swarf_cutter_init(&c, SWARF_CUTTER_BULL, 10.0, 5.0, 25.0, &why) == SWARF_ERR_TOOL &&
            why.message[0] != '\0' && why.status == SWARF_ERR_TOOL && strcmp(why.word, "R") == 0,
        "bull with R = D/2 refused");
  CHECK(swarf_cutter_init(&c, SWARF_CUTTER_BULL, 10.0, 0.0, 25.0, &why) == SWARF_ERR_TOOL,
        "bull R = 0");
  CHECK(swarf_cutter_init(&c, SWARF_CUTTER_FLAT, 0.0, 0.0, 25.0, &why) == SWARF_ERR_TOOL, "D = 0");
  CHECK(swarf_cutter_init(&c, SWARF_CUTTER_FLAT, NAN, 0.0, 25.0, &why) == SWARF_ERR_TOOL,
        "D = NaN");
  CHECK(swarf_cutter_init(&c, SWARF_CUTTER_FLAT, 6.0, 0.0, 5.0, &why) == SWARF_OK,
        "length < D: a short-fluted flat is real");
  CHECK(swarf_cutter_init(&c, SWARF_CUTTER_FLAT, 6.0, 0.0, NAN, &why) == SWARF_ERR_TOOL,
        "length NaN");
  CHECK(swarf_cutter_init(NULL, SWARF_CUTTER_FLAT, 6.0, 0.0, 0.0, &why) == SWARF_ERR_ARG,
        "NULL cutter");
}

/* Independent exact sdf: clamp into the core's (r, z) rectangle. */
static double ref_sdf(const swarf_cutter *c, const double p[3]) {
  double R = c->corner_radius, a = 0.5 * c->diameter - R, r = hypot(p[0], p[1]);
  double cr = fmin(r, a), cz = fmin(fmax(p[2], R), c->length - R);
  if (r <= a && p[2] >= R && p[2] <= c->length - R)
    return -fmin(a - r, fmin(p[2] - R, c->length - R - p[2])) - R;
  return hypot(r - cr, p[2] - cz) - R;
}

static void num_grad(const swarf_cutter *c, const double p[3], double g[3]) {
  const double h = 1e-8;
  for (int k = 0; k < 3; k++) {
    double a[3] = {p[0], p[1], p[2]}, b[3] = {p[0], p[1], p[2]};
    a[k] += h;
    b[k] -= h;
    g[k] = (swarf_cutter_sdf(c, a) - swarf_cutter_sdf(c, b)) / (2 * h);
  }
}

static void check_point(const swarf_cutter *c, const double n[3], const char *what) {
  double x[3], y[3], g[3];
  swarf_cutter_point(c, n, x);
  CHECK(fabs(swarf_cutter_sdf(c, x)) < 1e-12, "%s: x_h(n) on the surface (sdf %.3g)", what,
        swarf_cutter_sdf(c, x));
  CHECK_NEAR(tk_dot(x, n), swarf_cutter_support(c, n), 1e-12, "h(n) = x_h(n) . n");
  for (int k = 0; k < 3; k++)
    y[k] = x[k] + 0.1 * n[k];
  num_grad(c, y, g);
  CHECK(tk_dist(g, n) < 1e-6, "%s: n is the outward normal (|grad - n| = %.3g)", what,
        tk_dist(g, n));
}

/* A surface point drawn along the cross-section outline (faces, corner arcs,
 * side) by arc length, then turned about the axis: independent of x_h. */
static void surface_sample(const swarf_cutter *c, tk_rng *r, double x[3]) {
  double R = c->corner_radius, a = 0.5 * c->diameter - R, L = c->length;
  double side = L - 2 * R, arc = 0.5 * tk_pi * R, total = 2 * a + 2 * arc + side;
  double s = tk_uniform(r, 0.0, total), phi = tk_uniform(r, 0.0, 2 * tk_pi), rr, z;
  if (s < a) {
    rr = s, z = 0.0;
  } else if ((s -= a) < arc) {
    double t = s / R - 0.5 * tk_pi;
    rr = a + R * cos(t), z = R + R * sin(t);
  } else if ((s -= arc) < side) {
    rr = a + R, z = R + s;
  } else if ((s -= side) < arc) {
    double t = s / R;
    rr = a + R * cos(t), z = L - R + R * sin(t);
  } else {
    rr = s - arc, z = L;
  }
  x[0] = rr * cos(phi);
  x[1] = rr * sin(phi);
  x[2] = z;
}

static void check_cutter(const swarf_cutter *c, const char *what) {
  tk_rng r = {0x9e3779b97f4a7c15ull};
  static double samples[20000][3];
  const double special[][3] = {{0, 0, 1},     {0, 0, -1},    {1, 0, 0},   {0, -1, 0},
                               {0.6, 0.8, 0}, {1e-9, 0, -1}, {0, 1e-9, 1}};
  for (size_t i = 0; i < sizeof special / sizeof special[0]; i++) {
    double n[3] = {special[i][0], special[i][1], special[i][2]}, m = sqrt(tk_dot(n, n));
    for (int k = 0; k < 3; k++)
      n[k] /= m;
    check_point(c, n, what);
  }
  for (int i = 0; i < 20000; i++) {
    double n[3];
    tk_unit(&r, n);
    if (i < 300) check_point(c, n, what);
    surface_sample(c, &r, samples[i]);
    CHECK(fabs(swarf_cutter_sdf(c, samples[i])) < 1e-12, "%s: outline sample on surface", what);
  }
  for (int i = 0; i < 200; i++) {
    double n[3], best = -INFINITY, h;
    tk_unit(&r, n);
    h = swarf_cutter_support(c, n);
    for (int j = 0; j < 20000; j++)
      best = fmax(best, tk_dot(samples[j], n));
    CHECK(best <= h + 1e-12 && best >= h - 0.05 * c->diameter,
          "%s: h(n) = max x.n over the surface (%.6g vs %.6g)", what, h, best);
  }
  for (int i = 0; i < 5000; i++) {
    double p[3] = {tk_uniform(&r, -c->diameter, c->diameter),
                   tk_uniform(&r, -c->diameter, c->diameter),
                   tk_uniform(&r, -c->diameter, c->length + c->diameter)};
    CHECK_NEAR(swarf_cutter_sdf(c, p), ref_sdf(c, p), 1e-12, "sdf vs clamp reference");
  }
}

static void test_profile(const swarf_cutter *c, const char *what) {
  for (double z = -0.95; z < 0.96; z += 0.1) {
    double phi, dphi, p1, p2, n[3] = {sqrt(1 - z * z), 0.0, z};
    swarf_cutter_profile(c, z, &phi, &dphi);
    CHECK_NEAR(phi, swarf_cutter_support(c, n), 1e-12, "phi(z) = h(n)");
    swarf_cutter_profile(c, z + 1e-6, &p1, NULL);
    swarf_cutter_profile(c, z - 1e-6, &p2, NULL);
    if (fabs(z) > 1e-3) CHECK_NEAR(dphi, (p1 - p2) / 2e-6, 1e-5, what);
  }
}

static void test_ball_support(void) {
  swarf_cutter c;
  tk_rng r = {12345};
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 5.0, 0.0, 5.0, NULL); /* a sphere */
  for (int i = 0; i < 1000; i++) {
    double n[3];
    tk_unit(&r, n);
    /* sphere of radius 2.5 centred at (0, 0, 2.5): h(n) = 2.5 + 2.5 n_z */
    CHECK_NEAR(swarf_cutter_support(&c, n), 2.5 + 2.5 * n[2], 1e-14, "sphere support");
  }
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 5.0, 0.0, 20.0, NULL);
  for (int i = 0; i < 1000; i++) {
    double n[3], top;
    tk_unit(&r, n);
    top = n[2] > 0 ? 17.5 * n[2] : 2.5 * n[2]; /* capsule: centres at z = 2.5 and 17.5 */
    CHECK_NEAR(swarf_cutter_support(&c, n), 2.5 + top, 1e-14, "capsule support");
  }
}

static void test_kinks(void) {
  swarf_cutter c;
  double x[3], phi, dphi;
  const double up[3] = {0, 0, 1}, down[3] = {0, 0, -1}, side[3] = {1, 0, 0};
  swarf_cutter_init(&c, SWARF_CUTTER_BULL, 10.0, 2.0, 25.0, NULL);
  swarf_cutter_point(&c, down, x);
  CHECK(x[0] == 0 && x[1] == 0 && x[2] == 0, "bottom pole: face centre");
  swarf_cutter_point(&c, up, x);
  CHECK(x[0] == 0 && x[1] == 0 && x[2] == 25.0, "top pole: face centre");
  swarf_cutter_point(&c, side, x);
  CHECK(x[0] == 5.0 && x[2] == 23.0, "ruling: its top end (n_z -> 0+)");
  swarf_cutter_profile(&c, 1.0, &phi, &dphi);
  CHECK(phi == 25.0 && dphi == -INFINITY, "phi'(1) = -inf for a > 0");
  swarf_cutter_profile(&c, 0.0, &phi, &dphi);
  CHECK(phi == 5.0 && dphi == 23.0, "phi'(0) one-sided from above");
}

int main(void) {
  swarf_cutter c;
  test_init();
  swarf_cutter_init(&c, SWARF_CUTTER_FLAT, 6.0, 0.0, 20.0, NULL);
  check_cutter(&c, "flat");
  test_profile(&c, "flat phi'");
  swarf_cutter_init(&c, SWARF_CUTTER_BALL, 3.175, 0.0, 12.0, NULL);
  check_cutter(&c, "ball");
  test_profile(&c, "ball phi'");
  swarf_cutter_init(&c, SWARF_CUTTER_BULL, 10.0, 2.0, 25.0, NULL);
  check_cutter(&c, "bull");
  test_profile(&c, "bull phi'");
  test_ball_support();
  test_kinks();
  return check_done();
}
