/* SPDX-License-Identifier: MPL-2.0 */
/* motion.c -- rigid motions of the cutter: the xyz machine's lines and
 * helices (t(alpha), U(alpha) = I: the tool tip follows the programmed
 * straight line or helix exactly, no chords) and the public dispatch to
 * rigid.c for RIGID motions. Values only; the caller owns every struct.
 */
#include <math.h>
#include <string.h>

#include "toolpath_private.h"

static const double pi = 3.14159265358979323846;

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double out[3]) {
  double r[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  memcpy(out, r, sizeof r);
}

/* Rotate v by angle th about the unit axis n (right-hand rule). */
static void rotate3(const double n[3], double th, const double v[3], double out[3]) {
  double c = cos(th), s = sin(th), nxv[3], nv = dot3(n, v);
  cross3(n, v, nxv);
  for (int k = 0; k < 3; k++)
    out[k] = v[k] * c + nxv[k] * s + n[k] * nv * (1.0 - c);
}

static void set_identity(double U[9]) {
  static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  memcpy(U, I, sizeof I);
}

void swarf_motion_eval(const swarf_motion *m, double alpha, double t[3], double U[9]) {
  if (m->kind == SWARF_MOTION_RIGID) {
    swarf_rigid_eval(m, alpha, t, U);
    return;
  }
  if (U != NULL) set_identity(U);
  swarf_path_point(m, alpha, t, NULL);
}

void swarf_path_point(const swarf_motion *m, double alpha, double t[3], double d[3]) {
  if (!m->helix) {
    for (int k = 0; k < 3; k++)
      t[k] = m->p0[k] + alpha * (m->p1[k] - m->p0[k]);
    if (d != NULL)
      for (int k = 0; k < 3; k++)
        d[k] = m->p1[k] - m->p0[k];
    return;
  }
  double r[3], rr[3], nxr[3];
  for (int k = 0; k < 3; k++)
    r[k] = m->p0[k] - m->center[k];
  rotate3(m->axis, alpha * m->angle, r, rr);
  for (int k = 0; k < 3; k++)
    t[k] = m->center[k] + rr[k] + alpha * m->rise * m->axis[k];
  if (d == NULL) return;
  cross3(m->axis, rr, nxr);
  for (int k = 0; k < 3; k++)
    d[k] = m->angle * nxr[k] + m->rise * m->axis[k];
}

void swarf_motion_velocity(const swarf_motion *m, double alpha, double tdot[3], double v[3],
                           double omega[3]) {
  double d[3], t[3];
  if (m->kind == SWARF_MOTION_RIGID) {
    swarf_rigid_velocity(m, alpha, tdot, v, omega);
    return;
  }
  swarf_path_point(m, alpha, t, d);
  if (tdot != NULL) memcpy(tdot, d, sizeof d);
  if (v != NULL) memcpy(v, d, sizeof d); /* U = I: v = U^T tdot = tdot */
  if (omega != NULL) omega[0] = omega[1] = omega[2] = 0.0;
}

/* Widen [lo, hi] in coordinate k by the helix at parameter theta (radians). */
static void helix_include(const swarf_motion *m, double theta, double lo[3], double hi[3]) {
  double t[3];
  if (theta < 0.0 || theta > m->angle) return;
  swarf_motion_eval(m, theta / m->angle, t, NULL);
  for (int k = 0; k < 3; k++) {
    if (t[k] < lo[k]) lo[k] = t[k];
    if (t[k] > hi[k]) hi[k] = t[k];
  }
}

/* Coordinate k of the helix is c + r rho cos(theta - theta_k) + s theta; its
 * stationary points solve sin(theta - theta_k) = s / (r rho). */
static void helix_extrema(const swarf_motion *m, int k, double lo[3], double hi[3]) {
  double r[3], e2[3], a, b, rho, thk, s, q;
  for (int j = 0; j < 3; j++)
    r[j] = m->p0[j] - m->center[j];
  cross3(m->axis, r, e2);
  a = r[k];  /* coefficient of cos(theta) */
  b = e2[k]; /* coefficient of sin(theta) */
  rho = hypot(a, b);
  if (rho == 0.0) return;
  thk = atan2(b, a);
  s = m->rise * m->axis[k] / m->angle;
  q = s / rho;
  if (fabs(q) > 1.0) return;
  double roots[2] = {thk + asin(q), thk + pi - asin(q)};
  for (int i = 0; i < 2; i++) {
    double th = roots[i] - 2.0 * pi * floor(roots[i] / (2.0 * pi));
    for (; th <= m->angle; th += 2.0 * pi)
      helix_include(m, th, lo, hi);
  }
}

void swarf_motion_bounds(const swarf_motion *m, double lo[3], double hi[3]) {
  if (m->kind == SWARF_MOTION_RIGID) {
    swarf_rigid_bounds(m, lo, hi);
    return;
  }
  for (int k = 0; k < 3; k++) {
    lo[k] = fmin(m->p0[k], m->p1[k]);
    hi[k] = fmax(m->p0[k], m->p1[k]);
  }
  if (m->kind != SWARF_MOTION_HELIX) return;
  helix_include(m, m->angle, lo, hi);
  for (int k = 0; k < 3; k++)
    helix_extrema(m, k, lo, hi);
}

int swarf_motion_is_null(const swarf_motion *m) {
  if (m->kind == SWARF_MOTION_RIGID && (m->th0[0] != m->th1[0] || m->th0[1] != m->th1[1])) return 0;
  if (m->helix) return m->angle == 0.0 && m->rise == 0.0;
  return m->p0[0] == m->p1[0] && m->p0[1] == m->p1[1] && m->p0[2] == m->p1[2];
}

void swarf_motion_pose(const swarf_motion *m, double alpha, swarf_pose *out) {
  if (m->kind == SWARF_MOTION_RIGID) {
    swarf_rigid_pose(m, alpha, out->t, out->U, NULL, out->v, out->omega);
    return;
  }
  swarf_motion_eval(m, alpha, out->t, out->U);
  swarf_motion_velocity(m, alpha, NULL, out->v, out->omega);
}

void swarf_pose_rates_of(const swarf_pose *p, swarf_pose_rates *out) {
  const double *U = p->U, *v = p->v, *w = p->omega;
  for (int i = 0; i < 3; i++) {
    out->tdot[i] = U[3 * i] * v[0] + U[3 * i + 1] * v[1] + U[3 * i + 2] * v[2];
    out->kdot[i] = U[3 * i] * w[1] - U[3 * i + 1] * w[0]; /* U (omega_y, -omega_x, 0) */
  }
}
