/* SPDX-License-Identifier: MPL-2.0 */
/* cutter.c -- cutters of revolution: validation of flat/ball/bull, support
 * function, surface points x_h(n) and the exact signed distance of any
 * cutter (closed forms for flat/ball/bull, the profile's pieces otherwise).
 *
 * A flat, ball or bull cutter is C + B(R) (Minkowski sum): C the solid
 * cylinder of radius a = D/2 - R over z in [R, length - R], B(R) the ball of
 * the corner radius. Every function takes caller-owned values and keeps no
 * state.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "engine_private.h"

/* The dimensions are impossible: err gets the reason, and the letter of the
 * tool spec's number that is wrong (D, R or L) as its word. */
static swarf_status fail(swarf_error *err, const char *letter, const char *reason) {
  swarf_error_at(err, NULL, 0, 0, letter);
  return swarf_error_set(err, SWARF_ERR_TOOL, "%s", reason);
}

/* Corner radius for the shape, or a negative value when impossible. */
static double corner_for(swarf_cutter_shape shape, double d, double r, swarf_error *err) {
  switch (shape) {
  case SWARF_CUTTER_FLAT:
    return 0.0;
  case SWARF_CUTTER_BALL:
    return 0.5 * d;
  case SWARF_CUTTER_BULL:
    if (!isfinite(r) || r <= 0.0) {
      fail(err, "R", "a bull nose cutter needs a corner radius > 0");
      return -1.0;
    }
    if (r >= 0.5 * d) {
      fail(err, "R",
           "the corner radius of a bull nose cutter must be below half the diameter "
           "(use a ball cutter for R = D/2)");
      return -1.0;
    }
    return r;
  default:
    break;
  }
  fail(err, "D", "unknown cutter shape");
  return -1.0;
}

/* The one hull piece of a flat, ball or bull cutter: rounded at both rims
 * (the closed forms' body), or for a ball shorter than D the hemisphere on
 * a cylinder cut flat at the top. */
static void classic_piece(swarf_cutter *c) {
  double a = swarf_cutter_core(c), R = c->corner_radius, L = c->length;
  const double k[2][3] = {{a, R, R}, {a, L - R, R}};
  const double cut[2][3] = {{0.0, R, R}, {R, L, 0.0}};
  c->npieces = 0;
  if (c->fast)
    swarf_cutter_add_hull(c, k, 2, NULL);
  else
    swarf_cutter_add_hull_clipped(c, cut, 2, L, NULL);
  c->convex = 1;
  c->zmin = 0.0;
}

swarf_status swarf_cutter_init(swarf_cutter *c, swarf_cutter_shape shape, double diameter,
                               double corner_radius, double length, swarf_error *err) {
  double r;
  if (c == NULL) return swarf_error_set(err, SWARF_ERR_ARG, "no cutter to fill");
  if (!isfinite(diameter) || diameter <= 0.0) return fail(err, "D", "the diameter must be > 0");
  if (diameter < SWARF_CUTTER_MIN_MM || diameter > SWARF_CUTTER_MAX_MM)
    return fail(err, "D", "the diameter must be between 0.001 and 1000 mm (a typo or a unit slip)");
  r = corner_for(shape, diameter, corner_radius, err);
  if (r < 0.0) return SWARF_ERR_TOOL;
  if (isnan(length) || length == INFINITY)
    return fail(err, "L", "the length must be a finite number");
  if (length > SWARF_CUTTER_MAX_MM)
    return fail(err, "L", "the length must be at most 1000 mm (a typo or a unit slip)");
  if (length <= 0.0) length = 4.0 * diameter;
  if (shape == SWARF_CUTTER_BALL && length < r)
    return fail(err, "L", "the cutting length of a ball cutter must be at least its radius");
  if (shape == SWARF_CUTTER_BULL && length < 2.0 * r)
    return fail(err, "R",
                "the cutting length of a bull nose cutter must be at least twice its corner "
                "radius");
  memset(c, 0, sizeof *c);
  for (int i = 0; i < 8; i++)
    c->param[i] = NAN;
  c->shape = shape;
  c->diameter = diameter;
  c->corner_radius = r;
  c->length = length;
  c->fast = length >= 2.0 * r;
  c->param[0] = diameter, c->param[1] = r, c->param[2] = length;
  classic_piece(c);
  return SWARF_OK;
}

/* ---- Support function and surface points -------------------------------- */

/* Support of one piece in the meridian direction (rho, nz), rho >= 0, and
 * its support point (r, z) in the meridian plane. */
