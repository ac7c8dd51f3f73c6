/* test_machine.c -- machine kinematics (machine.c, rigid.c) against values
 * computed here independently: the table rotation built from elementary
 * rotation matrices, velocities and angular velocities by central finite
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

static void test_parse_errors(void) {
  static const char *bad[] = {
      "xyzq",          "xyza,pivot=1",  "xyza,pivot=1,2,3",        "xyzac-trt,mode=tpc",
      "xyz,pivot=1,2", "xyza,mode=tcp", "xyzac-trt,pivot=1,nan,2", ""};
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
}

int main(void) {
  test_machines();
  test_parse_errors();
  return check_done();
}
