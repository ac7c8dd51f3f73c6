/* cutter.c -- cutters of revolution: validation, support function, surface
 * points x_h(n) and the exact signed distance.
 *
 * A cutter is C + B(R) (Minkowski sum): C the solid cylinder of radius
 * a = D/2 - R over z in [R, length - R], B(R) the ball of the corner radius.
 * Every function takes caller-owned values and keeps no state.
 */
#include <math.h>
#include <stddef.h>

#include "engine_private.h"

static int fail(const char **why, const char *reason) {
  if (why != NULL) *why = reason;
  return -1;
}

/* Corner radius for the shape, or a negative value when impossible. */
static double corner_for(swarf_cutter_shape shape, double d, double r, const char **why) {
  switch (shape) {
  case SWARF_CUTTER_FLAT:
    return 0.0;
  case SWARF_CUTTER_BALL:
    return 0.5 * d;
  case SWARF_CUTTER_BULL:
    if (!isfinite(r) || r <= 0.0) {
      fail(why, "a bull nose cutter needs a corner radius > 0");
      return -1.0;
    }
    if (r >= 0.5 * d) {
      fail(why, "the corner radius of a bull nose cutter must be below half the diameter "
                "(use a ball cutter for R = D/2)");
      return -1.0;
    }
    return r;
  }
  fail(why, "unknown cutter shape");
  return -1.0;
}

int swarf_cutter_init(swarf_cutter *c, swarf_cutter_shape shape, double diameter,
                      double corner_radius, double length, const char **why) {
  double r;
  if (c == NULL) return fail(why, "no cutter to fill");
  if (!isfinite(diameter) || diameter <= 0.0) return fail(why, "the diameter must be > 0");
  r = corner_for(shape, diameter, corner_radius, why);
  if (r < 0.0) return -1;
  if (isnan(length) || length == INFINITY) return fail(why, "the length must be a finite number");
  if (length <= 0.0) length = 4.0 * diameter;
  if (length < diameter) return fail(why, "the cutting length must be at least the diameter");
  c->shape = shape;
  c->diameter = diameter;
  c->corner_radius = r;
  c->length = length;
  return 0;
}

double swarf_cutter_support(const swarf_cutter *c, const double n[3]) {
  double R = c->corner_radius, z = n[2];
  double h = swarf_cutter_core(c) * sqrt(n[0] * n[0] + n[1] * n[1]) + R;
  return h + (z >= 0.0 ? (c->length - R) * z : R * z);
}

void swarf_cutter_profile(const swarf_cutter *c, double z, double *phi, double *dphi) {
  double a = swarf_cutter_core(c), R = c->corner_radius, top = c->length - R;
  double s;
  if (z > 1.0) z = 1.0;
  if (z < -1.0) z = -1.0;
  s = sqrt((1.0 - z) * (1.0 + z));
  if (phi != NULL) *phi = a * s + R + (z >= 0.0 ? top * z : R * z);
  if (dphi == NULL) return;
  if (s > 0.0 || a == 0.0)
    *dphi = (s > 0.0 ? -a * z / s : 0.0) + (z >= 0.0 ? top : R);
  else
    *dphi = z > 0.0 ? -INFINITY : INFINITY;
}

void swarf_cutter_point(const swarf_cutter *c, const double n[3], double x[3]) {
  double a = swarf_cutter_core(c), R = c->corner_radius;
  double rho = sqrt(n[0] * n[0] + n[1] * n[1]);
  double k = rho > 0.0 ? a / rho : 0.0; /* the face centre at the poles */
  double h = n[2] >= 0.0 ? c->length - R : R;
  x[0] = k * n[0] + R * n[0];
  x[1] = k * n[1] + R * n[1];
  x[2] = h + R * n[2];
}

double swarf_cutter_sdf(const swarf_cutter *c, const double p[3]) {
  return swarf_cutter_sdf_rz(c, sqrt(p[0] * p[0] + p[1] * p[1]), p[2]);
}

double swarf_cutter_sdf_grad(const swarf_cutter *c, const double p[3], double g[3]) {
  double R = c->corner_radius, mid = 0.5 * c->length;
  double r = sqrt(p[0] * p[0] + p[1] * p[1]);
  double dr = r - swarf_cutter_core(c), dz = fabs(p[2] - mid) - (mid - R);
  double sz = p[2] >= mid ? 1.0 : -1.0;
  if (dr > 0.0 || dz > 0.0) {
    double gr = dr > 0.0 ? dr : 0.0, gz = dz > 0.0 ? dz : 0.0, d = sqrt(gr * gr + gz * gz);
    double inv = r > 0.0 ? 1.0 / (d * r) : 1.0 / d; /* one division */
    double kr = r > 0.0 ? gr * inv : 0.0;
    g[0] = kr * p[0];
    g[1] = kr * p[1];
    g[2] = (r > 0.0 ? gz * r * inv : gz * inv) * sz;
    return d - R;
  }
  if (dr > dz) {
    double inv = r > 0.0 ? 1.0 / r : 0.0;
    g[0] = r > 0.0 ? p[0] * inv : 1.0;
    g[1] = p[1] * inv;
    g[2] = 0.0;
    return dr - R;
  }
  g[0] = g[1] = 0.0;
  g[2] = sz;
  return dz - R;
}
