/* SPDX-License-Identifier: MPL-2.0 */
/* test_machines.c -- the 5-axis machines xyzab-tdr, xyzbc-hh and xyzbc-ht end
 * to end (G-code text -> parser -> machine kinematics -> rigid sweeps ->
 * OpenVDB stock) against an analytic shape: in joint mode, a ball held still
 * at distance r from a rotary axis while that axis turns 90 degrees sweeps a
 * torus section with spherical ends (the points within rho of a quarter
 * circle). The stock is chosen so that the shank's sweep never reaches into
 * it (the shank points away from the axis, or up out of a half-space), so
 * the remaining stock's distance is exactly max(stock, rho - dist(arc)):
 *   - a cylinder of radius r about the axis: the inner half of the tube,
 *     volume (pi/2) (r pi rho^2/2 - 2 rho^3/3) (Pappus) plus two end caps
 *     (integrated here: disc segments, Simpson's rule);
 *   - the half-space below the ball centres (the table C axis of xyzbc-ht,
 *     whose tool stays parallel to it): (pi/2) r pi rho^2/2 + 2 pi rho^3/3.
 * The arc's ends come from the LinuxCNC conventions written here with
 * elementary rotations (toolpath.h), not from swarf. Compared: every active
 * voxel inside the initial stock, within 1 mm of the cut and within one
 * voxel of the analytic surface (error in voxels), and the removed volume. Head machines use a
 * negative head length (the head's pivot below the tip) so that the shank points away from the
 * axis; the kinematics are the same formula either way (tests/toolpath/test_machine.c checks both
 * signs).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "swarf_sim.h"

#define VOXEL 0.1
#define R_ARC 4.0 /* distance of the ball's centre from the axis, mm */
#define RHO 1.0   /* ball radius (T1=ball,D2) */

static const double deg = M_PI / 180.0;

typedef struct {
  double c0[3], axis[3]; /* a point of the rotary axis and its direction */
  double u0[3], u1[3];   /* unit directions of the arc's ends from the axis (90 degrees) */
  int halfspace;         /* stock: 0 cylinder of radius R_ARC about the axis, 1 z < 0 */
} arc;

static double dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Distance from p to the quarter circle of radius R_ARC about the axis. */
static double arc_dist(const arc *A, const double p[3]) {
  double d[3], h, q[3], a, b, e0 = 0, e1 = 0;
  for (int k = 0; k < 3; k++)
    d[k] = p[k] - A->c0[k];
  h = dot(d, A->axis);
  for (int k = 0; k < 3; k++)
    q[k] = d[k] - h * A->axis[k];
  a = dot(q, A->u0), b = dot(q, A->u1);
  if (a >= 0 && b >= 0) return hypot(sqrt(dot(q, q)) - R_ARC, h);
  for (int k = 0; k < 3; k++) {
    e0 += (d[k] - R_ARC * A->u0[k]) * (d[k] - R_ARC * A->u0[k]);
    e1 += (d[k] - R_ARC * A->u1[k]) * (d[k] - R_ARC * A->u1[k]);
  }
  return sqrt(fmin(e0, e1));
}

static double stock_sdf(const arc *A, const double p[3]) {
  double d[3], h, q[3];
  if (A->halfspace) return p[2];
  for (int k = 0; k < 3; k++)
    d[k] = p[k] - A->c0[k];
  h = dot(d, A->axis);
  for (int k = 0; k < 3; k++)
    q[k] = d[k] - h * A->axis[k];
  return sqrt(dot(q, q)) - R_ARC;
}

/* Area of the part y < Y of a disc of radius s about the origin. */
static double disc_below(double s, double Y) {
  if (Y >= s) return M_PI * s * s;
  if (Y <= -s) return 0.0;
  return M_PI * s * s - s * s * acos(Y / s) + Y * sqrt(s * s - Y * Y);
}

/* The removed volume, mm^3. */
static double analytic_volume(int halfspace) {
  const double r = R_ARC, p = RHO;
  const int n = 2000;
  double cap = 0.0;
  if (halfspace) return 0.5 * M_PI * r * M_PI * p * p / 2 + 2.0 * M_PI * p * p * p / 3.0;
  /* an end cap: x beyond the end plane, the disc of radius sqrt(p^2 - x^2)
   * across the tangent, below Y(x) = sqrt(r^2 - x^2) - r (inside radius r) */
  for (int i = 0; i <= n; i++) {
    double x = p * i / n, w = i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0);
    cap += w * disc_below(sqrt(fmax(0.0, p * p - x * x)), sqrt(r * r - x * x) - r);
  }
  cap *= p / (3.0 * n);
  return 0.5 * M_PI * (r * M_PI * p * p / 2 - 2.0 * p * p * p / 3.0) + 2.0 * cap;
}

typedef struct {
  const arc *A;
  double max_err;
  long n;
} cmp;

static void visit(void *ctx, const double c[3], float value) {
  cmp *k = ctx;
  double s = stock_sdf(k->A, c), d = arc_dist(k->A, c), ref = fmax(s, RHO - d);
  /* outside the initial stock: the shank's; far from the cut: the stock's other faces */
  if (s > 0 || fabs(ref) > VOXEL || d > RHO + 1.0) return;
  k->max_err = fmax(k->max_err, fabs(value - ref) / VOXEL);
  k->n++;
}

