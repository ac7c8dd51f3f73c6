/* SPDX-License-Identifier: MPL-2.0 */
/* test_machine.c -- machine kinematics (machine.c, rigid.c) against values
 * computed here independently: the table rotation built from elementary
 * rotation matrices, the head machines' tip from the spherical coordinates
 * LinuxCNC's 5axiskins documents (tip = head pivot + L (sin B cos C,
 * sin B sin C, -cos B)), velocities and angular velocities by central finite
 * differences of the pose, the option parser's answers and errors. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "move_motion.h"

static const double deg = M_PI / 180.0;

static void rx(double a, double M[9]) {
  double c = cos(a), s = sin(a), R[9] = {1, 0, 0, 0, c, -s, 0, s, c};
  memcpy(M, R, sizeof R);
}
static void ry(double a, double M[9]) {
  double c = cos(a), s = sin(a), R[9] = {c, 0, s, 0, 1, 0, -s, 0, c};
  memcpy(M, R, sizeof R);
}
static void rz(double a, double M[9]) {
  double c = cos(a), s = sin(a), R[9] = {c, -s, 0, s, c, 0, 0, 0, 1};
  memcpy(M, R, sizeof R);
}
static void mul(const double A[9], const double B[9], double C[9]) {
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

static swarf_motion motion(const char *spec, const double s6[6], const double e6[6], int *rc) {
  swarf_machine mc;
  swarf_move mv;
  swarf_motion m;
  swarf_error err;
  memset(&mv, 0, sizeof mv);
  memset(&m, 0, sizeof m);
  mv.kind = SWARF_MOVE_LINE;
  mv.feed = 600;
  memcpy(mv.start, s6, sizeof mv.start);
  memcpy(mv.end, e6, sizeof mv.end);
  CHECK(swarf_machine_parse(&mc, spec, &err) == SWARF_OK, "%s: %s", spec, err.message);
  *rc = swarf_machine_motion(&mc, &mv, &m, NULL);
  return m;
}

/* Pose against R = Rot(e1) Rot(e2) built here; t for TCP and joint mode. */
static void check_pose(const char *spec, const swarf_motion *m, const double s6[6],
                       const double e6[6], int tilt_axis, const double pivot[3], int tcp) {
  for (int i = 0; i <= 4; i++) {
    double a = i / 4.0, q[6], A[9], C[9], R[9], t[3], U[9], P[3];
    for (int k = 0; k < 6; k++)
      q[k] = s6[k] + a * (e6[k] - s6[k]);
    if (tilt_axis == 0)
      rx(q[3] * deg, A);
    else
      ry(q[4] * deg, A);
    rz(q[5] * deg, C);
    mul(A, C, R);
    swarf_motion_eval(m, a, t, U);
    for (int k = 0; k < 9; k++)
      CHECK_NEAR(U[k], R[3 * (k % 3) + k / 3], 1e-12, "U = R^T");
    if (tcp) {
      for (int k = 0; k < 3; k++)
        CHECK_NEAR(t[k], q[k], 1e-12, "TCP: t is the programmed tip");
      continue;
    }
    for (int k = 0; k < 3; k++) /* machine point of the tip: pivot + R (t - pivot) = P */
      P[k] = pivot[k] + R[3 * k] * (t[0] - pivot[0]) + R[3 * k + 1] * (t[1] - pivot[1]) +
             R[3 * k + 2] * (t[2] - pivot[2]);
    for (int k = 0; k < 3; k++)
      CHECK_NEAR(P[k], q[k], 1e-12, "joint: tip at the joint position");
  }
  (void)spec;
}

