/* SPDX-License-Identifier: MPL-2.0 */
/* test_families.c -- every named cutter family end to end (G-code text ->
 * parser -> motions -> sweeps -> stock), against the exact signed distance
 * of the box minus the swept volume computed here, independently of the
 * engine.
 *
 * Each cutter cuts a straight groove (plunge, slot, retract) and a ramp
 * (plunge, line down in x and z, retract) in the box [0,40]x[0,20]x[-10,0]
 * at 0.2 mm. Reference:
 *  - convex cutters (vee, drill, spot, chamfer, taper flat and ball, APT,
 *    the paper's QSS 2,3,0,0): a body of revolution is the hull of rings
 *    (r, z, rho) written here from each family's drawing, support
 *    h_K(n) = max (r |n_xy| + z n_z + rho) (the QSS: its own support
 *    a(1-n_z^2) + b n_z^2 + e n_z + f, lifted to its lowest point); the
 *    body's signed distance is max over unit n of (p.n - h_K(n)), taken in
 *    its meridian plane (240 angles, golden polish); along a segment the
 *    swept volume is the Minkowski sum, whose distance outside is the least
 *    over the instances (convex in the time: 60 samples, golden polish);
 *  - unions of convex pieces (lollipop = ball + neck, dovetail = frustum +
 *    neck, T-slot = disk + neck): the minimum of the pieces' sweeps;
 *  - the non-convex QSS 2,-2,0,0 (Example 2's x^2+y^2-z^2 scaled by 2, a
 *    spool with dished ends): the minimum over instances along each segment
 *    (300 samples, golden polish) of the distance to its meridian profile,
 *    the curve (r(s), z(s)) derived here from its support function.
 * The grid's values at active voxels within a voxel of the surface near the
 * cuts (a deterministic sample) must match max(box, -sweep) in the material
 * (where the minimum over instances is exact) and be no shallower inside the
 * swept volume (where it is the deepest instance's depth, and the union's
 * true depth, the grid's, can be deeper: a dovetail's plunge is a cylinder
 * of its widest radius): p99 <= 0.1 voxel, max <= 0.5 voxel, no sign
 * differing where |reference| > 0.01 voxel.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include "swarf_sim.h"

#define VOXEL 0.2
#define MAXRING 6
#define MAXPIECE 2
#define SAMPLES 100

static const double box_lo[3] = {0, 0, -10}, box_hi[3] = {40, 20, 0};

typedef struct {
  int nring;
  double ring[MAXRING][3]; /* r, z, rho */
  int qss;                 /* 1: the support is the QSS's */
  double qa, qb, qe, qf, lift;
} piece;

typedef struct {
  const char *name, *tool;
  int npiece;
  piece p[MAXPIECE];
  int dense; /* non-convex QSS: dense instance reference */
} family;

#define RMAX 4.5 /* mm: every test cutter's widest radius is below it */

static double support(const piece *k, const double *n) {
  double s = sqrt(n[0] * n[0] + n[1] * n[1]), best = -1e300;
  if (k->qss) {
    double z = n[2];
    return k->qa * (1 - z * z) + k->qb * z * z + k->qe * z + k->qf + k->lift * z;
  }
  for (int i = 0; i < k->nring; i++) {
    double h = k->ring[i][0] * s + k->ring[i][1] * n[2] + k->ring[i][2];
    if (h > best) best = h;
  }
  return best;
}

/* The body's signed distance at q (cutter frame), in its meridian plane:
 * (rho, z) = (|q_xy|, q_z); for a convex body sdf = max over unit m of
 * (rho m_r + z m_z - h(m)), h its support (m_r >= 0 suffices, rho >= 0):
 * 720 angles, golden polish around the best. */
