/* SPDX-License-Identifier: MPL-2.0 */
/* test_profile.c -- cutters of revolution from a profile (engine.h: families,
 * bodies, QSS pieces) against an independent truth: the outline of each
 * family written here from its drawing (lines, and arcs sampled every 2e-4
 * rad), the 2-D distance to that closed polyline with an even-odd sign.
 *   - one-piece (convex) cutters: sdf equal to the truth inside and outside;
 *   - unions (lollipop, dovetail, T-slot): equal outside; inside never deeper
 *     than the truth and equal near the surface away from the joints;
 *   - gradients against central differences; support function against
 *     the outline's points (h(n) = max x.n);
 *   - the paper's QSS (2,3,0,0) and Example 2's x^2+y^2-z^2 scaled by 3,
 *     their curve x_h(n) sampled densely as the truth;
 *   - bad numbers rejected naming the parameter; real tools accepted
 *     (a 2" face mill with 1.5" flutes).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "testkit.h"

#define DEG (tk_pi / 180.0)

typedef struct {
  double (*p)[2];
  int n, cap;
  double zlo, zhi, rmax;
} outline;

static void out_push(outline *o, double r, double z) {
  if (o->n == o->cap) {
    o->cap = o->cap ? 2 * o->cap : 1024;
    o->p = realloc(o->p, sizeof *o->p * (size_t)o->cap);
  }
  o->p[o->n][0] = r, o->p[o->n][1] = z, o->n++;
}

/* The arc of centre (cr, cz), radius rad from angle a0 to a1 (radians). */
static void out_arc(outline *o, double cr, double cz, double rad, double a0, double a1) {
  int n = (int)ceil(fabs(a1 - a0) / 2e-4) + 1;
  for (int i = 0; i <= n; i++) {
    double a = a0 + (a1 - a0) * i / n;
    out_push(o, cr + rad * cos(a), cz + rad * sin(a));
  }
}

/* Distance to the closed polyline (mirrored into r >= 0 is not needed: the
 * outline runs from the axis to the axis and points have r >= 0), sign by
 * the even-odd rule on the polyline closed along the axis. */