/* tdot, v = U^T tdot and [omega]_x = U^T dU against central differences. */
static void check_velocity(const swarf_motion *m) {
  const double h = 1e-6;
  for (int i = 0; i <= 4; i++) {
    double a = 0.1 + 0.2 * i, tp[3], tm[3], Up[9], Um[9], t[3], U[9], td[3], v[3], w[3], dU[9];
    swarf_motion_eval(m, a + h, tp, Up);
    swarf_motion_eval(m, a - h, tm, Um);
    swarf_motion_eval(m, a, t, U);
    swarf_motion_velocity(m, a, td, v, w);
    for (int k = 0; k < 3; k++)
      CHECK_NEAR(td[k], (tp[k] - tm[k]) / (2 * h), 1e-6, "tdot");
    for (int k = 0; k < 3; k++)
      CHECK_NEAR(v[k], U[k] * td[0] + U[3 + k] * td[1] + U[6 + k] * td[2], 1e-12, "v = U^T tdot");
    for (int k = 0; k < 9; k++)
      dU[k] = (Up[k] - Um[k]) / (2 * h);
    double S[9]; /* U^T dU */
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++)
        S[3 * r + c] = U[r] * dU[c] + U[3 + r] * dU[3 + c] + U[6 + r] * dU[6 + c];
    CHECK_NEAR(S[7], w[0], 1e-6, "omega x");
    CHECK_NEAR(S[2], w[1], 1e-6, "omega y");
    CHECK_NEAR(S[3], w[2], 1e-6, "omega z");
    /* swarf_motion_pose: the same; its rates t' and the tool axis's derivative k' */
    swarf_pose P;
    swarf_pose_rates Pr;
    swarf_motion_pose(m, a, &P);
    swarf_pose_rates_of(&P, &Pr);
    for (int k = 0; k < 3; k++) {
      CHECK_NEAR(Pr.tdot[k], td[k], 1e-12, "pose rates: tdot");
      CHECK_NEAR(Pr.kdot[k], dU[3 * k + 2], 1e-6, "pose rates: kdot = d(U e_z)/da");
      CHECK_NEAR(P.v[k], v[k], 1e-12, "pose v");
      CHECK_NEAR(P.omega[k], w[k], 1e-12, "pose omega");
    }
  }
}

static void test_machines(void) {
  const double s6[6] = {1, 2, 3, 10, 20, -30}, e6[6] = {4, 0, 2, 40, 20, 60};
  const double b6[6] = {1, 2, 3, 0, 15, -30}, f6[6] = {4, 0, 2, 0, -25, 50};
  const double a6[6] = {-5, 1, 8, 0, 0, 0}, g6[6] = {5, 1, 8, 120, 0, 0};
  const double zero[3] = {0, 0, 0}, piv[3] = {0, 5, -20}, pa[3] = {0, 1, -1};
  double tmp[6];
  int rc;
  swarf_motion m = motion("xyzac-trt", s6, b6, &rc);
  CHECK(rc == SWARF_ERR_MACHINE, "xyzac-trt refuses a move that turns B");
  memcpy(tmp, s6, sizeof tmp);
  tmp[4] = 0;
  double e0[6];
  memcpy(e0, e6, sizeof e0);
  e0[4] = 0;
  m = motion("xyzac-trt", tmp, e0, &rc);
  CHECK(rc == 0 && m.kind == SWARF_MOTION_RIGID && m.tcp, "xyzac-trt TCP");
  check_pose("ac tcp", &m, tmp, e0, 0, zero, 1);
  check_velocity(&m);
  CHECK_NEAR(m.length, sqrt(9 + 4 + 1), 1e-12, "TCP length is the programmed length");
  CHECK_NEAR(m.turn, 120 * deg, 1e-12, "turn");
  m = motion("xyzac-trt,mode=joint,pivot=0,5,-20", tmp, e0, &rc);
  CHECK(rc == 0 && !m.tcp, "xyzac-trt joint");
  check_pose("ac joint", &m, tmp, e0, 0, piv, 0);
  check_velocity(&m);
  m = motion("xyzbc-trt", b6, f6, &rc);
  CHECK(rc == 0, "xyzbc-trt");
  check_pose("bc tcp", &m, b6, f6, 1, zero, 1);
  check_velocity(&m);
  m = motion("xyza,pivot=1,-1", a6, g6, &rc);
  CHECK(rc == 0 && m.kind == SWARF_MOTION_RIGID && !m.tcp, "xyza is joint kinematics");
  check_pose("xyza", &m, a6, g6, 0, pa, 0);
  check_velocity(&m);
  m = motion("xyza", a6, a6, &rc);
  CHECK(rc == 0 && m.kind == SWARF_MOTION_LINE, "A = 0 throughout: a plain 3-axis line");
  m = motion("xyz", a6, g6, &rc);
  CHECK(rc == SWARF_ERR_MACHINE, "xyz refuses A");
}

/* Expected pose of a new machine at the axis values q (degrees for A B C):
 * U (row-major) and the tip t in the workpiece frame. */
typedef void (*expect_fn)(const double q[6], int tcp, const double pivot[3], double head,
                          double U[9], double t[3]);

