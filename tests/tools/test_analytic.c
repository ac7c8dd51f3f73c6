/* SPDX-License-Identifier: MPL-2.0 */
/* test_analytic.c -- end-to-end simulations against analytic swept volumes.
 *
 * A straight slot, a full circular groove and a helix of two and one of
 * twelve turns (the engine searches those turn by turn), and helices of
 * twelve turns about the Y (G18) and X (G19) axes (searched in a one-turn
 * window), each milled with a ball and a flat cutter through the whole pipeline (G-code text ->
 * parser -> motions -> sweeps -> OpenVDB stock). The remaining grid's values near the surface are
 * compared with the signed distance of (box minus sweep), where the sweep's distance is written
 * here independently of the engine (closed forms for slots and grooves, dense sampling for the
 * helix), and the removed volume with the analytic volume (Pappus for grooves, a lower-envelope
 * quadrature for the helix).
 *
 * Tolerances (stated in voxels h): values within 0.1 h of the reference at
 * every active voxel closer than 1 h to the surface; removed volume within
 * 0.5 % (it comes from OpenVDB's levelSetVolume on both the box and the
 * result, whose discretization error dominates).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "swarf_sim.h"

#define VOXEL 0.2
#define LEN 16.0 /* cutting length of every test cutter */

static const double box_lo[3] = {0, 0, -10}, box_hi[3] = {40, 30, 0};

typedef struct {
  const char *name;
  const char *gcode;
  const char *tool;
  double (*sweep_sdf)(const double p[3]); /* reference */
  double volume;                          /* reference removed volume */
  int turns;                              /* the helix's (helix_turns) */
  int volume_only; /* no voxel comparison (the sampled reference would be slow: the engine's
                      values for many turns are checked by tests/engine/test_sweep.c) */
} sim_case;

/* ---- independent geometry ------------------------------------------------ */

static double clampd(double v, double lo, double hi) {
  return v < lo ? lo : v > hi ? hi : v;
}

/* Signed distance to the 2-D box {|u| <= 0 for u = r - a... }: q = (qa, qb) are
 * signed distances to two slabs; exact combination. */
static double combine(double qa, double qb) {
  double oa = fmax(qa, 0.0), ob = fmax(qb, 0.0);
  return sqrt(oa * oa + ob * ob) + fmin(fmax(qa, qb), 0.0);
}

static double interval_sd(double z, double lo, double hi) {
  return fmax(lo - z, z - hi);
}

static double box_sdf(const double p[3]) {
  double q[3], o = 0.0, m = -1e30;
  for (int k = 0; k < 3; k++) {
    q[k] = fmax(box_lo[k] - p[k], p[k] - box_hi[k]);
    o += fmax(q[k], 0.0) * fmax(q[k], 0.0);
    m = fmax(m, q[k]);
  }
  return sqrt(o) + fmin(m, 0.0);
}

/* Ball cutter of radius r with tip at height tip: a capsule whose axis runs
 * from tip + r to tip + LEN - r. Flat: cylinder of radius r, z in [tip, tip+LEN]. */
static double ball_column(double dh, double z, double zlo_tip, double zhi_tip, double r) {
  return combine(dh, interval_sd(z, zlo_tip + r, zhi_tip + LEN - r)) - r;
}
static double flat_column(double dh, double z, double zlo_tip, double zhi_tip, double r) {
  return combine(dh - r, interval_sd(z, zlo_tip, zhi_tip + LEN));
}

/* Horizontal distance from (x, y) to the segment y = y0, x in [x0, x1]. */
static double seg_x_dist(const double p[3], double x0, double x1, double y0) {
  return hypot(p[0] - clampd(p[0], x0, x1), p[1] - y0);
}

/* Slots: plunge at (5, 15) from z = 5 to -2, then along X to 35. */
static double ball_slot(const double p[3]) {
  double plunge = ball_column(hypot(p[0] - 5, p[1] - 15), p[2], -2, 5, 3);
  double slot = ball_column(seg_x_dist(p, 5, 35, 15), p[2], -2, -2, 3);
  return fmin(plunge, slot);
}
static double flat_slot(const double p[3]) {
  double plunge = flat_column(hypot(p[0] - 5, p[1] - 15), p[2], -2, 5, 3);
  double slot = flat_column(seg_x_dist(p, 5, 35, 15), p[2], -2, -2, 3);
  return fmin(plunge, slot);
}