static void run_case(const char *name, const char *machine, const char *stock, const char *gcode,
                     const arc *A) {
  swarf_sim_config cfg;
  swarf_sim_report rep;
  swarf_stock *out = NULL;
  swarf_error err;
  swarf_sim_config_init(&cfg);
  cfg.voxel = VOXEL;
  cfg.half_width = 3;
  CHECK(swarf_machine_parse(&cfg.machine, machine, &err) == SWARF_OK, "%s", err.message);
  CHECK(swarf_sim_parse_stock(stock, &cfg.stock, &err) == 0, "%s", err.message);
  CHECK(swarf_sim_parse_tool("T1=ball,D2,L6", &cfg.tools[0], &err) == 0, "%s", err.message);
  cfg.ntools = 1;
  int rc = swarf_sim_run_text(&cfg, name, gcode, strlen(gcode), &out, &rep, &err);
  CHECK(rc == 0, "%s: run: %s", name, err.message);
  if (rc != 0) return;
  cmp c = {A, 0, 0};
  swarf_stock_visit_active(out, visit, &c);
  double removed = rep.volume_before - rep.volume_after, want = analytic_volume(A->halfspace);
  printf("%-28s removed %.4f mm^3 vs analytic %.4f (%+.3f%%); distance max %.2e voxel over %ld "
         "voxels\n",
         name, removed, want, 100 * (removed - want) / want, c.max_err, c.n);
  CHECK(c.n > 1000, "%s: compared %ld voxels", name, c.n);
  CHECK(c.max_err < 0.01, "%s: distance error %g voxel", name, c.max_err);
  CHECK(fabs(removed - want) < 0.005 * want, "%s: removed %g vs %g", name, removed, want);
  swarf_stock_free(out);
}

/* v = rotation by th (radians, right-hand) about the unit axis n, of v. */
static void rotate(const double n[3], double th, const double v[3], double out[3]) {
  double c = cos(th), s = sin(th), d = dot(n, v), x[3];
  x[0] = n[1] * v[2] - n[2] * v[1];
  x[1] = n[2] * v[0] - n[0] * v[2];
  x[2] = n[0] * v[1] - n[1] * v[0];
  for (int k = 0; k < 3; k++)
    out[k] = v[k] * c + x[k] * s + n[k] * d * (1 - c);
}

static void set3(double v[3], double x, double y, double z) {
  v[0] = x, v[1] = y, v[2] = z;
}

int main(void) {
  const double X[3] = {1, 0, 0}, Y[3] = {0, 1, 0}, Z[3] = {0, 0, 1}, up[3] = {0, 0, 1};
  arc A;
  memset(&A, 0, sizeof A);
  /* xyzab-tdr, A: the table turns the workpiece by -A about X, so the ball
   * held at machine (0,0,4) goes to Rx(+A) (0,0,4) in the workpiece. */
  memcpy(A.axis, X, sizeof X);
  memcpy(A.u0, up, sizeof up);
  rotate(X, 90 * deg, up, A.u1);
  run_case("xyzab-tdr A (joint)", "xyzab-tdr,mode=joint", "cylinder:x,4,-6,6",
           "G0 X0 Y0 Z3\nG1 A90 F100\nM2\n", &A);
  /* B: -B about Y for the workpiece, Ry(+B) (0,0,4) */
  memcpy(A.axis, Y, sizeof Y);
  rotate(Y, 90 * deg, up, A.u1);
  run_case("xyzab-tdr B (joint)", "xyzab-tdr,mode=joint", "cylinder:y,4,-6,6",
           "G0 X0 Y0 Z3\nG1 B90 F100\nM2\n", &A);
  /* xyzbc-hh, B with head=-3 (pivot 3 below the tip, at the origin): the
   * ball's centre is at pivot + 4 (-sin B cos C, -sin B sin C, cos B), the
   * tool axis direction (5axiskins) */
  set3(A.u1, -1, 0, 0);
  run_case("xyzbc-hh B (joint)", "xyzbc-hh,mode=joint,head=-3", "cylinder:y,4,-6,6",
           "G0 X0 Y0 Z3\nG1 B90 F100\nM2\n", &A);
  /* C at B = 90: the centre goes round Z from (-4,0,0) to (0,-4,0); the ball
   * comes in radially from X-20 so that the approach cuts only its end cap */
  memcpy(A.axis, Z, sizeof Z);
  set3(A.u0, -1, 0, 0);
  set3(A.u1, 0, -1, 0);
  run_case("xyzbc-hh C (joint)", "xyzbc-hh,mode=joint,head=-3", "cylinder:z,4,-6,6",
           "G0 X-20 Y0 Z30\nG0 B90\nG0 Z3\nG0 X0\nG1 C90 F100\nM2\n", &A);
  /* xyzbc-ht, B in the head: as xyzbc-hh's */
  memcpy(A.axis, Y, sizeof Y);
  memcpy(A.u0, up, sizeof up);
  set3(A.u1, -1, 0, 0);
  run_case("xyzbc-ht B (joint)", "xyzbc-ht,mode=joint,head=-3", "cylinder:y,4,-6,6",
           "G0 X0 Y0 Z3\nG1 B90 F100\nM2\n", &A);
  /* C in the table (through pivot 0,0): the workpiece turns by -C, so the ball
   * held at machine (4,0,0) goes to Rz(+C) (4,0,0); stock z < 0 */
  memcpy(A.axis, Z, sizeof Z);
  set3(A.u0, 1, 0, 0);
  rotate(Z, 90 * deg, A.u0, A.u1);
  A.halfspace = 1;
  run_case("xyzbc-ht C (joint)", "xyzbc-ht,mode=joint,head=50", "box:-8,-8,-4,8,8,0",
           "G0 X4 Y0\nG0 Z-1\nG1 C90 F100\nM2\n", &A);
  return check_done();
}
