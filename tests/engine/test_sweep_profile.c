/* SPDX-License-Identifier: MPL-2.0 */
/* test_sweep_profile.c -- swept volumes of profile cutters (every named
 * family, unions of pieces, QSS) on every kind of move, against an
 * independent truth: the minimum over many cutter instances of the cutter's
 * exact sdf (test_profile.c checks that sdf against the families' drawings),
 * with golden-section polish around every sampled local minimum.
 *   - lines (slot, plunge up and down, ramp), planar arcs and full circles,
 *     helices (and G18 arcs, G18 and G19 helices of several turns, searched
 *     in a one-turn window), xyza and 5-axis trt moves, and the paper's
 *     Example 2 motion (a turn about (2,1,2)/3 while moving along (1,1,0));
 *   - outside the swept volume the sweep equals the truth to 1e-6 mm; inside
 *     it is never shallower than the deepest instance (the plunge's closed
 *     form is the exact depth of the union, deeper);
 *   - the nearest instance (alpha) is one where the truth is attained;
 *   - nearest surface points of outside points lie on the characteristic
 *     curve of their time (swarf_sweep_char_curve), every curve point meets
 *     the characteristic condition.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "engine_private.h" /* the sweep's method */
#include "testkit.h"

#define VOXEL 0.1

static double truth(const swarf_cutter *c, const swarf_motion *m, const double p[3], int n) {
  static double g[20001];
  double best = INFINITY;
  for (int i = 0; i <= n; i++)
    g[i] = tk_rigid_instance(c, m, p, (double)i / n);
  for (int i = 0; i <= n; i++)
    best = fmin(best, g[i]);
  for (int i = 0; i <= n; i++) {
    double prev = i > 0 ? g[i - 1] : INFINITY, next = i < n ? g[i + 1] : INFINITY;
    if (g[i] <= prev && g[i] <= next && g[i] < best + 0.05)
      best = fmin(
          best, tk_rigid_golden(c, m, p, i > 0 ? (i - 1.0) / n : 0.0, i < n ? (i + 1.0) / n : 1.0));
  }
  return best;
}

/* A point within 3 voxels of the surface of a random instance. */
static void near_point(tk_rng *r, const swarf_cutter *c, const swarf_motion *m, double p[3]) {
  double q[3], t[3], U[9], a = tk_uniform(r, 0, 1), rr = 0.5 * c->diameter + 0.5;
  do {
    q[0] = tk_uniform(r, -rr, rr), q[1] = tk_uniform(r, -rr, rr);
    q[2] = tk_uniform(r, c->zmin - 0.5, c->length + 0.5);
  } while (fabs(swarf_cutter_sdf(c, q)) > 3 * VOXEL);
  swarf_motion_eval(m, a, t, U);
  for (int k = 0; k < 3; k++)
    p[k] = t[k] + U[3 * k] * q[0] + U[3 * k + 1] * q[1] + U[3 * k + 2] * q[2];
}

typedef struct {
  double out, shallow, deeper, alpha, curve;
  int nin, nout;
} errs;

static void compare(const char *name, const swarf_cutter *c, const swarf_motion *m, int npts,
                    int nsamp, errs *tot) {
  swarf_sweep s;
  tk_rng r = {0x51ed2701ull ^ (uint64_t)(size_t)npts * 7919u ^ (uint64_t)strlen(name)};
  errs e = {0, 0, 0, 0, 0, 0, 0};
  swarf_sweep_init_voxel(&s, c, m, VOXEL);
  for (int i = 0; i < npts; i++) {
    double p[3], a, lo[3], hi[3];
    near_point(&r, c, m, p);
    double d = swarf_sweep_sdf(&s, p, &a), tr = truth(c, m, p, nsamp);
    double at = tk_rigid_instance(c, m, p, a);
    if (tr >= 0) {
      e.out = fmax(e.out, fabs(d - tr)), e.nout++;
      e.alpha = fmax(e.alpha, at - tr);
    } else {
      e.shallow = fmax(e.shallow, d - tr), e.deeper = fmax(e.deeper, tr - d), e.nin++;
    }
    swarf_sweep_bounds(&s, lo, hi);
    for (int k = 0; k < 3; k++)
      CHECK(p[k] > lo[k] - 3 * VOXEL && p[k] < hi[k] + 3 * VOXEL, "%s: point in bounds", name);
  }
  printf("%-30s method %2d: outside %3d max |err| %.1e (alpha %.1e); inside %3d shallower %.1e "
         "deeper %.1e\n",
         name, swarf_sweep_cdata(&s)->method, e.nout, e.out, e.alpha, e.nin, e.shallow, e.deeper);
  CHECK(e.out <= 1e-6, "%s: outside error %g", name, e.out);
  CHECK(e.alpha <= 1e-6, "%s: alpha's instance off by %g", name, e.alpha);
  CHECK(e.shallow <= 1e-6, "%s: inside shallower than an instance by %g", name, e.shallow);
  tot->out = fmax(tot->out, e.out), tot->shallow = fmax(tot->shallow, e.shallow);
}