/* Grooves: a full circle of radius 10 about (20, 15), tip at -1.5, r = 2. */
static double groove_dh(const double p[3]) {
  return fabs(hypot(p[0] - 20, p[1] - 15) - 10);
}
static double ball_groove(const double p[3]) {
  double plunge = ball_column(hypot(p[0] - 30, p[1] - 15), p[2], -1.5, 5, 2);
  return fmin(plunge, ball_column(groove_dh(p), p[2], -1.5, -1.5, 2));
}
static double flat_groove(const double p[3]) {
  double plunge = flat_column(hypot(p[0] - 30, p[1] - 15), p[2], -1.5, 5, 2);
  return fmin(plunge, flat_column(groove_dh(p), p[2], -1.5, -1.5, 2));
}

/* Helix: about (20, 15), radius 8, from (28, 15, 1) clockwise (G2), two turns
 * (helix_turns; 12 for the engine's turn-by-turn search of helices of more
 * than two turns) down to z = -5, r = 2; then a retract to z = 5. */
static int helix_turns = 2;
#define HELIX_N (2000 * helix_turns)
static void helix_at(double a, double t[3]) {
  double th = -a * 2.0 * M_PI * helix_turns; /* G2 turns clockwise */
  t[0] = 20 + 8 * cos(th);
  t[1] = 15 + 8 * sin(th);
  t[2] = 1 - 6 * a;
}

/* A lower bound of the helix sweep's distance: every instance lies in the
 * solid annulus rho in [6, 10] about the axis, z >= -5. Where it exceeds
 * PRUNE the sampled minimum is not needed: visit() only compares voxels with
 * |reference| < h, and a sweep distance above h leaves the box's value as
 * the reference whatever it is exactly. */
#define PRUNE 0.5
static double helix_lower_bound(const double p[3]) {
  return combine(fabs(hypot(p[0] - 20, p[1] - 15) - 8) - 2, -5 - p[2]);
}

/* The helix's samples i / HELIX_N, computed once per helix_turns. */
static const double *helix_samples(void) {
  static double *pts = NULL;
  static int turns = 0;
  if (turns != helix_turns) {
    free(pts);
    pts = malloc(sizeof(double) * 3 * (HELIX_N + 1));
    if (pts == NULL) abort();
    for (int i = 0; i <= HELIX_N; i++)
      helix_at((double)i / HELIX_N, &pts[3 * i]);
    turns = helix_turns;
  }
  return pts;
}

static double helix_min(const double p[3], int ball) {
  double best = 1e30, ba = 0, t[3], lb = helix_lower_bound(p);
  if (lb > PRUNE) return lb;
  const double *pts = helix_samples();
  for (int i = 0; i <= HELIX_N; i++) {
    const double *s = &pts[3 * i], dx = p[0] - s[0], dy = p[1] - s[1];
    /* both columns lie within radius 2 of their axis: distance >= dh - 2 */
    if (best + 2 > 0 && dx * dx + dy * dy >= (best + 2) * (best + 2)) continue;
    double dh = hypot(dx, dy);
    double d = ball ? ball_column(dh, p[2], s[2], s[2], 2) : flat_column(dh, p[2], s[2], s[2], 2);
    if (d < best) best = d, ba = (double)i / HELIX_N;
  }
  /* golden refinement around the best sample */
  double lo = fmax(0, ba - 1.0 / HELIX_N), hi = fmin(1, ba + 1.0 / HELIX_N);
  for (int it = 0; it < 60; it++) {
    double m1 = hi - (hi - lo) * 0.618, m2 = lo + (hi - lo) * 0.618, d1, d2;
    helix_at(m1, t);
    d1 = ball ? ball_column(hypot(p[0] - t[0], p[1] - t[1]), p[2], t[2], t[2], 2)
              : flat_column(hypot(p[0] - t[0], p[1] - t[1]), p[2], t[2], t[2], 2);
    helix_at(m2, t);
    d2 = ball ? ball_column(hypot(p[0] - t[0], p[1] - t[1]), p[2], t[2], t[2], 2)
              : flat_column(hypot(p[0] - t[0], p[1] - t[1]), p[2], t[2], t[2], 2);
    if (d1 < d2)
      hi = m2;
    else
      lo = m1;
    best = fmin(best, fmin(d1, d2));
  }
  return best;
}