static double out_sdf(const outline *o, double r, double z) {
  double best = INFINITY;
  int cross = 0;
  for (int i = 0; i < o->n; i++) {
    const double *a = o->p[i], *b = o->p[(i + 1) % o->n];
    double dr = b[0] - a[0], dz = b[1] - a[1], l2 = dr * dr + dz * dz, t = 0.0;
    if (i + 1 == o->n) { /* the closing segment runs on the axis: not boundary */
      if ((a[1] > z) != (b[1] > z) && 0.0 > r) cross++;
      continue;
    }
    if (l2 > 0) t = fmax(0.0, fmin(1.0, ((r - a[0]) * dr + (z - a[1]) * dz) / l2));
    best = fmin(best, hypot(r - a[0] - t * dr, z - a[1] - t * dz));
    if ((a[1] > z) != (b[1] > z)) {
      double rc = a[0] + (z - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
      if (rc > r) cross++;
    }
  }
  return cross & 1 ? -best : best;
}

static void out_free(outline *o) {
  free(o->p);
}

/* ---- the families' drawings ------------------------------------------------ */

static void draw_pointed(outline *o, double d, double A, double L, double tip) {
  double h = 0.5 * (d - tip) / tan(0.5 * A * DEG);
  out_push(o, 0, 0);
  if (tip > 0) out_push(o, 0.5 * tip, 0);
  if (L < h) {
    out_push(o, 0.5 * tip + L * tan(0.5 * A * DEG), L);
  } else {
    out_push(o, 0.5 * d, h);
    out_push(o, 0.5 * d, L);
  }
  out_push(o, 0, L);
}

/* Tapered end mill: corner circle centre (d/2 - R, R), side at half-angle A. */
static void draw_taper(outline *o, double d, double A, double R, double L) {
  double a = A * DEG, c = 0.5 * d - R, t0r = c + R * cos(a), t0z = R - R * sin(a);
  out_push(o, 0, 0);
  if (R > 0)
    out_arc(o, c, R, R, -0.5 * tk_pi, -a);
  else
    out_push(o, 0.5 * d, 0);
  (void)t0r, (void)t0z;
  out_push(o, t0r + (L - t0z) * tan(a), L);
  out_push(o, 0, L);
}

/* APT: tip, bottom line at alpha, corner arc (E, F, R), side at beta to H. */
static void draw_apt(outline *o, double R, double E, double F, double al, double be, double H) {
  double a = al * DEG, b = be * DEG;
  out_push(o, 0, 0);
  out_arc(o, E, F, R, -0.5 * tk_pi + a, -b);
  out_push(o, E + R * cos(b) + (H - F + R * sin(b)) * tan(b), H);
  out_push(o, 0, H);
}

/* Union outlines: the outer boundary. */
static void draw_lollipop(outline *o, double d, double n, double L) {
  double R = 0.5 * d, y = sqrt(R * R - 0.25 * n * n);
  out_arc(o, 0, R, R, -0.5 * tk_pi, asin(y / R));
  out_push(o, 0.5 * n, L);
  out_push(o, 0, L);
}

static void draw_stack(outline *o, double d0, double h, double d1top, double n, double L) {
  out_push(o, 0, 0);
  out_push(o, 0.5 * d0, 0);
  out_push(o, 0.5 * d1top, h);
  out_push(o, 0.5 * n, h);
  out_push(o, 0.5 * n, L);
  out_push(o, 0, L);
}

/* The QSS curve of h = a(x^2+y^2) + b z^2 + e z + f, lifted by lift. */
static void draw_qss(outline *o, double a, double b, double e, double f, double *lift) {
  double q2 = b - a, q1 = e, q0 = a + f, lo = INFINITY;
  int n = 40000;
  for (int i = 0; i <= n; i++) {
    double s = -cos(tk_pi * i / n), z = (-q2 * s * s + q0 + 2 * q2) * s + q1;
    lo = fmin(lo, z);
  }
  *lift = -lo;
  for (int i = 0; i <= n; i++) {
    double s = -cos(tk_pi * i / n);
    out_push(o, sqrt(fmax(0, 1 - s * s)) * (q0 - q2 * s * s),
             (-q2 * s * s + q0 + 2 * q2) * s + q1 - lo);
  }
}

/* ---- the checks ------------------------------------------------------------- */

static void extent(outline *o) {
  o->zlo = INFINITY, o->zhi = -INFINITY, o->rmax = 0;
  for (int i = 0; i < o->n; i++)
    o->zlo = fmin(o->zlo, o->p[i][1]), o->zhi = fmax(o->zhi, o->p[i][1]),
    o->rmax = fmax(o->rmax, o->p[i][0]);
}

/* Random points around the body: sdf against the drawing. */
static int npts = 3000;

static void compare(const char *name, const swarf_cutter *c, outline *o, int convex, double tol) {
  tk_rng r = {0x1234567ull + (unsigned)o->n};
  double worst_out = 0, worst_in = 0, worst_deeper = 0, worst_g = 0;
  int nin = 0;
  extent(o);
  CHECK(fabs(c->diameter - 2 * o->rmax) < 1e-6, "%s: diameter %g", name, c->diameter);
  CHECK(fabs(c->length - o->zhi) < 1e-6, "%s: length %g", name, c->length);
  CHECK(fabs(c->zmin - o->zlo) < 1e-6, "%s: bottom %g", name, c->zmin);
  for (int i = 0; i < npts; i++) {
    double pad = 0.3 * (o->zhi - o->zlo) + 1.0, th = tk_uniform(&r, 0, 2 * tk_pi);
    double rr = tk_uniform(&r, 0, o->rmax + pad), z = tk_uniform(&r, o->zlo - pad, o->zhi + pad);
    double p[3] = {rr * cos(th), rr * sin(th), z}, g[3], e = 1e-6;
    double d = swarf_cutter_sdf(c, p), ref = out_sdf(o, rr, z);
    CHECK((d < 0) == (ref < 0) || fabs(ref) < tol, "%s: sign at r %g z %g (%g vs %g)", name, rr, z,
          d, ref);
    if (ref >= 0 || convex)
      worst_out = fmax(worst_out, fabs(d - ref));
    else {
      worst_deeper = fmax(worst_deeper, ref - d); /* > 0: deeper than the truth */
      if (ref > -0.05) worst_in = fmax(worst_in, fabs(d - ref)), nin++;
    }
    /* gradient against central differences where the sdf is smooth */
    {
      double g2[2], dd = swarf_cutter_sdf2(c, rr, z, g2), fd[3], ok = 1;
      CHECK(fabs(dd - d) < 1e-12, "%s: sdf2 value", name);
      g[0] = g2[0] * cos(th), g[1] = g2[0] * sin(th), g[2] = g2[1];
      for (int k = 0; k < 3; k++) {
        double a[3] = {p[0], p[1], p[2]}, b[3] = {p[0], p[1], p[2]};
        a[k] += e, b[k] -= e;
        double fa = swarf_cutter_sdf(c, a), fb = swarf_cutter_sdf(c, b);
        fd[k] = (fa - fb) / (2 * e);
        if (fabs(fa + fb - 2 * d) > 1e-9) ok = 0; /* a kink nearby */
      }
      if (ok) worst_g = fmax(worst_g, tk_dist(fd, g));
    }
  }
  printf("%-22s outside%s max |sdf - truth| %.2e, inside: deeper by %.2e, near-surface %.2e (%d), "
         "gradient %.2e\n",
         name, convex ? "+inside" : "", worst_out, worst_deeper, worst_in, nin, worst_g);
  CHECK(worst_out < tol, "%s: sdf vs drawing %g", name, worst_out);
  CHECK(worst_deeper < tol, "%s: never deeper than the truth (%g)", name, worst_deeper);
  CHECK(worst_g < 1e-5, "%s: gradient %g", name, worst_g);
}

/* h(n) = max over the outline of x . n (convex cutters). */
static void check_support(const char *name, const swarf_cutter *c, const outline *o, double tol) {
  tk_rng r = {99};
  double worst = 0, worstp = 0;
  for (int i = 0; i < 400; i++) {
    double n[3], rho, best = -INFINITY, x[3];
    tk_unit(&r, n);
    rho = hypot(n[0], n[1]);
    for (int k = 0; k < o->n; k++)
      best = fmax(best, o->p[k][0] * rho + o->p[k][1] * n[2]);
    worst = fmax(worst, fabs(swarf_cutter_support(c, n) - best));
    swarf_cutter_point(c, n, x);
    worstp = fmax(worstp, fabs(tk_dot(x, n) - best));
    worstp = fmax(worstp, fabs(swarf_cutter_sdf(c, x)));
  }
  CHECK(worst < tol && worstp < tol, "%s: support %g, point %g", name, worst, worstp);
}

static swarf_cutter make(swarf_cutter_spec s) {
  swarf_cutter c;
  swarf_error err;
  swarf_error_init(&err);
  CHECK(swarf_cutter_make(&c, &s, &err) == SWARF_OK, "make: %s", err.message);
  return c;
}

static void test_families(void) {
  swarf_cutter_spec s;
  swarf_cutter c;
  outline o = {0};
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_VEE, s.d = 6, s.angle = 90, s.length = 10;
  c = make(s), draw_pointed(&o, 6, 90, 10, 0), compare("vee D6 A90 L10", &c, &o, 1, 1e-7);
  check_support("vee", &c, &o, 1e-9), o.n = 0;
  s.angle = 30, s.length = NAN, s.d = 3.175;
  c = make(s), draw_pointed(&o, 3.175, 30, fmax(4 * 3.175, 1.5875 / tan(15 * DEG)), 0);
  compare("vee D3.175 A30", &c, &o, 1, 1e-7), o.n = 0;
  s.angle = 20, s.length = 2;
  c = make(s), draw_pointed(&o, 3.175, 20, 2, 0), compare("vee cut at L2", &c, &o, 1, 1e-7),
  o.n = 0;
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_DRILL, s.d = 5;
  c = make(s), draw_pointed(&o, 5, 118, 20, 0), compare("drill D5 (A118)", &c, &o, 1, 1e-7);
  check_support("drill", &c, &o, 1e-9), o.n = 0;
  s.shape = SWARF_CUTTER_SPOT, s.d = 8, s.length = 12;
  c = make(s), draw_pointed(&o, 8, 90, 12, 0), compare("spot D8 (A90)", &c, &o, 1, 1e-7), o.n = 0;
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_CHAMFER, s.d = 10, s.angle = 60, s.tip = 2, s.length = 15;
  c = make(s), draw_pointed(&o, 10, 60, 15, 2), compare("chamfer D10 A60 T2", &c, &o, 1, 1e-7);
  check_support("chamfer", &c, &o, 1e-9), o.n = 0;
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_TAPER, s.d = 2, s.angle = 5, s.r = 1, s.length = 20;
  c = make(s), draw_taper(&o, 2, 5, 1, 20), compare("taper ball D2 A5", &c, &o, 1, 1e-7);
  check_support("taper ball", &c, &o, 1e-6), o.n = 0;
  s.r = 0.25, s.angle = 10;
  c = make(s), draw_taper(&o, 2, 10, 0.25, 20), compare("taper D2 A10 R0.25", &c, &o, 1, 1e-7),
  o.n = 0;
  s.r = NAN, s.angle = 3;
  c = make(s), draw_taper(&o, 2, 3, 0, 20), compare("taper flat D2 A3", &c, &o, 1, 1e-7), o.n = 0;
  swarf_cutter_spec_init(&s); /* APT: E = 2, R = 1, alpha 10, beta 8 */
  {
    double R = 1, E = 2, al = 10 * DEG, be = 8 * DEG, F = (R + E * sin(al)) / cos(al);
    s.shape = SWARF_CUTTER_APT, s.r = R, s.e = E, s.f = F, s.angle = 10, s.beta = 8, s.h = 12;
    s.d = 2 * (E + R / cos(be));
    c = make(s), draw_apt(&o, R, E, F, 10, 8, 12), compare("apt alpha 10 beta 8", &c, &o, 1, 1e-7);
    check_support("apt", &c, &o, 1e-6), o.n = 0;
    s.beta = -12, be = -12 * DEG, s.d = 2 * (E + R / cos(be));
    c = make(s), draw_apt(&o, R, E, F, 10, -12, 12), compare("apt beta -12", &c, &o, 1, 1e-7),
    o.n = 0;
  }
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_LOLLIPOP, s.d = 6, s.neck = 3, s.length = 20;
  c = make(s), draw_lollipop(&o, 6, 3, 20), compare("lollipop D6 N3", &c, &o, 0, 1e-7), o.n = 0;
  CHECK(!c.convex && c.npieces == 2, "lollipop: two pieces, non-convex");
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_DOVETAIL, s.d = 12, s.angle = 60, s.h = 4, s.neck = 5, s.length = 20;
  c = make(s), draw_stack(&o, 12, 4, 12 - 8 / tan(60 * DEG), 5, 20);
  compare("dovetail D12 A60 H4 N5", &c, &o, 0, 1e-7), o.n = 0;
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_TSLOT, s.d = 16, s.h = 3, s.neck = 6, s.length = 25;
  c = make(s), draw_stack(&o, 16, 3, 16, 6, 25), compare("tslot D16 H3 N6", &c, &o, 0, 1e-7),
  o.n = 0;
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_BALL, s.d = 12, s.length = 8; /* a ball with flutes shorter than D */
  c = make(s);
  CHECK(!c.fast, "ball L < D: profile cutter");
  out_arc(&o, 0, 6, 6, -0.5 * tk_pi, 0), out_push(&o, 6, 8), out_push(&o, 0, 8);
  compare("ball D12 L8", &c, &o, 1, 1e-7), o.n = 0;
  out_free(&o);
}

static void test_qss(void) {
  swarf_cutter_spec s;
  swarf_cutter c;
  outline o = {0};
  double lift;
  npts = 1200;
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_QSS, s.qa = 2, s.qb = 3, s.qe = 0, s.qf = 0;
  c = make(s), draw_qss(&o, 2, 3, 0, 0, &lift);
  CHECK(c.convex, "qss 2,3,0,0 convex");
  CHECK_NEAR(lift, 3.0, 1e-9, "qss 2,3,0,0: lowest point 3 below the centre");
  compare("qss 2,3,0,0", &c, &o, 1, 1e-6);
  check_support("qss convex", &c, &o, 1e-6), o.n = 0;
  s.qa = 3, s.qb = -3; /* Example 2's h = x^2 + y^2 - z^2, scaled by 3 */
  c = make(s), draw_qss(&o, 3, -3, 0, 0, &lift);
  CHECK(!c.convex, "qss 3,-3,0,0 non-convex");
  CHECK_NEAR(lift, 3 * sqrt(2.0), 1e-6, "qss 3,-3: lowest at the rims (3 sqrt 2)");
  compare("qss 3,-3,0,0", &c, &o, 1, 1e-6), o.n = 0;
  s.qa = 1, s.qb = 2, s.qe = 0.5, s.qf = 1;
  c = make(s), draw_qss(&o, 1, 2, 0.5, 1, &lift), compare("qss 1,2,0.5,1", &c, &o, 1, 1e-6),
  o.n = 0;
  out_free(&o);
  npts = 3000;
}

static void expect_bad(swarf_cutter_spec s, const char *letter, const char *what) {
  swarf_cutter c;
  swarf_error err;
  swarf_error_init(&err);
  CHECK(swarf_cutter_make(&c, &s, &err) == SWARF_ERR_TOOL, "%s: rejected", what);
  CHECK(strcmp(err.word, letter) == 0, "%s: names %s (got \"%s\": %s)", what, letter, err.word,
        err.message);
  printf("  rejected %-28s %s\n", what, err.message);
}

static void test_errors(void) {
  swarf_cutter_spec s;
  swarf_cutter c;
  swarf_error err;
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_VEE, s.d = 6;
  expect_bad(s, "A", "vee without angle");
  s.angle = 180, expect_bad(s, "A", "vee A180");
  s.angle = 90, s.d = -1, expect_bad(s, "D", "vee D-1");
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_CHAMFER, s.d = 6, s.angle = 90, s.tip = 7;
  expect_bad(s, "T", "chamfer tip > D");
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_TAPER, s.d = 2, s.angle = 5, s.r = 1.5;
  expect_bad(s, "R", "taper R > D/2");
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_APT, s.d = 6, s.r = 1, s.e = 2, s.f = 3, s.angle = 0, s.beta = 0, s.h = 10;
  expect_bad(s, "F", "apt F inconsistent");
  s.f = 1, s.d = 7, expect_bad(s, "D", "apt D inconsistent");
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_LOLLIPOP, s.d = 6, s.neck = 6;
  expect_bad(s, "K", "lollipop neck = D");
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_DOVETAIL, s.d = 10, s.angle = 45, s.h = 6;
  expect_bad(s, "H", "dovetail flanks meet");
  swarf_cutter_spec_init(&s);
  s.shape = SWARF_CUTTER_QSS, s.qa = -1, s.qb = 1, s.qe = 0, s.qf = 0;
  swarf_error_init(&err);
  CHECK(swarf_cutter_make(&c, &s, &err) == SWARF_ERR_TOOL, "qss crossing its axis rejected");
  printf("  rejected qss -1,1,0,0              %s\n", err.message);
  /* real tools accepted: a 2" face mill with 1.5" flutes, a 6 mm flat with 4 mm flutes */
  CHECK(swarf_cutter_init(&c, SWARF_CUTTER_FLAT, 50.8, 0, 38.1, &err) == SWARF_OK,
        "face mill accepted");
  CHECK(c.fast && c.length == 38.1, "face mill keeps the closed forms");
  CHECK(swarf_cutter_init(&c, SWARF_CUTTER_BULL, 50.8, 0.8, 38.1, &err) == SWARF_OK,
        "bull face mill");
  CHECK(swarf_cutter_init(&c, SWARF_CUTTER_BULL, 10, 2, 3, &err) != SWARF_OK,
        "bull L < 2R rejected");
}

/* A body that is not a cutter: a holder-like stack of frustums above z = 30. */
static void test_body(void) {
  swarf_cutter c;
  swarf_error err;
  outline o = {0};
  swarf_error_init(&err);
  swarf_cutter_begin(&c);
  CHECK(swarf_cutter_add_frustum(&c, 30, 4, 40, 4, &err) == SWARF_OK, "shank: %s", err.message);
  CHECK(swarf_cutter_add_frustum(&c, 40, 10, 50, 16, &err) == SWARF_OK, "cone: %s", err.message);
  CHECK(swarf_cutter_add_frustum(&c, 50, 16, 80, 16, &err) == SWARF_OK, "cyl: %s", err.message);
  CHECK(swarf_cutter_finish(&c, &err) == SWARF_OK, "finish: %s", err.message);
  CHECK_NEAR(c.zmin, 30, 0, "body bottom");
  CHECK_NEAR(c.length, 80, 0, "body top");
  CHECK_NEAR(c.diameter, 32, 0, "body diameter");
  out_push(&o, 0, 30), out_push(&o, 4, 30), out_push(&o, 4, 40), out_push(&o, 10, 40);
  out_push(&o, 16, 50), out_push(&o, 16, 80), out_push(&o, 0, 80);
  compare("body shank+holder", &c, &o, 0, 1e-7);
  CHECK(swarf_cutter_add_frustum(&c, 5, 1, 5, 2, &err) == SWARF_ERR_TOOL, "z0 = z1 rejected");
  out_free(&o);
}

int main(void) {
  test_families();
  test_qss();
  test_errors();
  test_body();
  return check_done();
}
