/* SPDX-License-Identifier: MPL-2.0 */
/* test_sweep.c -- swept volumes of single moves.
 *
 * 1. Closed forms against analytic solids written here: the ball slot is a
 *    capsule below the ball centres, the flat slot a stadium prism, the full
 *    circle of a ball a torus, the plunge a cylinder.
 * 2. Every evaluator against the brute force of testkit.h (20000 instances
 *    plus golden section) on random moves of every kind and flat, ball and
 *    bull cutters: equal outside to 1e-6 mm, at least as deep inside; the
 *    instance at the returned alpha realizes the value; 1-Lipschitz.
 * 3. The sdf and the characteristic curves describe the same envelope:
 *    (a) the world points of the curve at any alpha lie on the boundary of a
 *        straight move's sweep (|sdf| < 1e-9), inside or on it for a helix;
 *    (b) for a point outside, the nearest point q on the instance at the
 *        returned alpha has a normal n with v(alpha) . n = 0 (stationarity =
 *        the characteristic condition) unless alpha is an end, and q is
 *        within the tolerance of the curve at that alpha.
 */
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "testkit.h"

enum {
  K_SLOT,
  K_PLUNGE,
  K_RAMP,
  K_ARC,
  K_RING,
  K_HELIX,
  K_TURNS,
  K_G18,
  K_G19,
  K_G18_TURNS,
  K_G19_TURNS,
  K_NKINDS
};
static const char *kind_name[K_NKINDS] = {"slot",
                                          "plunge",
                                          "ramp",
                                          "arc",
                                          "ring",
                                          "helix",
                                          "helix of 2-15 turns",
                                          "G18 arc",
                                          "G19 helix",
                                          "G18 of 1-15 turns",
                                          "G19 of 1-15 turns"};

static double tk_sign(tk_rng *r) {
  return tk_uniform(r, 0, 1) < 0.5 ? -1.0 : 1.0;
}

static swarf_motion random_move(tk_rng *r, int kind) {
  double p0[3], p1[3], c[3], nrm[3] = {0, 0, 0}, rad, ph, len = tk_uniform(r, 0.5, 12.0);
  for (int k = 0; k < 3; k++)
    p0[k] = c[k] = tk_uniform(r, -5, 5);
  ph = tk_uniform(r, 0, 2 * tk_pi);
  rad = tk_uniform(r, 0, 1) < 0.3 ? tk_uniform(r, 0.2, 3.0) : tk_uniform(r, 3.0, 12.0);
  switch (kind) {
  case K_SLOT:
  case K_PLUNGE:
  case K_RAMP: {
    double dz = kind == K_SLOT ? 0 : kind == K_PLUNGE ? 1 : tk_uniform(r, -1.5, 1.5);
    double d[3] = {kind == K_PLUNGE ? 0 : cos(ph), kind == K_PLUNGE ? 0 : sin(ph), dz};
    double m = sqrt(tk_dot(d, d));
    if (kind == K_PLUNGE) d[2] = tk_sign(r);
    for (int k = 0; k < 3; k++)
      p1[k] = p0[k] + len * d[k] / m;
    return tk_line(p0, p1);
  }
  case K_ARC:
  case K_RING:
  case K_HELIX:
  case K_TURNS: /* more than two turns: searched turn by turn */
    nrm[2] = tk_sign(r);
    p0[0] = c[0] + rad * cos(ph), p0[1] = c[1] + rad * sin(ph), p0[2] = c[2];
    if (kind == K_ARC) return tk_helix(p0, c, nrm, tk_uniform(r, 0.05, 2 * tk_pi - 0.05), 0.0);
    if (kind == K_RING)
      return tk_helix(p0, c, nrm, tk_uniform(r, 0, 1) < 0.7 ? 2 * tk_pi : 4 * tk_pi, 0.0);
    if (kind == K_TURNS)
      return tk_helix(p0, c, nrm, tk_uniform(r, 4.01 * tk_pi, 30 * tk_pi),
                      tk_sign(r) * tk_uniform(r, 0.3, 20));
    return tk_helix(p0, c, nrm, tk_uniform(r, 0.1, 4 * tk_pi), tk_sign(r) * tk_uniform(r, 0.2, 5));
  default: { /* G18, G19; more than one turn: searched in a one-turn window */
    int g18 = kind == K_G18 || kind == K_G18_TURNS, turns = kind >= K_G18_TURNS;
    int ax = g18 ? 1 : 0, o1 = g18 ? 2 : 1, o2 = g18 ? 0 : 2;
    double rise = tk_uniform(r, 0, 1) < (turns ? 0.2 : 0.5) ? 0.0
                  : turns                                   ? tk_sign(r) * tk_uniform(r, 0.3, 20)
                                                            : tk_sign(r) * tk_uniform(r, 0.2, 4);
    nrm[ax] = tk_sign(r);
    p0[ax] = c[ax], p0[o1] = c[o1] + rad * cos(ph), p0[o2] = c[o2] + rad * sin(ph);
    return tk_helix(p0, c, nrm,
                    turns ? tk_uniform(r, 2.01 * tk_pi, 30 * tk_pi) : tk_uniform(r, 0.1, 2 * tk_pi),
                    rise);
  }
  }
}