static void expect_tdr(const double q[6], int tcp, const double pv[3], double head, double U[9],
                       double t[3]) {
  double A[9], B[9], R[9], d[3];
  rx(q[3] * deg, A), ry(q[4] * deg, B), mul(A, B, U); /* U = Rx(A) Ry(B) */
  (void)head;
  if (tcp) {
    memcpy(t, q, 3 * sizeof *t);
    return;
  }
  /* the machine point q of the tip is pivot + Ry(-B) Rx(-A) (t - pivot) */
  rx(-q[3] * deg, A), ry(-q[4] * deg, B), mul(B, A, R);
  for (int k = 0; k < 3; k++)
    d[k] = q[k] - pv[k];
  for (int k = 0; k < 3; k++) /* R^T d */
    t[k] = pv[k] + R[k] * d[0] + R[3 + k] * d[1] + R[6 + k] * d[2];
}

/* The head's pivot is `head` above the joint position; the tip sits at
 * pivot + head (sin B cos C, sin B sin C, -cos B) (5axiskins' s2r with the
 * polar angle 180 - B). */
static void head_tip(const double q[6], double head, double c_in_head, double m[3]) {
  double b = q[4] * deg, c = c_in_head * deg;
  m[0] = q[0] + head * sin(b) * cos(c);
  m[1] = q[1] + head * sin(b) * sin(c);
  m[2] = q[2] + head - head * cos(b);
}

static void expect_hh(const double q[6], int tcp, const double pv[3], double head, double U[9],
                      double t[3]) {
  double B[9], C[9];
  rz(q[5] * deg, C), ry(-q[4] * deg, B), mul(C, B, U); /* U = Rz(C) Ry(-B) */
  (void)pv;
  if (tcp)
    memcpy(t, q, 3 * sizeof *t);
  else
    head_tip(q, head, q[5], t);
}

static void expect_ht(const double q[6], int tcp, const double pv[3], double head, double U[9],
                      double t[3]) {
  double B[9], C[9], m[3], d[3];
  rz(q[5] * deg, C), ry(-q[4] * deg, B), mul(C, B, U); /* U = Rz(C) Ry(-B) */
  if (tcp) {
    memcpy(t, q, 3 * sizeof *t);
    return;
  }
  head_tip(q, head, 0.0, m); /* B tilts in the machine's XZ plane */
  for (int k = 0; k < 3; k++)
    d[k] = m[k] - pv[k];
  /* the table turns the workpiece by -C: w = pivot + Rz(C) (m - pivot) */
  for (int k = 0; k < 3; k++)
    t[k] = pv[k] + C[3 * k] * d[0] + C[3 * k + 1] * d[1] + C[3 * k + 2] * d[2];
}

static void check_expected(const char *spec, const swarf_motion *m, const double s6[6],
                           const double e6[6], expect_fn f, int tcp, const double pivot[3],
                           double head) {
  for (int i = 0; i <= 4; i++) {
    double a = i / 4.0, q[6], Ue[9], te[3], t[3], U[9];
    for (int k = 0; k < 6; k++)
      q[k] = s6[k] + a * (e6[k] - s6[k]);
    f(q, tcp, pivot, head, Ue, te);
    swarf_motion_eval(m, a, t, U);
    for (int k = 0; k < 9; k++)
      CHECK(fabs(U[k] - Ue[k]) < 1e-12, "%s: U[%d] at %g: %g vs %g", spec, k, a, U[k], Ue[k]);
    for (int k = 0; k < 3; k++)
      CHECK(fabs(t[k] - te[k]) < 1e-9, "%s: t[%d] at %g: %g vs %g", spec, k, a, t[k], te[k]);
  }
}