/* The helix ends at angle -4 pi, i.e. back at (28, 15); the retract there. */
static double ball_helix(const double p[3]) {
  return fmin(helix_min(p, 1), ball_column(hypot(p[0] - 28, p[1] - 15), p[2], -5, 5, 2));
}
static double flat_helix(const double p[3]) {
  return fmin(helix_min(p, 0), flat_column(hypot(p[0] - 28, p[1] - 15), p[2], -5, 5, 2));
}

/* Removed volume of the helix: the cutters are columns reaching above the
 * stock, so the removed set is {z >= lowest tip surface} over the disk each
 * instance covers: integrate -min(lower, 0) on a fine xy grid. */
static double helix_volume(int ball) {
  const double cell = 0.02, x0 = 8, y0 = 3;
  const int n = (int)(24 / cell);
  double *low = malloc(sizeof(double) * n * n), t[3], vol = 0;
  for (int i = 0; i < n * n; i++)
    low[i] = 0.0;
  /* Only the last two turns can hold the lowest surface (each turn lies
   * a pitch below the one before it): sampled as densely as a two-turn helix. */
  const int ns = 10000 * helix_turns;
  for (int s = ns - 20000; s <= ns; s++) {
    helix_at((double)s / ns, t);
    int i0 = (int)((t[0] - 2 - x0) / cell), j0 = (int)((t[1] - 2 - y0) / cell);
    for (int i = i0; i <= i0 + (int)(4 / cell) + 1; i++) {
      double dx = x0 + (i + 0.5) * cell - t[0];
      if (dx * dx > 4 || i < 0 || i >= n) continue;
      double h = sqrt(4 - dx * dx); /* the disk's half chord at this column */
      int ja = (int)((t[1] - h - y0) / cell) - 1, jb = (int)((t[1] + h - y0) / cell) + 1;
      for (int j = ja > j0 ? ja : j0; j <= jb && j <= j0 + (int)(4 / cell) + 1; j++) {
        double dy = y0 + (j + 0.5) * cell - t[1], d2 = dx * dx + dy * dy;
        if (d2 > 4 || j < 0 || j >= n) continue;
        double z = ball ? t[2] + 2 - sqrt(4 - d2) : t[2];
        if (z < low[i * n + j]) low[i * n + j] = z;
      }
    }
  }
  for (int i = 0; i < n * n; i++)
    vol += -low[i] * cell * cell;
  free(low);
  return vol;
}

/* Helices about a horizontal axis (G18: Y, G19: X), 12 turns of radius 8
 * about (20, 3) in XZ or (15, 3) in YZ from the start X28 Z3 or Y23 Z3, the
 * axis coordinate from 8 to 32. G2 turns clockwise seen from the axis'
 * positive end: in G18 from +X up to +Z, in G19 from +Y down to -Z. (The box
 * is symmetric about the circle's centre across the axis, so the volume does
 * not depend on the turning sense.) Tips reach z = -5; the columns (LEN)
 * reach above the stock's top. */
#define VTURNS 12
static void vhelix_at(int plane, double a, double t[3]) {
  double th = a * 2.0 * M_PI * VTURNS, u = 8 * cos(th), v = 8 * sin(th), ax = 8 + 24 * a;
  if (plane == 18)
    t[0] = 20 + u, t[1] = ax, t[2] = 3 + v;
  else
    t[0] = ax, t[1] = 15 + u, t[2] = 3 - v;
}