/* ---- 1. closed forms against analytic solids ----------------------------- */

static void test_analytic(void) {
  swarf_cutter ball, flat;
  swarf_sweep s;
  swarf_motion m;
  tk_rng r = {4242};
  const double a[3] = {1, 2, -3}, b[3] = {9, -4, -3}, top[3] = {2, 1, 5}, bot[3] = {2, 1, -3};
  double c[3] = {0, 0, -2}, st[3] = {7, 0, -2}, up[3] = {0, 0, 1};
  swarf_cutter_init(&ball, SWARF_CUTTER_BALL, 6.0, 0, 20.0, NULL);
  swarf_cutter_init(&flat, SWARF_CUTTER_FLAT, 6.0, 0, 20.0, NULL);
  m = tk_line(a, b); /* ball slot: capsule of radius 3 about the centre segment */
  swarf_sweep_init(&s, &ball, &m);
  for (int i = 0; i < 4000; i++) {
    double p[3] = {tk_uniform(&r, -4, 14), tk_uniform(&r, -9, 7), tk_uniform(&r, -8, 0)};
    double a3[3] = {a[0], a[1], a[2] + 3}, b3[3] = {b[0], b[1], b[2] + 3};
    CHECK_NEAR(swarf_sweep_sdf(&s, p, NULL), tk_seg_dist(p, a3, b3) - 3, 1e-12, "ball slot");
  }
  swarf_sweep_init(&s, &flat, &m); /* flat slot: stadium prism over [-3, 17] */
  for (int i = 0; i < 4000; i++) {
    double p[3] = {tk_uniform(&r, -4, 14), tk_uniform(&r, -9, 7), tk_uniform(&r, -8, 20)};
    double q[3] = {p[0], p[1], a[2]}, d = tk_seg_dist(q, a, b) - 3, dz = fmax(-3 - p[2], p[2] - 17);
    double want = d > 0 || dz > 0 ? hypot(fmax(d, 0), fmax(dz, 0)) : fmax(d, dz);
    CHECK_NEAR(swarf_sweep_sdf(&s, p, NULL), want, 1e-12, "flat slot");
  }
  m = tk_helix(st, c, up, 2 * tk_pi, 0.0); /* ball ring: torus (R 7, r 3) below z = 1 */
  swarf_sweep_init(&s, &ball, &m);
  for (int i = 0; i < 4000; i++) {
    double p[3] = {tk_uniform(&r, -11, 11), tk_uniform(&r, -11, 11), tk_uniform(&r, -6, 1)};
    double want = hypot(hypot(p[0], p[1]) - 7, p[2] - 1) - 3;
    CHECK_NEAR(swarf_sweep_sdf(&s, p, NULL), want, 1e-12, "ball ring = torus");
  }
  m = tk_line(top, bot); /* flat plunge: cylinder r 3 over z in [-3, 25] */
  swarf_sweep_init(&s, &flat, &m);
  for (int i = 0; i < 4000; i++) {
    double p[3] = {tk_uniform(&r, -4, 8), tk_uniform(&r, -5, 7), tk_uniform(&r, -6, 28)};
    double d = hypot(p[0] - 2, p[1] - 1) - 3, dz = fmax(-3 - p[2], p[2] - 25);
    double want = d > 0 || dz > 0 ? hypot(fmax(d, 0), fmax(dz, 0)) : fmax(d, dz);
    CHECK_NEAR(swarf_sweep_sdf(&s, p, NULL), want, 1e-12, "flat plunge = cylinder");
  }
}