/* Spot values that need no matrix: directions as LinuxCNC turns them. */
static void test_directions(void) {
  const double z6[6] = {0, 0, 10, 0, 0, 0}, a6[6] = {0, 0, 10, 90, 0, 0};
  const double b6[6] = {0, 0, 10, 0, 90, 0}, bc6[6] = {0, 0, 10, 0, 90, 90};
  double t[3], U[9];
  int rc;
  /* xyzab-tdr, joint, pivot 0: A = 90 turns the workpiece by -90 about X, so
   * the tip held at machine (0,0,10) is at workpiece (0,-10,0) */
  swarf_motion m = motion("xyzab-tdr,mode=joint", z6, a6, &rc);
  swarf_motion_eval(&m, 1.0, t, U);
  CHECK(rc == 0 && fabs(t[0]) < 1e-12 && fabs(t[1] + 10) < 1e-12 && fabs(t[2]) < 1e-12,
        "tdr A: (%g %g %g)", t[0], t[1], t[2]);
  /* B = 90 turns it by -90 about Y: machine (0,0,10) is workpiece (10,0,0) */
  m = motion("xyzab-tdr,mode=joint", z6, b6, &rc);
  swarf_motion_eval(&m, 1.0, t, U);
  CHECK(rc == 0 && fabs(t[0] - 10) < 1e-12 && fabs(t[2]) < 1e-12, "tdr B: (%g %g %g)", t[0], t[1],
        t[2]);
  /* tool axis relative to the workpiece: U e_z = (sin B, 0, cos B) at A = 0 */
  CHECK_NEAR(U[2], 1.0, 1e-12, "tdr B tool axis x");
  /* xyzbc-hh: B = 90 tilts the tool axis to -X, C = 90 then turns it to -Y */
  m = motion("xyzbc-hh", z6, b6, &rc);
  swarf_motion_eval(&m, 1.0, t, U);
  CHECK(rc == 0 && fabs(U[2] + 1) < 1e-12 && fabs(t[2] - 10) < 1e-12, "hh B: axis x %g", U[2]);
  m = motion("xyzbc-hh", b6, bc6, &rc);
  swarf_motion_eval(&m, 1.0, t, U);
  CHECK(rc == 0 && fabs(U[5] + 1) < 1e-12, "hh C: axis y %g", U[5]);
  /* joint mode, head 100: at B = 90 the tip is 100 along +X and 100 up */
  m = motion("xyzbc-hh,mode=joint,head=100", z6, b6, &rc);
  swarf_motion_eval(&m, 1.0, t, U);
  CHECK(rc == 0 && fabs(t[0] - 100) < 1e-9 && fabs(t[2] - 110) < 1e-9, "hh joint: (%g %g %g)", t[0],
        t[1], t[2]);
  /* xyzbc-ht: C = 90 turns the workpiece by -90 about Z through (5, 0):
   * machine (0,0,10) is workpiece (5,-5,10) */
  m = motion("xyzbc-ht,mode=joint,head=100,pivot=5,0", z6, (double[6]){0, 0, 10, 0, 0, 90}, &rc);
  swarf_motion_eval(&m, 1.0, t, U);
  CHECK(rc == 0 && fabs(t[0] - 5) < 1e-9 && fabs(t[1] + 5) < 1e-9 && fabs(t[2] - 10) < 1e-9,
        "ht C: (%g %g %g)", t[0], t[1], t[2]);
}