/* The lowest tip surface over an xy grid, as for helix_volume, of the ball
 * (vol[0]) and the flat (vol[1]): every instance whose tip is below the
 * stock's top, 0.02 mm apart along the path, on 0.025 mm cells (the flat's
 * value errs low by ~0.08 %, where a cell's first covering instance is
 * found up to a step late: 0.004 mm steps give 1631.5 and 1879.3 mm^3, the
 * ball's moves by 0.0003 %). */
static void vhelix_volumes(int plane, double vol[2]) {
  const double cell = 0.025;
  const int nx = (int)(40 / cell), ny = (int)(30 / cell), ns = (int)(VTURNS * 2 * M_PI * 8 / 0.02);
  double *low = malloc(sizeof(double) * 2 * nx * ny), t[3];
  for (int i = 0; i < 2 * nx * ny; i++)
    low[i] = 0.0;
  for (int s = 0; s <= ns; s++) {
    vhelix_at(plane, (double)s / ns, t);
    if (t[2] >= 0.0) continue;
    for (int i = (int)((t[0] - 2) / cell); i <= (int)((t[0] + 2) / cell); i++) {
      double dx = (i + 0.5) * cell - t[0], h = 4 - dx * dx;
      if (h < 0 || i < 0 || i >= nx) continue;
      h = sqrt(h);
      for (int j = (int)((t[1] - h) / cell); j <= (int)((t[1] + h) / cell); j++) {
        double dy = (j + 0.5) * cell - t[1], e = 4 - dx * dx - dy * dy;
        double *cl = &low[2 * (i * ny + j)];
        if (e < 0 || j < 0 || j >= ny) continue;
        cl[0] = fmin(cl[0], t[2] + 2 - sqrt(e)); /* ball */
        cl[1] = fmin(cl[1], t[2]);               /* flat */
      }
    }
  }
  vol[0] = vol[1] = 0.0;
  for (int i = 0; i < nx * ny; i++)
    vol[0] -= low[2 * i] * cell * cell, vol[1] -= low[2 * i + 1] * cell * cell;
  free(low);
}

/* Area of the circular segment of a disk of radius r cut at distance d from its centre. */
static double segment_area(double r, double d) {
  return r * r * acos(d / r) - d * sqrt(r * r - d * d);
}

/* ---- the comparison -------------------------------------------------------- */

typedef struct {
  const sim_case *c;
  double max_err, h;
  long compared, worst_count;
} visit_ctx;

static void visit(void *user, const double centre[3], float value) {
  visit_ctx *v = user;
  double ref = fmax(box_sdf(centre), -v->c->sweep_sdf(centre));
  if (fabs(ref) >= v->h) return;
  double err = fabs(ref - value);
  v->compared++;
  if (err > v->max_err) v->max_err = err;
  if (err > 0.1 * v->h) v->worst_count++;
}

static void run_case(const sim_case *c) {
  swarf_sim_config cfg;
  helix_turns = c->turns;
  swarf_sim_report rep;
  swarf_stock *stock = NULL;
  swarf_error err;
  swarf_sim_config_init(&cfg);
  memcpy(cfg.stock.lo, box_lo, sizeof box_lo);
  memcpy(cfg.stock.hi, box_hi, sizeof box_hi);
  cfg.voxel = VOXEL;
  cfg.half_width = 3;
  cfg.ntools = 1;
  if (swarf_sim_parse_tool(c->tool, &cfg.tools[0], &err) != 0) {
    CHECK(0, "%s: tool: %s", c->name, err.message);
    return;
  }
  int rc = swarf_sim_run_text(&cfg, c->name, c->gcode, strlen(c->gcode), &stock, &rep, &err);
  CHECK(rc == 0, "%s: simulation failed: %s", c->name, err.message);
  if (rc != 0) return;
  visit_ctx v = {c, 0.0, VOXEL, 0, 0};
  if (!c->volume_only) swarf_stock_visit_active(stock, visit, &v);
  double removed = rep.volume_before - rep.volume_after;
  printf("%-12s compared %6ld voxels, max |error| %.1e voxel, removed %.3f mm^3 vs %.3f "
         "analytic (%+.3f%%)\n",
         c->name, v.compared, v.max_err / VOXEL, removed, c->volume,
         100.0 * (removed - c->volume) / c->volume);
  CHECK(c->volume_only || v.compared > 1000, "%s: enough voxels near the surface (%ld)", c->name,
        v.compared);
  CHECK(v.max_err <= 0.1 * VOXEL, "%s: max error %.4f voxel (%ld over 0.1)", c->name,
        v.max_err / VOXEL, v.worst_count);
  CHECK(fabs(removed - c->volume) <= 0.005 * c->volume, "%s: removed %.3f vs %.3f", c->name,
        removed, c->volume);
  CHECK(swarf_stock_check(stock, &err) == SWARF_OK, "%s: level set valid: %s", c->name,
        err.message);
  swarf_stock_free(stock);
}