/* ---- 2. against the brute force ------------------------------------------ */

typedef struct {
  double worst_out, worst_in, worst_alpha;
  int n_out, n_in;
} brute_stats;

static void compare_point(const swarf_cutter *c, const swarf_motion *m, const swarf_sweep *s,
                          const double p[3], brute_stats *st, const char *what) {
  double alpha, d = swarf_sweep_sdf(s, p, &alpha), want = tk_brute(c, m, p, 20000, NULL);
  if (want > 1e-9) {
    double at = tk_instance(c, m, p, alpha);
    st->n_out++;
    st->worst_out = fmax(st->worst_out, fabs(d - want));
    st->worst_alpha = fmax(st->worst_alpha, fabs(at - d));
    CHECK(fabs(d - want) <= 1e-6, "%s: outside %.12g vs brute %.12g", what, d, want);
    CHECK(fabs(at - d) <= 1e-9, "%s: instance at alpha %.9g gives %.12g, sdf %.12g", what, alpha,
          at, d);
  } else {
    st->n_in++;
    st->worst_in = fmax(st->worst_in, d - want);
    CHECK(d <= want + 1e-6, "%s: inside %.12g vs brute %.12g", what, d, want);
  }
}

static void test_brute(const swarf_cutter *c, const char *cname, tk_rng *r) {
  for (int kind = 0; kind < K_NKINDS; kind++) {
    brute_stats st = {0, -INFINITY, 0, 0, 0};
    char what[64];
    snprintf(what, sizeof what, "%s %s", cname, kind_name[kind]);
    for (int mv = 0; mv < 5; mv++) {
      swarf_motion m = random_move(r, kind);
      swarf_sweep s;
      double lo[3], hi[3];
      swarf_sweep_init(&s, c, &m);
      swarf_sweep_bounds(&s, lo, hi);
      for (int i = 0; i < 40; i++) {
        double p[3], q[3], e[3];
        for (int k = 0; k < 3; k++)
          p[k] = tk_uniform(r, lo[k] - 1.5, hi[k] + 1.5);
        if (i % 4 == 0) p[2] = tk_uniform(r, lo[2] - 1.5, lo[2] + 0.5 * c->diameter);
        compare_point(c, &m, &s, p, &st, what);
        tk_unit(r, e); /* 1-Lipschitz on a nearby pair */
        for (int k = 0; k < 3; k++)
          q[k] = p[k] + 0.05 * e[k];
        CHECK(fabs(swarf_sweep_sdf(&s, p, NULL) - swarf_sweep_sdf(&s, q, NULL)) <= 0.05 + 1e-12,
              "%s: 1-Lipschitz", what);
      }
    }
    printf("%-16s vs brute: %3d outside, max |diff| %.2e, alpha realizes it to %.1e; "
           "%3d inside, max (sdf - brute) %.2e\n",
           what, st.n_out, st.worst_out, st.worst_alpha, st.n_in, st.n_in ? st.worst_in : 0.0);
  }
}

/* ---- 2b. supporting planes of straight moves ------------------------------ */

/* swarf_sweep_support on slots, plunges and ramps: its d is the sdf's, bit
 * for bit; where it gives a plane, the normal is the sdf's gradient (central
 * differences) and no point of the box around the move lies below the plane
 * (the sweep is convex), inside the sweep as well as outside: planes at a
 * quarter of the points inside at least. */