static double body_sdf(const piece *k, const double q[3]) {
  enum { N = 240 };
  double rho = hypot(q[0], q[1]), z = q[2], best = -1e300, ba = 0;
  /* the slack at the unit normal (s, c) = (sin t, cos t) of the meridian plane */
#define SLACK_SC(s, c) (rho * (s) + z * (c)-support(k, (double[3]){(s), 0, (c)}))
#define SLACK(t) SLACK_SC(sin(t), cos(t))
  static double st[N + 1], ct[N + 1]; /* sin and cos of the scan's angles, taken once */
  static int tabled;
  if (!tabled) {
    for (int i = 0; i <= N; i++)
      st[i] = sin(M_PI * i / N), ct[i] = cos(M_PI * i / N);
    tabled = 1;
  }
  for (int i = 0; i <= N; i++) {
    double v = SLACK_SC(st[i], ct[i]);
    if (v > best) best = v, ba = M_PI * i / N;
  }
  double lo = fmax(0, ba - M_PI / N), hi = fmin(M_PI, ba + M_PI / N);
  for (int it = 0; it < 40; it++) {
    double m1 = hi - 0.618 * (hi - lo), m2 = lo + 0.618 * (hi - lo), v1 = SLACK(m1), v2 = SLACK(m2);
    if (v1 > v2)
      hi = m2;
    else
      lo = m1;
    best = fmax(best, fmax(v1, v2));
  }
#undef SLACK
#undef SLACK_SC
  return best;
}

/* The swept volume of a convex body along [a, b]: the minimum over its
 * instances (the Minkowski sum: exact outside, the deepest instance inside),
 * 120 samples, golden polish around the best local minima. */
static double minkowski_sdf(const piece *k, const double p[3], const double a[3],
                            const double b[3]) {
  const int N = 60;
  double g[61], best = 1e300, q[3];
  for (int i = 0; i <= N; i++) {
    for (int c = 0; c < 3; c++)
      q[c] = p[c] - (a[c] + (b[c] - a[c]) * i / N);
    g[i] = body_sdf(k, q), best = fmin(best, g[i]);
  }
  for (int i = 0; i <= N; i++) {
    double prev = i > 0 ? g[i - 1] : 1e300, next = i < N ? g[i + 1] : 1e300;
    if (!(g[i] <= prev && g[i] <= next && g[i] < best + 0.2)) continue;
    double lo = fmax(0, (i - 1.0) / N), hi = fmin(1, (i + 1.0) / N);
    for (int it = 0; it < 40; it++) {
      double m[2] = {hi - 0.618 * (hi - lo), lo + 0.618 * (hi - lo)}, v[2];
      for (int j = 0; j < 2; j++) {
        for (int c = 0; c < 3; c++)
          q[c] = p[c] - (a[c] + (b[c] - a[c]) * m[j]);
        v[j] = body_sdf(k, q);
      }
      if (v[0] < v[1])
        hi = m[1];
      else
        lo = m[0];
      best = fmin(best, fmin(v[0], v[1]));
    }
  }
  return best;
}

/* ---- the non-convex QSS: its meridian profile ---- */
#define NPOLY 2000
static double poly[NPOLY + 1][2];
static double q_a, q_b, q_e, q_f, q_lift;

/* Surface point of h(n) = g(n_z) = a + f + e s + (b - a) s^2 on the meridian
 * n = (sqrt(1 - s^2), s): x = g n + g' (e_z - s n) (the gradient of h's
 * 1-homogeneous extension), lifted so that the lowest point is at z = 0. */
static void profile_at(double s, double *r, double *z) {
  double c = sqrt(fmax(0, 1 - s * s));
  double g = q_a + q_f + q_e * s + (q_b - q_a) * s * s, dg = q_e + 2 * (q_b - q_a) * s;
  *r = g * c - dg * s * c;
  *z = g * s + dg * (1 - s * s) + q_lift;
}

static void qss_profile(const family *f) {
  const piece *k = &f->p[0];
  double zmin = 1e300, r, z;
  q_a = k->qa, q_b = k->qb, q_e = k->qe, q_f = k->qf, q_lift = 0;
  for (int i = 0; i <= 100000; i++) {
    profile_at(-1 + 2.0 * i / 100000, &r, &z);
    zmin = fmin(zmin, z);
  }
  q_lift = -zmin;
  for (int i = 0; i <= NPOLY; i++)
    profile_at(-1 + 2.0 * i / NPOLY, &poly[i][0], &poly[i][1]);
}

static double curve_d2(double s, double r, double z) {
  double cr, cz;
  profile_at(s, &cr, &cz);
  return (r - cr) * (r - cr) + (z - cz) * (z - cz);
}

