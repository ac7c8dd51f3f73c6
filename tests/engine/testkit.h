/* SPDX-License-Identifier: MPL-2.0 */
/* testkit.h -- helpers shared by the engine tests and the benchmark (header
 * only): a seeded random generator, small vector helpers, moves built through
 * the toolpath module, and the brute-force swept-volume sdf (a dense minimum
 * over cutter instances plus golden-section refinement) that the engine's
 * evaluators are checked against.
 */
#ifndef SWARF_TESTS_ENGINE_TESTKIT_H
#define SWARF_TESTS_ENGINE_TESTKIT_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "engine.h"
#include "move_motion.h"

static const double tk_pi = 3.14159265358979323846;

typedef struct {
  uint64_t s;
} tk_rng;

static inline double tk_uniform(tk_rng *r, double lo, double hi) {
  r->s ^= r->s << 13;
  r->s ^= r->s >> 7;
  r->s ^= r->s << 17;
  return lo + (hi - lo) * ((double)(r->s >> 11) * (1.0 / 9007199254740992.0));
}

static inline void tk_unit(tk_rng *r, double n[3]) {
  double m;
  do {
    for (int k = 0; k < 3; k++)
      n[k] = tk_uniform(r, -1.0, 1.0);
    m = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  } while (m < 0.1 || m > 1.0);
  for (int k = 0; k < 3; k++)
    n[k] /= m;
}

static inline double tk_dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline double tk_dist(const double a[3], const double b[3]) {
  double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return sqrt(tk_dot(d, d));
}

static inline void tk_cross(const double a[3], const double b[3], double o[3]) {
  o[0] = a[1] * b[2] - a[2] * b[1];
  o[1] = a[2] * b[0] - a[0] * b[2];
  o[2] = a[0] * b[1] - a[1] * b[0];
}

/* Distance from p to the segment [a, b]. */
static inline double tk_seg_dist(const double p[3], const double a[3], const double b[3]) {
  double d[3], w[3], t, dd;
  for (int k = 0; k < 3; k++) {
    d[k] = b[k] - a[k];
    w[k] = p[k] - a[k];
  }
  dd = tk_dot(d, d);
  t = dd > 0.0 ? tk_dot(w, d) / dd : 0.0;
  t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
  for (int k = 0; k < 3; k++)
    w[k] -= t * d[k];
  return sqrt(tk_dot(w, w));
}

static inline swarf_motion tk_line(const double p0[3], const double p1[3]) {
  swarf_move mv;
  swarf_motion m;
  memset(&mv, 0, sizeof mv);
  mv.kind = SWARF_MOVE_LINE;
  mv.feed = 600.0;
  for (int k = 0; k < 3; k++) {
    mv.start[k] = p0[k];
    mv.end[k] = p1[k];
  }
  swarf_motion_from_move(&mv, &m, NULL);
  return m;
}

/* Helix from `start` about the axis through `center` with unit `normal`. */
static inline swarf_motion tk_helix(const double start[3], const double center[3],
                                    const double normal[3], double angle, double rise) {
  swarf_move mv;
  swarf_motion m;
  memset(&mv, 0, sizeof mv);
  mv.kind = SWARF_MOVE_ARC;
  mv.feed = 600.0;
  for (int k = 0; k < 3; k++) {
    mv.start[k] = start[k];
    mv.center[k] = center[k];
    mv.normal[k] = normal[k];
  }
  mv.angle = angle;
  mv.rise = rise;
  swarf_motion_from_move(&mv, &m, NULL);
  for (int k = 0; k < 3; k++)
    mv.end[k] = m.p1[k];
  return m;
}

/* The paper's Example 2 (ENVELOPE.md, Fact 3): U(alpha) = rotation by
 * +alpha about (2,1,2)/3, t(alpha) = alpha (1,1,0), alpha in [0, 2 atan bmax]
 * (half-angle tangent up to bmax), as a RIGID TCP motion turning about that
 * axis (U = R^T, R = Rot(axis, -alpha)). */
static inline swarf_motion tk_example2(double bmax) {
  swarf_motion m;
  double A = 2 * atan(bmax);
  memset(&m, 0, sizeof m);
  m.kind = SWARF_MOTION_RIGID;
  m.tcp = 1;
  m.e1[0] = 2.0 / 3.0, m.e1[1] = 1.0 / 3.0, m.e1[2] = 2.0 / 3.0;
  m.th1[0] = -A;
  m.p1[0] = m.p1[1] = A;
  m.turn = A, m.length = A * sqrt(2.0), m.duration = 1.0;
  return m;
}

static inline double tk_instance(const swarf_cutter *c, const swarf_motion *m, const double p[3],
                                 double alpha) {
  double t[3], q[3];
  swarf_motion_eval(m, alpha, t, NULL);
  for (int k = 0; k < 3; k++)
    q[k] = p[k] - t[k];
  return swarf_cutter_sdf(c, q);
}