/* Outside points whose nearest instance is inside the move: the nearest
 * surface point lies on the characteristic curve of that time; every curve
 * point satisfies (v + omega x x) . n = 0. */
static void on_characteristic(const char *name, const swarf_cutter *c, const swarf_motion *m,
                              int npts, double *worst_all) {
  swarf_sweep s;
  swarf_char_curve cc;
  tk_rng r = {0xc0ffeeull ^ (uint64_t)strlen(name)};
  double worst = 0.0, worst_f = 0.0;
  int used = 0;
  swarf_sweep_init_voxel(&s, c, m, VOXEL);
  swarf_char_curve_init(&cc);
  for (int i = 0; i < 40 * npts && used < npts; i++) {
    double p[3], a, d, gw[3], x[3], best = INFINITY, t[3], U[9], tdot[3], v[3], w[3];
    near_point(&r, c, m, p);
    d = swarf_sweep_sdf(&s, p, &a);
    if (d < 0.2 * VOXEL || a < 0.02 || a > 0.98) continue;
    for (int k = 0; k < 3; k++) {
      double pp[3] = {p[0], p[1], p[2]}, pm[3] = {p[0], p[1], p[2]};
      pp[k] += 1e-6, pm[k] -= 1e-6;
      gw[k] = (tk_rigid_instance(c, m, pp, a) - tk_rigid_instance(c, m, pm, a)) / 2e-6;
    }
    for (int k = 0; k < 3; k++)
      x[k] = p[k] - d * gw[k];
    if (swarf_sweep_char_curve(&s, a, 1e-3, &cc) != SWARF_OK || cc.ncomp == 0) continue;
    for (size_t j = 0; j + 1 < cc.len; j++)
      best = fmin(best, tk_seg_dist(x, cc.pts[j].w, cc.pts[j + 1].w));
    swarf_motion_eval(m, a, t, U);
    swarf_motion_velocity(m, a, tdot, v, w);
    for (size_t j = 0; j < cc.len; j++) {
      const double *n = cc.pts[j].n, *q = cc.pts[j].x;
      double wx[3];
      tk_cross(w, q, wx);
      worst_f = fmax(worst_f,
                     fabs((v[0] + wx[0]) * n[0] + (v[1] + wx[1]) * n[1] + (v[2] + wx[2]) * n[2]));
    }
    worst = fmax(worst, best);
    used++;
  }
  swarf_char_curve_clear(&cc);
  printf("%-30s nearest points on the curves: %3d points, max distance %.2e mm; max |f| %.1e\n",
         name, used, worst, worst_f);
  CHECK(used >= npts / 4, "%s: enough points (%d)", name, used);
  CHECK(worst < 0.01, "%s: nearest points on the characteristic curve: %g mm", name, worst);
  CHECK(worst_f < 1e-9 * (1 + c->length), "%s: characteristic condition %g", name, worst_f);
  *worst_all = fmax(*worst_all, worst);
}

static swarf_motion machine_move(const char *machine, const double s6[6], const double e6[6]) {
  swarf_motion m;
  CHECK(tk_machine_move(machine, s6, e6, &m) == SWARF_OK, "motion on %s", machine);
  return m;
}