int main(void) {
  static const char slot[] = "G21 G90 G17\nG0 Z5\nG0 X5 Y15 Z5\nG1 Z-2 F200\nG1 X35 F600\nM30\n";
  static const char groove[] =
      "G21 G90\nG0 Z5\nG0 X30 Y15 Z5\nG1 Z-1.5 F200\nG2 X30 Y15 I-10 J0 F600\nM30\n";
  static const char helix[] =
      "G21 G90\nG0 Z5\nG0 X28 Y15 Z1\nG2 X28 Y15 Z-5 I-8 J0 P2 F600\nG0 Z5\nM30\n";
  static const char helix12[] =
      "G21 G90\nG0 Z5\nG0 X28 Y15 Z1\nG2 X28 Y15 Z-5 I-8 J0 P12 F600\nG0 Z5\nM30\n";
  static const char g18[] =
      "G21 G90\nG0 Z5\nG0 X28 Y8\nG0 Z3\nG18 G2 X28 Z3 Y32 I-8 K0 P12 F600\nG0 Z5\nM30\n";
  static const char g19[] =
      "G21 G90\nG0 Z5\nG0 X8 Y23\nG0 Z3\nG19 G2 Y23 Z3 X32 J-8 K0 P12 F600\nG0 Z5\nM30\n";
  double seg3 = segment_area(3, 1), cap3 = M_PI * 4 * (9 - 2) / 3; /* d = 1, h = 2 */
  sim_case cases[] = {
      {"ball-slot", slot, "T1=ball,D6,L16", ball_slot, 30 * seg3 + cap3, 2, 0},
      {"flat-slot", slot, "T1=flat,D6,L16", flat_slot, 2 * (30 * 6 + 9 * M_PI), 2, 0},
      {"ball-groove", groove, "T1=ball,D4,L16", ball_groove, 2 * M_PI * 10 * segment_area(2, 0.5),
       2, 0},
      {"flat-groove", groove, "T1=flat,D4,L16", flat_groove, M_PI * (144 - 64) * 1.5, 2, 0},
      {"ball-helix", helix, "T1=ball,D4,L16", ball_helix, 0, 2, 0},
      {"flat-helix", helix, "T1=flat,D4,L16", flat_helix, 0, 2, 0},
      {"ball-helix12", helix12, "T1=ball,D4,L16", ball_helix, 0, 12, 1},
      {"flat-helix12", helix12, "T1=flat,D4,L16", flat_helix, 0, 12, 1},
      {"ball-g18-12", g18, "T1=ball,D4,L16", NULL, 0, 2, 1},
      {"flat-g18-12", g18, "T1=flat,D4,L16", NULL, 0, 2, 1},
      {"ball-g19-12", g19, "T1=ball,D4,L16", NULL, 0, 2, 1},
      {"flat-g19-12", g19, "T1=flat,D4,L16", NULL, 0, 2, 1},
  };
  for (size_t i = 4; i < 8; i++) { /* the helices' quadratures */
    helix_turns = cases[i].turns;
    cases[i].volume = helix_volume(cases[i].sweep_sdf == ball_helix);
  }
  for (size_t i = 8; i < 12; i += 2) {
    double vol[2];
    vhelix_volumes(i < 10 ? 18 : 19, vol);
    cases[i].volume = vol[0], cases[i + 1].volume = vol[1];
  }
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    run_case(&cases[i]);
  return check_done();
}
