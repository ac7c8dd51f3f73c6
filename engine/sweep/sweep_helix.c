/* SPDX-License-Identifier: MPL-2.0 */
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
 *   sampling and certified refinement, in sweep_sampled.c; turn by turn
 *   when it makes more than two turns about a vertical axis, and only the
 *   one-turn window level with the point when it makes more than one turn
 *   about a horizontal axis.
 * The per-method data (engine_private.h) is set by swarf_sweep_helix_init.
 */
#include <math.h>

#include "engine_private.h"

static const double two_pi = 6.28318530717958647692;

static void arc_init(swarf_sweep *s, const double e1[3], const double e2[3]) {
  const swarf_motion *m = s->motion;
  swarf_sweep_data *sd = swarf_sweep_data_of(s);
  swarf_sweep_arc *x = &sd->u.arc;
  sd->method = m->angle >= two_pi ? SWARF_SWEEP_RING : SWARF_SWEEP_ARC;
  x->cx = m->center[0];
  x->cy = m->center[1];
  x->z0 = m->p0[2];
  x->e1[0] = e1[0];
  x->e1[1] = e1[1];
  x->e2[0] = e2[0];
  x->e2[1] = e2[1];
  x->radius = m->radius;
  x->angle = m->angle;
  x->cos_angle = cos(m->angle);
  x->sin_angle = sin(m->angle);
  x->x1 = m->center[0] + m->radius * (x->cos_angle * e1[0] + x->sin_angle * e2[0]);
  x->y1 = m->center[1] + m->radius * (x->cos_angle * e1[1] + x->sin_angle * e2[1]);
}

/* Sample spacing along the path, mm: a fraction of the cutter, finer on tight
 * helices (whose curvature makes g non-convex over shorter spans). */
static double helix_step(const swarf_cutter *c, double radius) {
  double d = 0.125 * (c->fast ? c->diameter : fmin(c->diameter, c->length - c->zmin)),
         bend = fmax(0.25 * radius, 0.02 * c->diameter);
  d = fmin(d, bend);
  return fmin(d, 0.5);
}

static void helix_frame_init(swarf_sweep *s, const double e1[3], const double e2[3]) {
  const swarf_motion *m = s->motion;
  swarf_sweep_data *sd = swarf_sweep_data_of(s);
  swarf_sweep_helix *x = &sd->u.helix;
  double len = hypot(m->radius * m->angle, m->rise), n;
  sd->method = SWARF_SWEEP_HELIX;
  for (int k = 0; k < 3; k++) {
    x->c[k] = m->center[k];
    x->e1[k] = e1[k];
    x->e2[k] = e2[k];
  }
  x->radius = m->radius;
  x->angle = m->angle;
  x->rise = m->rise;
  n = ceil(len / helix_step(s->cutter, m->radius));
  x->tn = 0;
  if ((m->axis[0] == 0.0 && m->axis[1] == 0.0 && m->angle > 2.0 * two_pi) ||
      (m->axis[2] == 0.0 && m->angle > two_pi)) {
    /* turn by turn, or one turn's window (sweep_sampled.c): the samples of one turn */
    double tn = ceil(n * two_pi / m->angle);
    x->tn = tn < 2.0 ? 2 : tn > 1e6 ? 1000000 : (int)tn;
  }
  n = n < 2.0 ? 2.0 : n > 1e6 ? 1e6 : n;
  x->n = (int)n;
  x->step = len / n;
  x->len = len;
}

void swarf_sweep_helix_init(swarf_sweep *s) {
  const swarf_motion *m = s->motion;
  double e1[3], e2[3], r = m->radius;
  if (!(r > 0.0) || !(m->angle > 0.0)) {
    swarf_sweep_line_init(s, m->p0, m->p1);
    return;
  }
  for (int k = 0; k < 3; k++)
    e1[k] = (m->p0[k] - m->center[k]) / r;
  e2[0] = m->axis[1] * e1[2] - m->axis[2] * e1[1];
  e2[1] = m->axis[2] * e1[0] - m->axis[0] * e1[2];
  e2[2] = m->axis[0] * e1[1] - m->axis[1] * e1[0];
  if (m->axis[0] == 0.0 && m->axis[1] == 0.0 && m->rise == 0.0)
    arc_init(s, e1, e2);
  else
    helix_frame_init(s, e1, e2);
}

static int arc_in_range(const swarf_sweep_arc *x, double x1, double x2) {
  double side = x->cos_angle * x2 - x->sin_angle * x1; /* < 0: before the end direction */
  if (x->angle <= 0.5 * two_pi) return x2 >= 0.0 && side <= 0.0;
  return x2 >= 0.0 || side <= 0.0;
}

static double arc_alpha(const swarf_sweep_arc *x, double x1, double x2) {
  double psi = atan2(x2, x1);
  if (psi < 0.0) psi += two_pi;
  psi /= x->angle;
  return psi < 1.0 ? psi : 1.0;
}

double swarf_sweep_arc_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  const swarf_sweep_arc *x = &swarf_sweep_cdata(s)->u.arc;
  double qx = p[0] - x->cx, qy = p[1] - x->cy, z = p[2] - x->z0;
  double x1 = qx * x->e1[0] + qy * x->e1[1], x2 = qx * x->e2[0] + qy * x->e2[1];
  double d0x, d0y, d1x, d1y, d0, d1;
  if (arc_in_range(x, x1, x2)) {
    if (alpha != NULL) *alpha = arc_alpha(x, x1, x2);
    return swarf_cutter_rz(s->cutter, fabs(sqrt(x1 * x1 + x2 * x2) - x->radius), z);
  }
  d0x = qx - x->radius * x->e1[0];
  d0y = qy - x->radius * x->e1[1];
  d1x = p[0] - x->x1;
  d1y = p[1] - x->y1;
  d0 = sqrt(d0x * d0x + d0y * d0y);
  d1 = sqrt(d1x * d1x + d1y * d1y);
  if (alpha != NULL) *alpha = d0 <= d1 ? 0.0 : 1.0;
  return swarf_cutter_rz(s->cutter, d0 <= d1 ? d0 : d1, z);
}

double swarf_sweep_ring_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  const swarf_sweep_arc *x = &swarf_sweep_cdata(s)->u.arc;
  const swarf_cutter *c = s->cutter;
  double qx = p[0] - x->cx, qy = p[1] - x->cy, z = p[2] - x->z0;
  double rho = sqrt(qx * qx + qy * qy), a = swarf_cutter_core(c), dr;
  if (!c->fast) { /* a profile's convex pieces: the nearest instance is at p's angle */
    if (alpha != NULL)
      *alpha = arc_alpha(x, qx * x->e1[0] + qy * x->e1[1], qx * x->e2[0] + qy * x->e2[1]);
    return swarf_cutter_sdf2(c, fabs(rho - x->radius), z, NULL);
  }
  /* A ring no wider than the core is a solid cylinder of radius radius + a. */
  dr = x->radius <= a ? rho - x->radius - a : fabs(rho - x->radius) - a;
  if (alpha != NULL)
    *alpha = arc_alpha(x, qx * x->e1[0] + qy * x->e1[1], qx * x->e2[0] + qy * x->e2[1]);
  return swarf_box2(dr, fabs(z - 0.5 * c->length) - (0.5 * c->length - c->corner_radius)) -
         c->corner_radius;
}