static void test_new_machines(void) {
  const double s6[6] = {1, 2, 3, 10, 20, -30}, e6[6] = {4, 0, 2, 40, -25, 60};
  const double ab0[6] = {1, 2, 3, 10, 20, 0}, ab1[6] = {4, 0, 2, 75, -25, 0};
  const double bc0[6] = {1, 2, 3, 0, 20, -30}, bc1[6] = {4, 0, 2, 0, -25, 60};
  const double zero[3] = {0, 0, 0}, piv[3] = {3, -5, -20}, pxy[3] = {3, -5, 0};
  int rc;
  swarf_motion m = motion("xyzab-tdr", s6, e6, &rc);
  CHECK(rc == SWARF_ERR_MACHINE, "xyzab-tdr refuses C");
  m = motion("xyzbc-hh", s6, e6, &rc);
  CHECK(rc == SWARF_ERR_MACHINE, "xyzbc-hh refuses A");
  m = motion("xyzbc-ht", s6, e6, &rc);
  CHECK(rc == SWARF_ERR_MACHINE, "xyzbc-ht refuses A");
  const struct {
    const char *spec;
    int ab; /* 1: A B moves, 0: B C moves */
    expect_fn f;
    int tcp;
    const double *pivot;
    double head;
  } cases[] = {{"xyzab-tdr", 1, expect_tdr, 1, zero, 0},
               {"xyzab-tdr,mode=joint,pivot=3,-5,-20", 1, expect_tdr, 0, piv, 0},
               {"xyzbc-hh", 0, expect_hh, 1, zero, 0},
               {"xyzbc-hh,mode=joint,head=120", 0, expect_hh, 0, zero, 120},
               {"xyzbc-hh,head=-7.5,mode=joint", 0, expect_hh, 0, zero, -7.5},
               {"xyzbc-ht,pivot=3,-5", 0, expect_ht, 1, pxy, 0},
               {"xyzbc-ht,mode=joint,pivot=3,-5,head=80", 0, expect_ht, 0, pxy, 80}};
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    const double *a = cases[i].ab ? ab0 : bc0, *b = cases[i].ab ? ab1 : bc1;
    m = motion(cases[i].spec, a, b, &rc);
    CHECK(rc == 0 && m.kind == SWARF_MOTION_RIGID && m.tcp == cases[i].tcp, "%s", cases[i].spec);
    check_expected(cases[i].spec, &m, a, b, cases[i].f, cases[i].tcp, cases[i].pivot,
                   cases[i].head);
    check_velocity(&m);
    if (cases[i].tcp)
      CHECK(fabs(m.length - sqrt(9 + 4 + 1)) < 1e-12, "%s: TCP length", cases[i].spec);
  }
  /* an arc at a fixed tilt in joint mode on the head: velocity still consistent */
  {
    swarf_machine mc;
    swarf_move mv;
    memset(&mv, 0, sizeof mv);
    mv.kind = SWARF_MOVE_ARC;
    mv.feed = 100;
    const double st[6] = {5, 0, 0, 0, 30, 40}, en[6] = {0, 5, 0, 0, 30, 40};
    memcpy(mv.start, st, sizeof st);
    memcpy(mv.end, en, sizeof en);
    mv.normal[2] = 1;
    mv.angle = M_PI / 2;
    CHECK(swarf_machine_parse(&mc, "xyzbc-hh,mode=joint,head=50", NULL) == SWARF_OK, "hh parse");
    CHECK(swarf_machine_motion(&mc, &mv, &m, NULL) == SWARF_OK && m.kind == SWARF_MOTION_RIGID &&
              m.helix,
          "hh arc at a tilt");
    check_velocity(&m);
  }
}

static void test_parse_errors(void) {
  static const char *bad[] = {"xyzq",
                              "xyza,pivot=1",
                              "xyza,pivot=1,2,3",
                              "xyzac-trt,mode=tpc",
                              "xyz,pivot=1,2",
                              "xyza,mode=tcp",
                              "xyzac-trt,pivot=1,nan,2",
                              "",
                              "xyzab-tdr,pivot=1,2",
                              "xyzab-tdr,head=5",
                              "xyzbc-hh,pivot=1,2,3",
                              "xyzbc-hh,mode=joint",
                              "xyzbc-hh,head=",
                              "xyzbc-hh,head=1,2",
                              "xyzbc-ht,pivot=1,2,3",
                              "xyzbc-ht,mode=joint,pivot=1,2",
                              "xyzac-trt,head=3",
                              "xyzbc-hh,head=inf,mode=joint"};
  swarf_machine m;
  swarf_error err;
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    swarf_error_init(&err);
    CHECK(swarf_machine_parse(&m, bad[i], &err) == SWARF_ERR_ARG && err.status == SWARF_ERR_ARG,
          "\"%s\" refused", bad[i]);
    CHECK(strstr(err.message, "--machine") != NULL && strcmp(err.word, "--machine") == 0,
          "message names the flag: %s (%s)", err.message, err.word);
  }
  CHECK(swarf_machine_parse(&m, "xyzbc-trt,mode=joint,pivot=1,2,3", &err) == SWARF_OK &&
            m.kind == SWARF_MACHINE_XYZBC_TRT && !m.tcp && m.pivot[2] == 3,
        "full spec: %s", err.message);
  CHECK(swarf_machine_parse(&m, "xyzbc-ht,mode=joint,pivot=1,2,head=150", &err) == SWARF_OK &&
            m.kind == SWARF_MACHINE_XYZBC_HT && !m.tcp && m.pivot[0] == 1 && m.pivot[1] == 2 &&
            m.pivot[2] == 0 && m.head == 150,
        "ht spec: %s", err.message);
  CHECK(swarf_machine_parse(&m, "xyzab-tdr", &err) == SWARF_OK && m.tcp &&
            m.kind == SWARF_MACHINE_XYZAB_TDR,
        "tdr default TCP");
  CHECK(swarf_machine_parse(&m, "xyzbc-hh", &err) == SWARF_OK && m.tcp && m.head == 0,
        "hh default TCP");
}

int main(void) {
  test_machines();
  test_new_machines();
  test_directions();
  test_parse_errors();
  return check_done();
}
