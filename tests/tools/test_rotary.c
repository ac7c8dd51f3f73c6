/* SPDX-License-Identifier: MPL-2.0 */
/* test_rotary.c -- rotary programs end to end (G-code text -> parser ->
 * machine kinematics -> rigid sweeps -> OpenVDB stock) against a truth
 * stock built here: the same initial stock with the volume of the exact
 * cutter sdf minimised over poses 10 times finer than the production time
 * steps, with golden-section polish at each sampled minimum (to ~1e-9 mm;
 * tests/engine/test_sweep_rigid.c samples 100 times finer) removed. Also the
 * stamping baseline (the cutter at the production's own poses) removed the
 * same way. Compared: every active voxel within one voxel of the surface
 * (error in voxels) and the removed volume.
 *   - xyza: a ball held at Z while A turns 90 degrees, in a cylinder stock;
 *   - xyza: X and A together (a 4th-axis helix);
 *   - xyzac-trt (TCP): a move changing A and C together, in a box.
 * usage: test_rotary [NAME] (NAME: only the case of that name; the sanitized
 * suite's tools_rotary_fast runs the TCP case).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "engine_private.h" /* the sweep's typed data */
#include "move_motion.h"
#include "swarf_sim.h"

#define VOXEL 0.1

typedef struct {
  const swarf_cutter *c;
  const swarf_motion *m;
  int n, polish;
  double step; /* bound on how far any cutter point moves between coarse poses, mm */
  int coarse;  /* number of coarse poses (the production's) */
} poses;

static double instance(const poses *ps, const double p[3], double a) {
  double t[3], U[9], d[3], q[3];
  swarf_motion_eval(ps->m, a, t, U);
  for (int k = 0; k < 3; k++)
    d[k] = p[k] - t[k];
  for (int k = 0; k < 3; k++)
    q[k] = U[k] * d[0] + U[3 + k] * d[1] + U[6 + k] * d[2];
  return swarf_cutter_sdf(ps->c, q);
}

static double golden(const poses *ps, const double p[3], double lo, double hi) {
  const double g = 0.6180339887498949;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = instance(ps, p, x1), f2 = instance(ps, p, x2);
  for (int it = 0; it < 50; it++) {
    if (f1 < f2)
      hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = instance(ps, p, x1);
    else
      lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = instance(ps, p, x2);
  }
  return fmin(f1, f2);
}

/* min over n + 1 poses; with polish, golden section at each local minimum.
 * Far from the volume (more than 4 voxels by the coarse poses and the travel
 * bound) the value is that lower bound: enough for the stock's block tests. */
static double pose_sdf(const void *ctx, double x, double y, double z) {
  const poses *ps = ctx;
  const double p[3] = {x, y, z};
  double best = INFINITY, prev = INFINITY, cur = instance(ps, p, 0.0);
  if (ps->polish) {
    double coarse = INFINITY;
    for (int i = 0; i <= ps->coarse; i++)
      coarse = fmin(coarse, instance(ps, p, (double)i / ps->coarse));
    if (coarse - ps->step > 4 * VOXEL) return coarse - ps->step;
  }
  for (int i = 0; i <= ps->n; i++) {
    double next = i < ps->n ? instance(ps, p, (i + 1.0) / ps->n) : INFINITY;
    best = fmin(best, cur);
    if (ps->polish && cur <= prev && cur <= next && cur < best + 0.5)
      best = fmin(best, golden(ps, p, i > 0 ? (i - 1.0) / ps->n : 0.0,
                               i < ps->n ? (i + 1.0) / ps->n : 1.0));
    prev = cur, cur = next;
  }
  return best;
}

typedef struct {
  const swarf_stock *ref;
  double max_err;
  long n;
} cmp;

static void visit(void *ctx, const double c[3], float value) {
  cmp *k = ctx;
  double ref = swarf_stock_voxel_value(k->ref, c[0], c[1], c[2], NULL);
  if (fabs(ref) > VOXEL) return;
  k->max_err = fmax(k->max_err, fabs(value - ref) / VOXEL);
  k->n++;
}

/* Remove the move's volume with n poses (polished or not) from a stock made
 * by the program's approach moves `pre` (the machine starts at 0,0,0). */
static swarf_stock *reference(const swarf_sim_config *cfg, const char *pre, const swarf_cutter *c,
                              const swarf_motion *m, int n, int polish, int coarse, double step) {
  swarf_stock *s = NULL;
  swarf_sweep sw;
  swarf_sim_report rep;
  poses ps = {c, m, n, polish, step, coarse};
  double lo[3], hi[3];
  CHECK(swarf_sim_run_text(cfg, "pre", pre, strlen(pre), &s, &rep, NULL) == 0, "approach");
  if (s == NULL) return NULL;
  swarf_sweep_init_voxel(&sw, c, m, VOXEL);
  swarf_sweep_bounds(&sw, lo, hi);
  CHECK(swarf_stock_remove(s, lo, hi, pose_sdf, &ps, NULL) == SWARF_OK, "reference removal");
  return s;
}

static double vol_pre(const swarf_sim_config *cfg, const char *pre) {
  swarf_stock *s = NULL;
  swarf_sim_report rep;
  double v = 0;
  if (swarf_sim_run_text(cfg, "pre", pre, strlen(pre), &s, &rep, NULL) == 0)
    v = rep.volume_before - rep.volume_after;
  swarf_stock_free(s);
  return v;
}

static const char *only; /* run only the case of this name (NULL: all) */
static int cases_run;

