/* SPDX-License-Identifier: MPL-2.0 */
/* rigid.c -- rigid motions with rotation (RIGID kind, toolpath.h): pose,
 * velocities and tip bounds for machines with rotary axes.
 *
 * R(a) = Rot(e1, th1(a)) Rot(e2, th2(a)) = H T (head factors first, then
 * table factors), U = R^T and, with d = th1 - th0,
 *   U^T dU/da = [omega]_x,  omega = -(d1 e1 + d2 Rot(e1, th1) e2)
 * (in the cutter frame). The tip: t = P in TCP mode; in joint mode
 * t = pivot + T^T (P - pivot + h - H^T h), h the head's pivot above the tip
 * (table machines: H = I, T = R). Values only.
 */
#include <math.h>
#include <string.h>

#include "toolpath_private.h"

/* sin and cos of th0 + x: for |x| <= 1/16 from those of th0 (kept per thread
 * for the last two th0 asked: a motion's axes) and the Taylor series of x
 * (to x^9 / 9!: the rest below 3e-19), else sin and cos. Poses at arbitrary times
 * (the rigid sweep's refinement) spend most of their time here otherwise. */
static _Thread_local struct {
  double th0[2], s0[2], c0[2];
  int next;
} sc_base = {{NAN, NAN}, {0, 0}, {0, 0}, 0};

static void sin_cos_sum(double th0, double x, double *s, double *c) {
  double x2 = x * x, x4, sx, cx, s0, c0;
  int k;
  if (!(fabs(x) <= 0.0625)) {
    *s = sin(th0 + x), *c = cos(th0 + x);
    return;
  }
  for (k = 0; k < 2 && sc_base.th0[k] != th0; k++)
    ;
  if (k == 2) {
    k = sc_base.next, sc_base.next ^= 1;
    sc_base.th0[k] = th0, sc_base.s0[k] = sin(th0), sc_base.c0[k] = cos(th0);
  }
  s0 = sc_base.s0[k], c0 = sc_base.c0[k];
  x4 = x2 * x2;
  sx = x * ((1.0 - x2 * (1.0 / 6)) + x4 * ((1.0 / 120 - x2 * (1.0 / 5040)) + x4 * (1.0 / 362880)));
  cx = (1.0 - 0.5 * x2) + x4 * ((1.0 / 24 - x2 * (1.0 / 720)) + x4 * (1.0 / 40320));
  *s = s0 * cx + c0 * sx;
  *c = c0 * cx - s0 * sx;
}

/* Rotation matrix (row-major) with cosine c and sine s about the unit axis n
 * (right-hand rule). */
static void rot_matrix_cs(const double n[3], double c, double s, double M[9]) {
  double k = 1.0 - c;
  M[0] = c + n[0] * n[0] * k;
  M[1] = n[0] * n[1] * k - n[2] * s;
  M[2] = n[0] * n[2] * k + n[1] * s;
  M[3] = n[1] * n[0] * k + n[2] * s;
  M[4] = c + n[1] * n[1] * k;
  M[5] = n[1] * n[2] * k - n[0] * s;
  M[6] = n[2] * n[0] * k - n[1] * s;
  M[7] = n[2] * n[1] * k + n[0] * s;
  M[8] = c + n[2] * n[2] * k;
}

/* Rotation matrix (row-major) by th0 + x about the unit axis n. */
static void rot_matrix_sum(const double n[3], double th0, double x, double M[9]) {
  double c, s;
  sin_cos_sum(th0, x, &s, &c);
  rot_matrix_cs(n, c, s, M);
}

/* Rotation matrix (row-major) by th about the unit axis n. */
static void rot_matrix(const double n[3], double th, double M[9]) {
  rot_matrix_cs(n, cos(th), sin(th), M);
}