/* Signed distance from (r, z) (r >= 0) to the region between the profile
 * and the axis: the distance to the curve (samples, golden polish), the
 * sign by a ray towards +r across the polyline. */
static double profile_sdf(double r, double z) {
  const int N = 240;
  double best = 1e300, bs = 0;
  int cross = 0;
  for (int i = 0; i <= N; i++) {
    double s = -1 + 2.0 * i / N, d = curve_d2(s, r, z);
    if (d < best) best = d, bs = s;
  }
  double lo = fmax(-1, bs - 2.0 / N), hi = fmin(1, bs + 2.0 / N);
  for (int it = 0; it < 40; it++) {
    double m1 = hi - 0.618 * (hi - lo), m2 = lo + 0.618 * (hi - lo);
    double d1 = curve_d2(m1, r, z), d2 = curve_d2(m2, r, z);
    if (d1 < d2)
      hi = m2;
    else
      lo = m1;
    best = fmin(best, fmin(d1, d2));
  }
  for (int i = 0; i < NPOLY; i++) {
    double ax = poly[i][0], az = poly[i][1], bx = poly[i + 1][0], bz = poly[i + 1][1];
    if ((az > z) != (bz > z) && r < ax + (z - az) * (bx - ax) / (bz - az)) cross++;
  }
  return cross % 2 ? -sqrt(best) : sqrt(best);
}

static double instance_sdf(const double p[3], const double a[3], const double b[3], double u) {
  double t[3];
  for (int k = 0; k < 3; k++)
    t[k] = a[k] + u * (b[k] - a[k]);
  return profile_sdf(hypot(p[0] - t[0], p[1] - t[1]), p[2] - t[2]);
}

/* Minimum over the instances along [a, b]: 300 samples, golden polish
 * around each of the three best local minima. */
static double dense_segment(const double p[3], const double a[3], const double b[3]) {
  const int N = 300;
  static double g[301];
  double best = 1e300;
  for (int i = 0; i <= N; i++)
    g[i] = instance_sdf(p, a, b, (double)i / N), best = fmin(best, g[i]);
  for (int i = 0; i <= N; i++) {
    double prev = i > 0 ? g[i - 1] : 1e300, next = i < N ? g[i + 1] : 1e300;
    if (!(g[i] <= prev && g[i] <= next && g[i] < best + 0.3)) continue;
    double lo = fmax(0, (i - 1.0) / N), hi = fmin(1, (i + 1.0) / N);
    for (int it = 0; it < 40; it++) {
      double m1 = hi - 0.618 * (hi - lo), m2 = lo + 0.618 * (hi - lo);
      double d1 = instance_sdf(p, a, b, m1), d2 = instance_sdf(p, a, b, m2);
      if (d1 < d2)
        hi = m2;
      else
        lo = m1;
      best = fmin(best, fmin(d1, d2));
    }
  }
  return best;
}

/* ---- the comparison ---- */
typedef struct {
  const family *f;
  const double (*seg)[3];
  int nseg;
  long candidates, stride, seen, n, wrong;
  double err[SAMPLES + 8];
} visit_ctx;

static double box_sdf(const double p[3]) {
  double o = 0.0, m = -1e30;
  for (int k = 0; k < 3; k++) {
    double q = fmax(box_lo[k] - p[k], p[k] - box_hi[k]);
    o += fmax(q, 0.0) * fmax(q, 0.0);
    m = fmax(m, q);
  }
  return sqrt(o) + fmin(m, 0.0);
}

static double sweep_sdf(const visit_ctx *v, const double p[3]) {
  double best = 1e300;
  for (int s = 0; s + 1 < v->nseg; s++) {
    const double *a = v->seg[s], *b = v->seg[s + 1];
    if (v->f->dense)
      best = fmin(best, dense_segment(p, a, b));
    else
      for (int k = 0; k < v->f->npiece; k++)
        best = fmin(best, minkowski_sdf(&v->f->p[k], p, a, b));
  }
  return best;
}

/* Voxels near the surface whose horizontal distance to a segment is within
 * the cutter's widest radius and a voxel (the faces of the box far from the
 * cuts would only dilute the statistics). */