static void run_cutter(const char *cname, const swarf_cutter *c, int npts, errs *tot) {
  const double o[3] = {0, 0, 0}, x1[3] = {6, 1, 0}, dn[3] = {0, 0, -4}, upz[3] = {0, 0, 3};
  const double ramp[3] = {5, -2, -1.5}, up[3] = {0, 0, 1}, ny[3] = {0, 1, 0};
  const double c2[3] = {-4, 0, 0}, c18[3] = {-3, 0, 0}, rc[3] = {-2.5, 0, 0};
  const double c19[3] = {0, 0, -3}, nx[3] = {-1, 0, 0};
  const double a0[6] = {-3, 0, 6, 0, 0, 0}, a1[6] = {3, 0, 6, 50, 0, 0};
  const double t0[6] = {1, 2, 3, 10, 0, -30}, t1[6] = {3, 0, 2, 30, 0, 40};
  struct {
    const char *what;
    swarf_motion m;
    int nsamp;
  } mv[] = {{"slot", tk_line(o, x1), 4000},
            {"plunge down", tk_line(o, dn), 4000},
            {"plunge up", tk_line(o, upz), 4000},
            {"ramp", tk_line(o, ramp), 4000},
            {"arc", tk_helix(o, c2, up, 1.2, 0.0), 4000},
            {"ring", tk_helix(o, rc, up, 2 * tk_pi, 0.0), 8000},
            {"helix", tk_helix(o, c2, up, 2.0, -1.5), 8000},
            {"G18 arc", tk_helix(o, c18, ny, 1.0, 0.0), 4000},
            {"xyza", machine_move("xyza", a0, a1), 8000},
            {"xyzac-trt", machine_move("xyzac-trt", t0, t1), 8000},
            {"the paper's Example 2", tk_example2(2.0), 8000},
            {"G18 helix of 3.5 turns", tk_helix(o, c18, ny, 7 * tk_pi, 20.0), 16000},
            {"G19 helix of 2.5 turns", tk_helix(o, c19, nx, 5 * tk_pi, -12.0), 16000}};
  for (size_t i = 0; i < sizeof mv / sizeof mv[0]; i++) {
    char name[96];
    snprintf(name, sizeof name, "%s, %s", cname, mv[i].what);
    compare(name, c, &mv[i].m, npts, mv[i].nsamp, tot);
    if (i == 3 || i == 6 || i == 9 || i == 10)
      on_characteristic(name, c, &mv[i].m, npts, &tot->curve);
  }
}

static swarf_cutter make(swarf_cutter_spec s) {
  swarf_cutter c;
  swarf_error err;
  swarf_error_init(&err);
  CHECK(swarf_cutter_make(&c, &s, &err) == SWARF_OK, "make: %s", err.message);
  return c;
}

int main(int argc, char **argv) {
  int npts = argc > 1 ? atoi(argv[1]) : 60;
  swarf_cutter_spec s;
  swarf_cutter c;
  errs tot = {0, 0, 0, 0, 0, 0, 0};
  swarf_cutter_spec_init(&s), s.shape = SWARF_CUTTER_VEE, s.d = 4, s.angle = 60, s.length = 8;
  c = make(s), run_cutter("vee D4 A60", &c, npts, &tot);
  swarf_cutter_spec_init(&s), s.shape = SWARF_CUTTER_DRILL, s.d = 3, s.length = 8;
  c = make(s), run_cutter("drill D3", &c, npts, &tot);
  swarf_cutter_spec_init(&s), s.shape = SWARF_CUTTER_TAPER, s.d = 2, s.angle = 8, s.r = 1,
                              s.length = 8;
  c = make(s), run_cutter("taper ball D2 A8", &c, npts, &tot);
  swarf_cutter_spec_init(&s), s.shape = SWARF_CUTTER_LOLLIPOP, s.d = 4, s.neck = 2, s.length = 8;
  c = make(s), run_cutter("lollipop D4 N2", &c, npts, &tot);
  swarf_cutter_spec_init(&s), s.shape = SWARF_CUTTER_DOVETAIL, s.d = 6, s.angle = 60, s.h = 2;
  s.neck = 2.5, s.length = 8;
  c = make(s), run_cutter("dovetail D6 A60 H2 N2.5", &c, npts, &tot);
  swarf_cutter_spec_init(&s), s.shape = SWARF_CUTTER_QSS, s.qa = 2, s.qb = 3, s.qe = 0, s.qf = 0;
  c = make(s), run_cutter("qss 2,3,0,0", &c, npts / 3 + 1, &tot);
  swarf_cutter_spec_init(&s), s.shape = SWARF_CUTTER_QSS, s.qa = 1, s.qb = -1, s.qe = 0, s.qf = 0;
  c = make(s), run_cutter("qss 1,-1,0,0 (non-convex)", &c, npts / 3 + 1, &tot);
  printf("all: outside max error %.2e mm, inside shallower %.2e mm, nearest points %.2e mm from "
         "the characteristic curves\n",
         tot.out, tot.shallow, tot.curve);
  return check_done();
}