static void run_case(const char *name, const char *machine, const char *stock, const char *tool,
                     const char *pre, const char *gcode, const double s6[6], const double e6[6]) {
  if (only && strcmp(only, name) != 0) return;
  cases_run++;
  swarf_sim_config cfg;
  swarf_sim_report rep;
  swarf_stock *out = NULL, *truth, *stamped;
  swarf_motion m;
  swarf_move mv;
  swarf_sweep sw;
  swarf_error err;
  swarf_sim_config_init(&cfg);
  cfg.voxel = VOXEL;
  cfg.half_width = 3;
  CHECK(swarf_machine_parse(&cfg.machine, machine, &err) == SWARF_OK, "%s", err.message);
  CHECK(swarf_sim_parse_stock(stock, &cfg.stock, &err) == 0, "%s", err.message);
  CHECK(swarf_sim_parse_tool(tool, &cfg.tools[0], &err) == 0, "%s", err.message);
  cfg.ntools = 1;
  int rc = swarf_sim_run_text(&cfg, name, gcode, strlen(gcode), &out, &rep, &err);
  CHECK(rc == 0, "%s: run: %s", name, err.message);
  if (rc != 0) return;
  /* the same move, built here from its axis values */
  memset(&mv, 0, sizeof mv);
  mv.kind = SWARF_MOVE_LINE;
  mv.feed = 100;
  memcpy(mv.start, s6, sizeof mv.start);
  memcpy(mv.end, e6, sizeof mv.end);
  CHECK(swarf_machine_motion(&cfg.machine, &mv, &m, NULL) == SWARF_OK, "motion");
  swarf_sweep_init_voxel(&sw, &cfg.tools[0].cutter, &m, VOXEL);
  int n = swarf_sweep_cdata(&sw)->u.rigid.n; /* the production's time steps */
  const swarf_cutter *c = &cfg.tools[0].cutter;
  double dt = 0.0,
         reach = hypot(0.5 * c->diameter, c->length) + fabs(s6[0]) + fabs(s6[1]) + fabs(s6[2]) + 6;
  for (int k = 0; k < 3; k++)
    dt += (e6[k] - s6[k]) * (e6[k] - s6[k]);
  double step =
      1.1 * (sqrt(dt) + reach * (fabs(e6[3] - s6[3]) + fabs(e6[5] - s6[5])) * M_PI / 180) / n;
  truth = reference(&cfg, pre, c, &m, 10 * n, 1, n, step);
  stamped = reference(&cfg, pre, c, &m, n, 0, n, step);
  if (truth == NULL || stamped == NULL) return;
  cmp a = {truth, 0, 0}, b = {truth, 0, 0};
  swarf_stock_visit_active(out, visit, &a);
  swarf_stock_visit_active(stamped, visit, &b);
  double v0 = rep.volume_before - vol_pre(&cfg, pre), vt = v0 - swarf_stock_volume(truth);
  double vs = v0 - swarf_stock_volume(stamped), vp = v0 - rep.volume_after;
  printf("%-22s %3d steps: swept max %.1e voxel, removed %.3f mm^3 vs truth %.3f (%+.3f%%); "
         "stamped max %.3f voxel, removed %+.3f%%\n",
         name, n, a.max_err, vp, vt, 100 * (vp - vt) / vt, b.max_err, 100 * (vs - vt) / vt);
  CHECK(a.n > 1000, "%s: compared %ld voxels", name, a.n);
  CHECK(a.max_err < 0.01, "%s: swept error %g voxel (aim 0.1)", name, a.max_err);
  CHECK(fabs(vp - vt) < 1e-4 * vt, "%s: removed volume %g vs %g", name, vp, vt);
  CHECK(b.max_err > 0.005 && b.max_err > 10 * a.max_err, "%s: stamping worse: %g vs %g voxel", name,
        b.max_err, a.max_err);
  CHECK(fabs(vs - vt) > 10 * fabs(vp - vt), "%s: stamped volume worse", name);
  swarf_stock_free(out);
  swarf_stock_free(truth);
  swarf_stock_free(stamped);
}

int main(int argc, char **argv) {
  only = argc > 1 ? argv[1] : NULL;
  {
    const double s6[6] = {0, 0, 4, 0, 0, 0}, e6[6] = {0, 0, 4, 90, 0, 0};
    run_case("xyza rotary only", "xyza", "cylinder:x,5,-4,4", "T1=ball,D2,L6", "G0 X0 Y0 Z4\nM2\n",
             "G0 X0 Y0 Z4\nG1 A90 F100\nM2\n", s6, e6);
  }
  {
    const double s6[6] = {-3, 0, 4, 0, 0, 0}, e6[6] = {3, 0, 4, 90, 0, 0};
    run_case("xyza 4th-axis helix", "xyza", "cylinder:x,5,-5,5", "T1=flat,D2,L6",
             "G0 X-3 Y0 Z4\nM2\n", "G0 X-3 Y0 Z4\nG1 X3 A90 F100\nM2\n", s6, e6);
  }
  {
    const double s6[6] = {-1, 0, -0.5, 0, 0, 0}, e6[6] = {2, 1, -0.8, 35, 0, 60};
    run_case("xyzac-trt A+C (TCP)", "xyzac-trt", "box:-5,-4,-4,5,5,0", "T1=ball,D2,L6",
             "G0 X-1 Y0 Z-0.5 A0 C0\nM2\n",
             "G0 X-1 Y0 Z-0.5 A0 C0\nG1 X2 Y1 Z-0.8 A35 C60 F100\nM2\n", s6, e6);
  }
  CHECK(cases_run > 0, "no case named '%s'", only ? only : "");
  return check_done();
}