/* Golden-section minimum of the instance sdf over [lo, hi]. */
static inline double tk_golden(const swarf_cutter *c, const swarf_motion *m, const double p[3],
                               double lo, double hi, double *amin) {
  const double g = 0.6180339887498949;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = tk_instance(c, m, p, x1), f2 = tk_instance(c, m, p, x2);
  for (int it = 0; it < 90; it++) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = tk_instance(c, m, p, x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = tk_instance(c, m, p, x2);
    }
  }
  *amin = f1 < f2 ? x1 : x2;
  return f1 < f2 ? f1 : f2;
}

/* Brute force: the minimum over nsamp + 1 instances, then golden section
 * around every sampled local minimum near the best. */
static inline double tk_brute(const swarf_cutter *c, const swarf_motion *m, const double p[3],
                              int nsamp, double *alpha) {
  double best = INFINITY, abest = 0.0, prev = INFINITY;
  double slack = 2.0 * (m->length + 1e-9) / nsamp + 1e-9, lowest = INFINITY;
  static double g[20001];
  int n = nsamp > 20000 ? 20000 : nsamp;
  for (int i = 0; i <= n; i++) {
    g[i] = tk_instance(c, m, p, (double)i / n);
    if (g[i] < lowest) lowest = g[i];
  }
  for (int i = 0; i <= n; i++) {
    double cur = g[i], next = i < n ? g[i + 1] : INFINITY, a;
    if (cur <= prev && cur <= next && cur <= lowest + slack) {
      double lo = i > 0 ? (double)(i - 1) / n : 0.0, hi = i < n ? (double)(i + 1) / n : 1.0;
      double v = tk_golden(c, m, p, lo, hi, &a);
      if (cur < v) {
        v = cur;
        a = (double)i / n;
      }
      if (v < best) {
        best = v;
        abest = a;
      }
    }
    prev = cur;
  }
  if (alpha != NULL) *alpha = abest;
  return best;
}

/* The cutter's sdf at p for the instance at alpha of a motion with rotation
 * (cutter frame q = U^T (p - t)). */
static inline double tk_rigid_instance(const swarf_cutter *c, const swarf_motion *m,
                                       const double p[3], double alpha) {
  double t[3], U[9], d[3], q[3];
  swarf_motion_eval(m, alpha, t, U);
  for (int k = 0; k < 3; k++)
    d[k] = p[k] - t[k];
  for (int k = 0; k < 3; k++)
    q[k] = U[k] * d[0] + U[3 + k] * d[1] + U[6 + k] * d[2];
  return swarf_cutter_sdf(c, q);
}

/* Golden-section minimum of tk_rigid_instance over [lo, hi]. */
static inline double tk_rigid_golden(const swarf_cutter *c, const swarf_motion *m,
                                     const double p[3], double lo, double hi) {
  const double g = 0.6180339887498949;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = tk_rigid_instance(c, m, p, x1), f2 = tk_rigid_instance(c, m, p, x2);
  for (int it = 0; it < 70; it++) {
    if (f1 < f2)
      hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = tk_rigid_instance(c, m, p, x1);
    else
      lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = tk_rigid_instance(c, m, p, x2);
  }
  return fmin(f1, f2);
}

/* The truth for a motion with rotation: n + 1 poses (n <= 60000), then golden
 * section around every sampled local minimum. */
static inline double tk_rigid_truth(const swarf_cutter *c, const swarf_motion *m, const double p[3],
                                    int n) {
  static double g[60001];
  double best = INFINITY;
  if (n > 60000) n = 60000;
  for (int i = 0; i <= n; i++)
    g[i] = tk_rigid_instance(c, m, p, (double)i / n);
  for (int i = 0; i <= n; i++) {
    double prev = i > 0 ? g[i - 1] : INFINITY, next = i < n ? g[i + 1] : INFINITY;
    best = fmin(best, g[i]);
    if (g[i] <= prev && g[i] <= next)
      best = fmin(
          best, tk_rigid_golden(c, m, p, i > 0 ? (i - 1.0) / n : 0.0, i < n ? (i + 1.0) / n : 1.0));
  }
  return best;
}

/* The motion of a straight move of six axes (X Y Z and the machine's two
 * rotary axes, as swarf_move's start and end) on `machine` (swarf_machine_parse's
 * description), at F500. Its status: the description's, else the motion's. */
static inline swarf_status tk_machine_move(const char *machine, const double s6[6],
                                           const double e6[6], swarf_motion *m) {
  swarf_machine mc;
  swarf_move mv;
  swarf_status st;
  memset(&mv, 0, sizeof mv);
  mv.kind = SWARF_MOVE_LINE;
  mv.feed = 500;
  memcpy(mv.start, s6, sizeof mv.start);
  memcpy(mv.end, e6, sizeof mv.end);
  if ((st = swarf_machine_parse(&mc, machine, NULL)) != SWARF_OK) return st;
  return swarf_machine_motion(&mc, &mv, m, NULL);
}

#endif