static void mat_mul(const double A[9], const double B[9], double C[9]) {
  double r[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      r[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
  memcpy(C, r, sizeof r);
}

/* R(alpha) (workpiece -> machine), row-major; R1 = Rot(e1, th1) if not NULL. */
static void table_rotation(const swarf_motion *m, double alpha, double R[9], double R1[9]) {
  double A[9], B[9];
  rot_matrix_sum(m->e1, m->th0[0], alpha * (m->th1[0] - m->th0[0]), A);
  if (m->e2[0] == 0.0 && m->e2[1] == 0.0 && m->e2[2] == 0.0)
    memcpy(R, A, sizeof A);
  else {
    rot_matrix_sum(m->e2, m->th0[1], alpha * (m->th1[1] - m->th0[1]), B);
    mat_mul(A, B, R);
  }
  if (R1 != NULL) memcpy(R1, A, sizeof A);
}

/* Tip in the machine frame at alpha (joint mode) minus the pivot, and dP/da. */
static void machine_arm(const swarf_motion *m, double alpha, double d[3], double dP[3]) {
  swarf_path_point(m, alpha, d, dP);
  for (int k = 0; k < 3; k++)
    d[k] -= m->pivot[k];
}

/* y = A x and y = A^T x (3x3 row-major). */
static void mat_vec(const double A[9], const double x[3], double y[3]) {
  for (int i = 0; i < 3; i++)
    y[i] = A[3 * i] * x[0] + A[3 * i + 1] * x[1] + A[3 * i + 2] * x[2];
}
static void mat_tvec(const double A[9], const double x[3], double y[3]) {
  for (int i = 0; i < 3; i++)
    y[i] = A[i] * x[0] + A[3 + i] * x[1] + A[6 + i] * x[2];
}

/* Rotation factor k (Rot(e_k, th_k(alpha))) and its alpha-derivative
 * d_k [e_k]_x Rot(e_k, th_k). */
static void factor(const swarf_motion *m, int k, double alpha, double F[9], double dF[9]) {
  const double *e = k == 0 ? m->e1 : m->e2;
  double d = m->th1[k] - m->th0[k], th = m->th0[k] + alpha * d;
  double S[9] = {0, -e[2], e[1], e[2], 0, -e[0], -e[1], e[0], 0};
  rot_matrix(e, th, F);
  mat_mul(S, F, dF);
  for (int i = 0; i < 9; i++)
    dF[i] *= d;
}

/* Joint mode with head axes: t = pivot + T^T g, g = P - pivot + h - H^T h,
 * and tdot = dT^T g + T^T (dP - dH^T h). */
static void head_tip(const swarf_motion *m, double alpha, double t[3], double td[3]) {
  static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, Z[9] = {0};
  double F1[9], dF1[9], F2[9], dF2[9], H[9], dH[9], T[9], dT[9], A[9], B[9];
  double g[3], dg[3], Hh[3], dHh[3], P[3], dP[3], a[3], b[3];
  factor(m, 0, alpha, F1, dF1);
  factor(m, 1, alpha, F2, dF2);
  if (m->nhead >= 2) { /* H = F1 F2, T = I */
    mat_mul(F1, F2, H);
    mat_mul(dF1, F2, A);
    mat_mul(F1, dF2, B);
    for (int i = 0; i < 9; i++)
      dH[i] = A[i] + B[i];
    memcpy(T, I, sizeof T);
    memcpy(dT, Z, sizeof dT);
  } else { /* H = F1, T = F2 */
    memcpy(H, F1, sizeof H), memcpy(dH, dF1, sizeof dH);
    memcpy(T, F2, sizeof T), memcpy(dT, dF2, sizeof dT);
  }
  machine_arm(m, alpha, P, dP);
  mat_tvec(H, m->head, Hh);
  mat_tvec(dH, m->head, dHh);
  for (int k = 0; k < 3; k++) {
    g[k] = P[k] + m->head[k] - Hh[k];
    dg[k] = dP[k] - dHh[k];
  }
  mat_tvec(T, g, a);
  mat_tvec(dT, g, b);
  mat_tvec(T, dg, td);
  for (int k = 0; k < 3; k++) {
    t[k] = m->pivot[k] + a[k];
    td[k] += b[k];
  }
}

/* Pose (t, U) and velocities (tdot, v, omega) at alpha from one table
 * rotation (sin and cos once per axis); any output may be NULL. */
void swarf_rigid_pose(const swarf_motion *m, double alpha, double t[3], double U[9], double tdot[3],
                      double v[3], double omega[3]) {
  double R[9], R1[9], w[3], vv[3], td[3], d[3], dP[3];
  double d1 = m->th1[0] - m->th0[0], d2 = m->th1[1] - m->th0[1];
  table_rotation(m, alpha, R, R1);
  if (U != NULL)
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        U[3 * i + j] = R[3 * j + i];
  for (int k = 0; k < 3; k++)
    w[k] = -(d1 * m->e1[k] +
             d2 * (R1[3 * k] * m->e2[0] + R1[3 * k + 1] * m->e2[1] + R1[3 * k + 2] * m->e2[2]));
  if (m->tcp) { /* t = P, v = U^T tdot = R tdot */
    swarf_path_point(m, alpha, d, td);
    if (t != NULL) memcpy(t, d, sizeof d);
    mat_vec(R, td, vv);
  } else if (m->nhead > 0) { /* head axes: head_tip, v = R tdot */
    head_tip(m, alpha, d, td);
    if (t != NULL) memcpy(t, d, sizeof d);
    mat_vec(R, td, vv);
  } else { /* t = pivot + R^T d, v = omega x (P - pivot) + dP/da */
    machine_arm(m, alpha, d, dP);
    if (t != NULL)
      for (int k = 0; k < 3; k++)
        t[k] = m->pivot[k] + R[k] * d[0] + R[3 + k] * d[1] + R[6 + k] * d[2];
    vv[0] = w[1] * d[2] - w[2] * d[1] + dP[0];
    vv[1] = w[2] * d[0] - w[0] * d[2] + dP[1];
    vv[2] = w[0] * d[1] - w[1] * d[0] + dP[2];
    mat_tvec(R, vv, td);
  }
  if (tdot != NULL) memcpy(tdot, td, sizeof td);
  if (v != NULL) memcpy(v, vv, sizeof vv);
  if (omega != NULL) memcpy(omega, w, sizeof w);
}

void swarf_rigid_eval(const swarf_motion *m, double alpha, double t[3], double U[9]) {
  swarf_rigid_pose(m, alpha, t, U, NULL, NULL, NULL);
}

void swarf_rigid_velocity(const swarf_motion *m, double alpha, double tdot[3], double v[3],
                          double omega[3]) {
  swarf_rigid_pose(m, alpha, NULL, NULL, tdot, v, omega);
}

/* Tip path bounds: SAMPLES poses, widened by the distance the tip can travel
 * between two of them (half a step at the largest sampled speed, doubled for
 * safety: the speed varies by a factor 1 + O(turn) only). */
#define SAMPLES 64
void swarf_rigid_bounds(const swarf_motion *m, double lo[3], double hi[3]) {
  double t[3], td[3], speed = 0.0;
  for (int k = 0; k < 3; k++)
    lo[k] = INFINITY, hi[k] = -INFINITY;
  for (int i = 0; i <= SAMPLES; i++) {
    swarf_rigid_eval(m, (double)i / SAMPLES, t, NULL);
    swarf_rigid_velocity(m, (double)i / SAMPLES, td, NULL, NULL);
    speed = fmax(speed, sqrt(td[0] * td[0] + td[1] * td[1] + td[2] * td[2]));
    for (int k = 0; k < 3; k++)
      lo[k] = fmin(lo[k], t[k]), hi[k] = fmax(hi[k], t[k]);
  }
  for (int k = 0; k < 3; k++)
    lo[k] -= speed / SAMPLES, hi[k] += speed / SAMPLES;
}

/* Tip path length (workpiece frame) by Simpson's rule on 64 intervals
 * (exact for TCP lines and helices). */
double swarf_rigid_length(const swarf_motion *m) {
  double sum = 0.0, td[3];
  for (int i = 0; i <= SAMPLES; i++) {
    double w = i == 0 || i == SAMPLES ? 1.0 : (i % 2 ? 4.0 : 2.0);
    swarf_rigid_velocity(m, (double)i / SAMPLES, td, NULL, NULL);
    sum += w * sqrt(td[0] * td[0] + td[1] * td[1] + td[2] * td[2]);
  }
  return sum / (3.0 * SAMPLES);
}