static int near_cut(const visit_ctx *v, const double c[3], float value) {
  if (!(fabs(value) < 1.5 * VOXEL)) return 0;
  for (int s = 0; s + 1 < v->nseg; s++) {
    const double *a = v->seg[s], *b = v->seg[s + 1];
    double dx = b[0] - a[0], dy = b[1] - a[1], l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((c[0] - a[0]) * dx + (c[1] - a[1]) * dy) / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    if (hypot(c[0] - a[0] - t * dx, c[1] - a[1] - t * dy) < RMAX + 2 * VOXEL) return 1;
  }
  return 0;
}

static void count_visit(void *user, const double c[3], float value) {
  visit_ctx *v = user;
  if (near_cut(v, c, value)) v->candidates++;
}

static void compare_visit(void *user, const double c[3], float value) {
  visit_ctx *v = user;
  if (!near_cut(v, c, value) || v->n >= SAMPLES) return;
  if (v->seen++ % v->stride) return;
  double ref = fmax(box_sdf(c), -sweep_sdf(v, c));
  if (!(fabs(ref) < VOXEL)) return;
  /* In the material (ref <= 0) the reference is exact; inside the swept
   * volume the minimum over instances is the deepest instance's depth, which
   * the union's true depth (the grid's closed forms) may exceed: there the
   * grid must not be shallower. */
  v->err[v->n++] = (ref <= 0 ? fabs(ref - value) : fmax(0.0, ref - value)) / VOXEL;
  if (getenv("FAMILIES_DEBUG") && fabs(ref - value) > 0.1 * VOXEL)
    printf("  at %.2f %.2f %.2f: grid %.4f reference %.4f\n", c[0], c[1], c[2], value, ref);
  if (fabs(ref) > 0.01 * VOXEL && (ref < 0) != (value < 0)) v->wrong++;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

static void run(const family *f, const char *what, const char *gcode, const double (*seg)[3],
                int nseg) {
  swarf_sim_config cfg;
  swarf_sim_report rep;
  swarf_stock *stock = NULL;
  swarf_error err;
  char name[128];
  snprintf(name, sizeof name, "%s-%s.ngc", f->name, what);
  swarf_sim_config_init(&cfg);
  memcpy(cfg.stock.lo, box_lo, sizeof box_lo);
  memcpy(cfg.stock.hi, box_hi, sizeof box_hi);
  cfg.voxel = VOXEL;
  cfg.half_width = 3;
  cfg.ntools = 1;
  if (swarf_sim_parse_tool(f->tool, &cfg.tools[0], &err) != SWARF_OK) {
    CHECK(0, "%s: tool %s: %s", name, f->tool, err.message);
    return;
  }
  int rc = swarf_sim_run_text(&cfg, name, gcode, strlen(gcode), &stock, &rep, &err);
  CHECK(rc == SWARF_OK, "%s: %s", name, err.message);
  if (rc != SWARF_OK) return;
  static visit_ctx v;
  memset(&v, 0, sizeof v);
  v.f = f, v.seg = seg, v.nseg = nseg;
  swarf_stock_visit_active(stock, count_visit, &v);
  v.stride = v.candidates / (2 * SAMPLES) + 1;
  swarf_stock_visit_active(stock, compare_visit, &v);
  qsort(v.err, (size_t)v.n, sizeof(double), cmp_double);
  double p99 = v.n ? v.err[(long)(0.99 * (v.n - 1))] : 0, mx = v.n ? v.err[v.n - 1] : 0;
  printf("%-30s %-6s %5ld voxels: p99 %.4f voxel, max %.4f voxel, wrong signs %ld\n", f->tool, what,
         v.n, p99, mx, v.wrong);
  CHECK(v.n >= 60, "%s: enough voxels near the surface (%ld)", name, v.n);
  CHECK(p99 <= 0.1, "%s: p99 %.4f voxel", name, p99);
  CHECK(mx <= 0.5, "%s: max %.4f voxel", name, mx);
  CHECK(v.wrong == 0, "%s: %ld wrong signs", name, v.wrong);
  swarf_stock_free(stock);
}

int main(int argc, char **argv) {
  const double d2r = M_PI / 180;
  /* taper: tip diameter 2, half-angle 10; with R1 the tip is a ball, the
   * flank tangent to it where its normal is (cos A, -sin A) */
  const double ta = 10 * d2r, L = 12;
  const double t0r = 1 - 1 + cos(ta), t0z = 1 - sin(ta);
  /* APT: E 2, R 1, alpha 10, beta 5, H 12 (F and D from the constraints) */
  const double E = 2, R = 1, al = 10 * d2r, be = 5 * d2r, F = (R + E * sin(al)) / cos(al);
  const double rh = E + R * cos(be) + (12 - (F - R * sin(be))) * tan(be);
  static char apt[160];
  snprintf(apt, sizeof apt, "T1=apt,D%.6f,R1,E2,F%.6f,A10,B5,H12", 2 * (E + R / cos(be)), F);
  const double v90 = 3 / tan(45 * d2r), d118 = 2.5 / tan(59 * d2r);
  family fam[] = {
      {"vee", "T1=vee,D6,A90,L12", 1, {{3, {{0, 0, 0}, {3, v90, 0}, {3, L, 0}}}}, 0},
      {"drill", "T1=drill,D5,L12", 1, {{3, {{0, 0, 0}, {2.5, d118, 0}, {2.5, L, 0}}}}, 0},
      {"spot", "T1=spot,D6,L12", 1, {{3, {{0, 0, 0}, {3, v90, 0}, {3, L, 0}}}}, 0},
      {"chamfer", "T1=chamfer,D8,A90,T2,L12", 1, {{3, {{1, 0, 0}, {4, 3, 0}, {4, L, 0}}}}, 0},
      {"taper", "T1=taper,D2,A10,L12", 1, {{2, {{1, 0, 0}, {1 + L * tan(ta), L, 0}}}}, 0},
      {"taperball",
       "T1=taper,D2,A10,R1,L12",
       1,
       {{2, {{0, 1, 1}, {t0r + (L - t0z) * tan(ta), L, 0}}}},
       0},
      {"apt", apt, 1, {{3, {{E, F, R}, {rh, 12, 0}, {0, 0, 0}}}}, 0},
      {"qss", "T1=qss,2,3,0,0", 1, {{0, {{0}}, 1, 2, 3, 0, 0, 3}}, 0},
      {"lollipop", "T1=lollipop,D4,K2,L12", 2, {{1, {{0, 2, 2}}}, {2, {{1, 2, 0}, {1, L, 0}}}}, 0},
      {"dovetail",
       "T1=dovetail,D6,A60,H2,K1.5,L12",
       2,
       {{2, {{3, 0, 0}, {3 - 2 / tan(60 * d2r), 2, 0}}}, {2, {{0.75, 2, 0}, {0.75, L, 0}}}},
       0},
      {"tslot",
       "T1=tslot,D8,H2,K3,L12",
       2,
       {{2, {{4, 0, 0}, {4, 2, 0}}}, {2, {{1.5, 2, 0}, {1.5, L, 0}}}},
       0},
      {"qss-spool", "T1=qss,2,-2,0,0", 1, {{0, {{0}}, 1, 2, -2, 0, 0, 0}}, 1},
  };
  /* Tools dip 1.5 (groove) and 1 to 2.5 (ramp) into the top; the tip starts
   * above the stock (the default start: X0 Y0, 10 mm above it). */
  static const char groove[] = "G21 G90\nG0 X5 Y10 Z5\nG1 Z-1.5 F200\nG1 X35 F600\nG0 Z5\nM2\n";
  static const char ramp[] = "G21 G90\nG0 X5 Y10 Z5\nG1 Z-1 F200\nG1 X35 Z-2.5 F600\nG0 Z5\nM2\n";
  static const double gseg[4][3] = {{5, 10, 5}, {5, 10, -1.5}, {35, 10, -1.5}, {35, 10, 5}};
  static const double rseg[4][3] = {{5, 10, 5}, {5, 10, -1}, {35, 10, -2.5}, {35, 10, 5}};
  const char *only = argc > 1 ? argv[1] : NULL;
  for (size_t i = 0; i < sizeof fam / sizeof fam[0]; i++) {
    if (only && strcmp(only, fam[i].name)) continue;
    if (fam[i].dense) qss_profile(&fam[i]);
    run(&fam[i], "groove", groove, gseg, 4);
    run(&fam[i], "ramp", ramp, rseg, 4);
  }
  return check_done();
}