static void test_support(const swarf_cutter *c, const char *cname, tk_rng *r) {
  for (int kind = K_SLOT; kind <= K_RAMP; kind++) {
    char what[64];
    int planes = 0, points = 0, inside = 0, inside_planes = 0;
    double worst_grad = 0.0, worst_below = 0.0;
    snprintf(what, sizeof what, "%s %s", cname, kind_name[kind]);
    for (int mv = 0; mv < 6; mv++) {
      swarf_motion m = random_move(r, kind);
      swarf_sweep s;
      double lo[3], hi[3];
      swarf_sweep_init(&s, c, &m);
      swarf_sweep_bounds(&s, lo, hi);
      for (int i = 0; i < 60; i++, points++) {
        double p[3], d, g[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++)
          p[k] = tk_uniform(r, lo[k] - 2.0, hi[k] + 2.0);
        int has = swarf_sweep_support(&s, p, &d, g);
        CHECK(d == swarf_sweep_sdf(&s, p, NULL), "%s: support's d %.17g is not the sdf's", what, d);
        inside += d < 0.0;
        if (!has) continue;
        planes++;
        inside_planes += d < 0.0;
        CHECK(fabs(tk_dot(g, g) - 1.0) <= 1e-12, "%s: d %.3g, |g|^2 %.15g", what, d, tk_dot(g, g));
        for (int k = 0; k < 3; k++) {
          double a[3] = {p[0], p[1], p[2]}, b[3] = {p[0], p[1], p[2]}, h = 1e-6;
          a[k] += h, b[k] -= h;
          double fd = (swarf_sweep_sdf(&s, a, NULL) - swarf_sweep_sdf(&s, b, NULL)) / (2 * h);
          worst_grad = fmax(worst_grad, fabs(fd - g[k]));
        }
        for (int j = 0; j < 50; j++) {
          double q[3], e[3];
          for (int k = 0; k < 3; k++)
            q[k] = tk_uniform(r, lo[k] - 2.0, hi[k] + 2.0), e[k] = q[k] - p[k];
          worst_below = fmax(worst_below, d + tk_dot(g, e) - swarf_sweep_sdf(&s, q, NULL));
        }
      }
    }
    CHECK(planes >= points / 4, "%s: planes at only %d of %d points", what, planes, points);
    CHECK(inside > 0 && inside_planes >= inside / 4, "%s: planes at only %d of %d points inside",
          what, inside_planes, inside);
    CHECK(worst_grad <= 1e-5, "%s: normal vs the sdf's gradient: %.2e", what, worst_grad);
    CHECK(worst_below <= 1e-9, "%s: a point %.2e below the supporting plane", what, worst_below);
    printf("%-16s support: planes at %3d of %3d points (%3d of %3d inside), max |g - grad| %.1e,"
           " max below %.1e\n",
           what, planes, points, inside_planes, inside, worst_grad, worst_below);
  }
}

/* ---- 3. the sdf and the characteristic curves ------------------------------ */

static double poly_dist_w(const swarf_char_curve *cc, const double p[3]) {
  double best = INFINITY;
  for (size_t k = 0; k < cc->ncomp; k++)
    for (size_t i = cc->start[k]; i + 1 < cc->start[k + 1]; i++)
      best = fmin(best, tk_seg_dist(p, cc->pts[i].w, cc->pts[i + 1].w));
  return best;
}

/* Nearest point q (world) and outward normal n on the instance at alpha. */
static void nearest_on_instance(const swarf_cutter *c, const swarf_motion *m, double alpha,
                                const double p[3], double q[3], double n[3]) {
  double t[3], x[3], R = c->corner_radius, a = 0.5 * c->diameter - R, r, cp[3], l;
  swarf_motion_eval(m, alpha, t, NULL);
  for (int k = 0; k < 3; k++)
    x[k] = p[k] - t[k];
  r = hypot(x[0], x[1]);
  cp[0] = r > a ? x[0] * a / r : x[0];
  cp[1] = r > a ? x[1] * a / r : x[1];
  cp[2] = fmin(fmax(x[2], R), c->length - R);
  for (int k = 0; k < 3; k++)
    n[k] = x[k] - cp[k];
  l = sqrt(tk_dot(n, n));
  for (int k = 0; k < 3; k++)
    n[k] /= l;
  for (int k = 0; k < 3; k++)
    q[k] = t[k] + cp[k] + R * n[k];
}

/* Where a flat face slides in its plane (n = +-e_z, v_z = 0) or the side
 * slides along the axis (n_z = 0, v_xy = 0), the characteristic set is that
 * whole face, which the polyline represents by one segment or by its rims:
 * q on the face is then characteristic without lying on the polyline. */
