/* sweep_helix.c -- swept volumes of arcs and helices.
 *
 * arc, ring: a planar arc about a vertical axis (the cutter's own axis
 *   direction). The cutter is a body of revolution whose sdf does not
 *   decrease with the horizontal distance to its axis, so the nearest
 *   instance is the one at the point's polar angle when that angle is in the
 *   arc's range (sdf = cutter sdf at horizontal distance |rho - radius|), and
 *   otherwise the nearer end. Exact outside; exact inside where the cutter
 *   does not cover the arc's axis (radius >= D/2) and the polar angle is in
 *   range; a full circle whose radius is at most the core radius is a solid
 *   cylinder and exact everywhere.
 * helix: any other helix (rise != 0, or a horizontal axis as for G18/G19):
 *   sampling and certified refinement, in sweep_sampled.c.
 * aux layouts are set by swarf_sweep_helix_init and read here only.
 */
#include <math.h>

#include "engine_private.h"

static const double two_pi = 6.28318530717958647692;

/* aux for arc and ring */
enum { A_CX, A_CY, A_Z0, A_E1X, A_E1Y, A_E2X, A_E2Y, A_RAD, A_ANG, A_COS, A_SIN, A_X1, A_Y1 };

static void arc_init(swarf_sweep *s, const double e1[3], const double e2[3]) {
  const swarf_motion *m = s->motion;
  double *x = s->aux;
  s->method = m->angle >= two_pi ? SWARF_SWEEP_RING : SWARF_SWEEP_ARC;
  x[A_CX] = m->center[0];
  x[A_CY] = m->center[1];
  x[A_Z0] = m->p0[2];
  x[A_E1X] = e1[0];
  x[A_E1Y] = e1[1];
  x[A_E2X] = e2[0];
  x[A_E2Y] = e2[1];
  x[A_RAD] = m->radius;
  x[A_ANG] = m->angle;
  x[A_COS] = cos(m->angle);
  x[A_SIN] = sin(m->angle);
  x[A_X1] = m->center[0] + m->radius * (x[A_COS] * e1[0] + x[A_SIN] * e2[0]);
  x[A_Y1] = m->center[1] + m->radius * (x[A_COS] * e1[1] + x[A_SIN] * e2[1]);
}

/* Sample spacing along the path, mm: a fraction of the cutter, finer on tight
 * helices (whose curvature makes g non-convex over shorter spans). */
static double helix_step(const swarf_cutter *c, double radius) {
  double d = 0.125 * (c->fast ? c->diameter : fmin(c->diameter, c->length - c->zmin)), bend = fmax(0.25 * radius, 0.02 * c->diameter);
  d = fmin(d, bend);
  return fmin(d, 0.5);
}

static void helix_frame_init(swarf_sweep *s, const double e1[3], const double e2[3]) {
  const swarf_motion *m = s->motion;
  double *x = s->aux, len = hypot(m->radius * m->angle, m->rise), n;
  s->method = SWARF_SWEEP_HELIX;
  for (int k = 0; k < 3; k++) {
    x[SWARF_H_C + k] = m->center[k];
    x[SWARF_H_E1 + k] = e1[k];
    x[SWARF_H_E2 + k] = e2[k];
  }
  x[SWARF_H_RAD] = m->radius;
  x[SWARF_H_ANG] = m->angle;
  x[SWARF_H_RISE] = m->rise;
  n = ceil(len / helix_step(s->cutter, m->radius));
  x[SWARF_H_N] = n < 2.0 ? 2.0 : n > 1e6 ? 1e6 : n;
  x[SWARF_H_STEP] = len / x[SWARF_H_N];
  x[SWARF_H_LEN] = len;
}

void swarf_sweep_helix_init(swarf_sweep *s) {
  const swarf_motion *m = s->motion;
  double e1[3], e2[3], r = m->radius;
  if (!(r > 0.0) || !(m->angle > 0.0)) {
    swarf_sweep_line_init(s, m->p0, m->p1);
    return;
  }
  for (int k = 0; k < 3; k++) e1[k] = (m->p0[k] - m->center[k]) / r;
  e2[0] = m->axis[1] * e1[2] - m->axis[2] * e1[1];
  e2[1] = m->axis[2] * e1[0] - m->axis[0] * e1[2];
  e2[2] = m->axis[0] * e1[1] - m->axis[1] * e1[0];
  if (m->axis[0] == 0.0 && m->axis[1] == 0.0 && m->rise == 0.0)
    arc_init(s, e1, e2);
  else
    helix_frame_init(s, e1, e2);
}

static int arc_in_range(const double *x, double x1, double x2) {
  double side = x[A_COS] * x2 - x[A_SIN] * x1; /* < 0: before the end direction */
  if (x[A_ANG] <= 0.5 * two_pi) return x2 >= 0.0 && side <= 0.0;
  return x2 >= 0.0 || side <= 0.0;
}

static double arc_alpha(const double *x, double x1, double x2) {
  double psi = atan2(x2, x1);
  if (psi < 0.0) psi += two_pi;
  psi /= x[A_ANG];
  return psi < 1.0 ? psi : 1.0;
}

double swarf_sweep_arc_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  const double *x = s->aux;
  double qx = p[0] - x[A_CX], qy = p[1] - x[A_CY], z = p[2] - x[A_Z0];
  double x1 = qx * x[A_E1X] + qy * x[A_E1Y], x2 = qx * x[A_E2X] + qy * x[A_E2Y];
  double d0x, d0y, d1x, d1y, d0, d1;
  if (arc_in_range(x, x1, x2)) {
    if (alpha != NULL) *alpha = arc_alpha(x, x1, x2);
    return swarf_cutter_rz(s->cutter, fabs(sqrt(x1 * x1 + x2 * x2) - x[A_RAD]), z);
  }
  d0x = qx - x[A_RAD] * x[A_E1X];
  d0y = qy - x[A_RAD] * x[A_E1Y];
  d1x = p[0] - x[A_X1];
  d1y = p[1] - x[A_Y1];
  d0 = sqrt(d0x * d0x + d0y * d0y);
  d1 = sqrt(d1x * d1x + d1y * d1y);
  if (alpha != NULL) *alpha = d0 <= d1 ? 0.0 : 1.0;
  return swarf_cutter_rz(s->cutter, d0 <= d1 ? d0 : d1, z);
}

double swarf_sweep_ring_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  const double *x = s->aux;
  const swarf_cutter *c = s->cutter;
  double qx = p[0] - x[A_CX], qy = p[1] - x[A_CY], z = p[2] - x[A_Z0];
  double rho = sqrt(qx * qx + qy * qy), a = swarf_cutter_core(c), dr;
  if (!c->fast) { /* a profile's convex pieces: the nearest instance is at p's angle */
    if (alpha != NULL)
      *alpha = arc_alpha(x, qx * x[A_E1X] + qy * x[A_E1Y], qx * x[A_E2X] + qy * x[A_E2Y]);
    return swarf_cutter_sdf2(c, fabs(rho - x[A_RAD]), z, NULL);
  }
  /* A ring no wider than the core is a solid cylinder of radius radius + a. */
  dr = x[A_RAD] <= a ? rho - x[A_RAD] - a : fabs(rho - x[A_RAD]) - a;
  if (alpha != NULL)
    *alpha = arc_alpha(x, qx * x[A_E1X] + qy * x[A_E1Y], qx * x[A_E2X] + qy * x[A_E2Y]);
  return swarf_box2(dr, fabs(z - 0.5 * c->length) - (0.5 * c->length - c->corner_radius)) -
         c->corner_radius;
}