static double piece_support(const swarf_profile_piece *pc, double rho, double nz, double y[2]) {
  double best = -INFINITY;
  if (pc->kind == SWARF_PIECE_HULL) {
    for (int i = 0; i < pc->ncircle; i++) {
      const double *k = pc->circle[i];
      double h = k[0] * rho + k[1] * nz + k[2], zc = k[1] + k[2] * nz;
      double tol = 1e-15 * (1.0 + fabs(k[0]) + fabs(k[1]) + k[2]);
      if (h > best + tol || (h >= best - tol && (nz >= 0.0 ? zc > y[1] : zc < y[1]))) {
        best = h;
        y[0] = rho > 0.0 ? k[0] + k[2] * rho : 0.0;
        y[1] = zc;
      }
    }
    return best;
  }
  /* QSS: the points of the profile curve, s = n_z of their normal */
  if (pc->convex) {
    double s = nz, phi = (pc->q2 * s + pc->q1) * s + pc->q0, dphi = 2.0 * pc->q2 * s + pc->q1;
    y[0] = rho * (phi - dphi * s);
    y[1] = phi * s + dphi * (1.0 - s * s) + pc->lift;
    return y[0] * rho + y[1] * nz;
  }
  for (int i = 0; i <= 256; i++) { /* non-convex: the hull's support, sampled and polished */
    double s = -cos(3.14159265358979323846 * i / 256), c2 = 1.0 - s * s, q[2], h;
    q[0] = sqrt(c2 > 0 ? c2 : 0) * (pc->q0 - pc->q2 * s * s);
    q[1] = (-pc->q2 * s * s + pc->q0 + 2.0 * pc->q2) * s + pc->q1 + pc->lift;
    h = q[0] * rho + q[1] * nz;
    if (h > best) best = h, y[0] = q[0], y[1] = q[1];
  }
  return best;
}

static double cutter_support2(const swarf_cutter *c, double rho, double nz, double y[2]) {
  double best = -INFINITY, q[2] = {0, 0};
  for (int i = 0; i < c->npieces; i++) {
    double h = piece_support(&c->piece[i], rho, nz, q);
    if (h > best) best = h, y[0] = q[0], y[1] = q[1];
  }
  return best;
}

double swarf_cutter_support(const swarf_cutter *c, const double n[3]) {
  double R = c->corner_radius, z = n[2], rho = sqrt(n[0] * n[0] + n[1] * n[1]), y[2];
  if (!c->fast) return cutter_support2(c, rho, z, y);
  return swarf_cutter_core(c) * rho + R + (z >= 0.0 ? (c->length - R) * z : R * z);
}

void swarf_cutter_profile(const swarf_cutter *c, double z, double *phi, double *dphi) {
  double a = swarf_cutter_core(c), R = c->corner_radius, top = c->length - R;
  double s, y[2] = {0, 0};
  if (z > 1.0) z = 1.0;
  if (z < -1.0) z = -1.0;
  s = sqrt((1.0 - z) * (1.0 + z));
  if (!c->fast) {
    double h = cutter_support2(c, s, z, y);
    if (phi != NULL) *phi = h;
    if (dphi != NULL) { /* d/dz of y . (sqrt(1 - z^2), z) at the supporting point */
      if (s > 0.0)
        *dphi = -y[0] * z / s + y[1];
      else
        *dphi = y[0] > 0.0 ? (z > 0.0 ? -INFINITY : INFINITY) : y[1];
    }
    return;
  }
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
  if (!c->fast) {
    double y[2] = {0, 0}, u;
    cutter_support2(c, rho, n[2], y);
    u = rho > 0.0 ? y[0] / rho : 0.0;
    x[0] = u * n[0], x[1] = u * n[1], x[2] = y[1];
    return;
  }
  x[0] = k * n[0] + R * n[0];
  x[1] = k * n[1] + R * n[1];
  x[2] = h + R * n[2];
}

/* ---- Signed distance ------------------------------------------------------- */

double swarf_cutter_sdf2(const swarf_cutter *c, double r, double z, double g[2]) {
  double best = INFINITY, gg[2];
  if (c->fast) {
    if (g != NULL) {
      double p[3] = {r, 0.0, z}, g3[3], d = swarf_cutter_sdf_grad(c, p, g3);
      g[0] = g3[0], g[1] = g3[2];
      return d;
    }
    return swarf_cutter_sdf_rz(c, r, z);
  }
  for (int i = 0; i < c->npieces; i++) {
    double d = swarf_profile_piece_sdf(&c->piece[i], r, z, g != NULL ? gg : NULL);
    if (d < best) {
      best = d;
      if (g != NULL) g[0] = gg[0], g[1] = gg[1];
    }
  }
  return best;
}

double swarf_cutter_sdf(const swarf_cutter *c, const double p[3]) {
  double r = sqrt(p[0] * p[0] + p[1] * p[1]);
  if (!c->fast) return swarf_cutter_sdf2(c, r, p[2], NULL);
  return swarf_cutter_sdf_rz(c, r, p[2]);
}

/* The 3-D gradient from the meridian one (dr, dz) at p. */
static void lift_grad(const double p[3], double r, const double g2[2], double g[3]) {
  if (r > 0.0) {
    double k = g2[0] / r;
    g[0] = k * p[0], g[1] = k * p[1];
  } else {
    g[0] = g2[0], g[1] = 0.0;
  }
  g[2] = g2[1];
}

double swarf_cutter_sdf_grad(const swarf_cutter *c, const double p[3], double g[3]) {
  double R = c->corner_radius, mid = 0.5 * c->length;
  double r = sqrt(p[0] * p[0] + p[1] * p[1]);
  double dr, dz, sz;
  if (!c->fast) {
    double g2[2], d = swarf_cutter_sdf2(c, r, p[2], g2);
    lift_grad(p, r, g2, g);
    return d;
  }
  dr = r - swarf_cutter_core(c), dz = fabs(p[2] - mid) - (mid - R);
  sz = p[2] >= mid ? 1.0 : -1.0;
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