static int plane_contact(const double n[3], const double v[3]) {
  double sp = sqrt(tk_dot(v, v));
  if (fabs(fabs(n[2]) - 1.0) < 1e-12 && fabs(v[2]) <= 1e-9 * sp) return 1;
  return fabs(n[2]) < 1e-12 && hypot(v[0], v[1]) <= 1e-9 * sp;
}

static void test_envelope(const swarf_cutter *c, const char *cname, tk_rng *r) {
  const double alphas[5] = {0.0, 0.25, 0.5, 0.9, 1.0}, tol = 1e-3;
  swarf_char_curve cc;
  swarf_char_curve_init(&cc);
  for (int kind = 0; kind < K_NKINDS; kind++) {
    double worst_a = 0, worst_f = 0, worst_q = 0;
    int nb = 0, nface = 0, straight = kind <= K_RAMP;
    char what[64];
    snprintf(what, sizeof what, "%s %s", cname, kind_name[kind]);
    for (int mv = 0; mv < 4; mv++) {
      swarf_motion m = random_move(r, kind);
      swarf_sweep s;
      double lo[3], hi[3];
      swarf_sweep_init(&s, c, &m);
      swarf_sweep_bounds(&s, lo, hi);
      for (int j = 0; j < 5; j++) { /* (a) */
        CHECK((swarf_sweep_char_curve(&s, alphas[j], tol, &cc) == SWARF_OK ? (int)cc.ncomp : -1) >=
                  1,
              "%s: a curve", what);
        for (size_t i = 0; i < cc.len; i++) {
          double d = swarf_sweep_sdf(&s, cc.pts[i].w, NULL);
          worst_a = fmax(worst_a, straight ? fabs(d) : d);
          CHECK(straight ? fabs(d) < 1e-9 : d <= 1e-9, "%s: curve point sdf %.3g", what, d);
        }
      }
      for (int i = 0; i < 60; i++) { /* (b) */
        double p[3], alpha, d, q[3], n[3], td[3], v[3], w[3], f;
        for (int k = 0; k < 3; k++)
          p[k] = tk_uniform(r, lo[k] - 2, hi[k] + 2);
        d = swarf_sweep_sdf(&s, p, &alpha);
        if (d < 1e-3 || alpha <= 1e-12 || alpha >= 1 - 1e-12) continue;
        nearest_on_instance(c, &m, alpha, p, q, n);
        swarf_motion_velocity(&m, alpha, td, v, w);
        f = tk_dot(v, n);
        nb++;
        worst_f = fmax(worst_f, fabs(f));
        CHECK(fabs(f) <= 1e-6, "%s: v . n = %.3g at alpha %.6f", what, f, alpha);
        swarf_sweep_char_curve(&s, alpha, tol, &cc);
        if (poly_dist_w(&cc, q) > tol && plane_contact(n, v)) {
          nface++; /* a whole flat face or the side is characteristic */
          continue;
        }
        worst_q = fmax(worst_q, poly_dist_w(&cc, q));
        CHECK(poly_dist_w(&cc, q) <= tol + 1e-9, "%s: q off the curve by %.3g", what,
              poly_dist_w(&cc, q));
      }
    }
    printf("%-16s (a) max %s %.1e   (b) %3d points: max |v.n| %.1e, max dist(q, curve) %.2e"
           " (%d on a sliding face)\n",
           what, straight ? "|sdf(w)|" : " sdf(w) ", worst_a, nb, worst_f, worst_q, nface);
  }
  swarf_char_curve_clear(&cc);
}

int main(void) {
  swarf_cutter cs[3];
  const char *names[3] = {"flat", "ball", "bull"};
  tk_rng r = {20240601};
  swarf_cutter_init(&cs[0], SWARF_CUTTER_FLAT, 6.0, 0, 20.0, NULL);
  swarf_cutter_init(&cs[1], SWARF_CUTTER_BALL, 3.175, 0, 12.0, NULL);
  swarf_cutter_init(&cs[2], SWARF_CUTTER_BULL, 10.0, 2.0, 25.0, NULL);
  test_analytic();
  for (int i = 0; i < 3; i++)
    test_brute(&cs[i], names[i], &r);
  for (int i = 0; i < 3; i++)
    test_support(&cs[i], names[i], &r);
  for (int i = 0; i < 3; i++)
    test_envelope(&cs[i], names[i], &r);
  return check_done();
}
