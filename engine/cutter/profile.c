/* SPDX-License-Identifier: MPL-2.0 */
/* profile.c -- the profile of a body of revolution in the (r, z) half-plane:
 * a hull piece's outline built from its circles, and the exact 2-D signed
 * distance of a piece (hull or QSS) with its gradient.
 *
 * Hull: the convex hull of circles (r_i, z_i, rho_i) and their mirrors. Its
 * outline over r >= 0 is traced by the outward normal u = (cos psi, sin psi),
 * psi from -pi/2 (down) to pi/2 (up): the supporting circle is the argmax of
 * r_i cos psi + z_i sin psi + rho_i; where another circle takes over, a
 * tangent segment joins them (gift wrapping by angle). Arcs are split at
 * psi = 0 so that the lower chain (psi < 0, r growing) and the upper chain
 * (psi > 0) meet at the side: the vertical part at r = rmax.
 *
 * QSS: the profile curve gamma(s) = (R(s), Z(s)), s = n_z in [-1, 1],
 * R = sqrt(1 - s^2)(q0 - q2 s^2), Z = -q2 s^3 + (q0 + 2 q2) s + q1 + lift.
 * Nearest points are where x - gamma is along the normal u(s) (a quartic in
 * s), at the cusps (Z'(s) = 0) or at the axis (s = +-1); the sign is the
 * parity of the crossings of the ray from x to r = +inf (a cubic in s).
 * Pure functions of caller-owned values.
 */
#include <math.h>
#include <string.h>

#include "engine_private.h"

#define HALF_PI 1.57079632679489661923
#define TWO_PI 6.28318530717958647692
#define ANG_EPS 1e-12

/* ---- Hull outline -------------------------------------------------------- */

static double support_at(const double c[3], double psi) {
  return c[0] * cos(psi) + c[1] * sin(psi) + c[2];
}

static void point_at(const double c[3], double psi, double p[2]) {
  p[0] = c[0] + c[2] * cos(psi);
  p[1] = c[1] + c[2] * sin(psi);
}

/* The angle in (psi, psi_end] where circle j takes over from circle i, or
 * +inf: where D = h_j - h_i = M cos(psi - psi0) + C turns positive. */
static double takeover(const double ci[3], const double cj[3], double psi) {
  double A = cj[0] - ci[0], B = cj[1] - ci[1], C = cj[2] - ci[2], M = hypot(A, B), a, t;
  if (!(M > fabs(C) + 1e-14 * (M + fabs(C)))) return INFINITY;
  a = atan2(B, A) - acos(-C / M);
  t = a + TWO_PI * ceil((psi + ANG_EPS - a) / TWO_PI);
  return t;
}

static int add_elem(swarf_profile_piece *pc, const double p0[2], const double p1[2],
                    const double *circle) {
  swarf_profile_elem *e;
  if (pc->nel == SWARF_PIECE_MAX_ELEMS) return -1;
  e = &pc->el[pc->nel++];
  memset(e, 0, sizeof *e);
  e->r0 = p0[0], e->z0 = p0[1], e->r1 = p1[0], e->z1 = p1[1];
  if (circle != NULL && circle[2] > 0.0) {
    e->cr = circle[0], e->cz = circle[1], e->rad = circle[2];
  } else {
    double dr = p1[0] - p0[0], dz = p1[1] - p0[1], l2 = dr * dr + dz * dz;
    e->inv = l2 > 0.0 ? 1.0 / l2 : 0.0;
  }
  return 0;
}

/* The arc of circle c from psi0 to psi1 (nothing for a point or an empty
 * range), split at psi = 0 where the side goes (a zero-length side when no
 * tangent segment is vertical there). */
static int add_arc(swarf_profile_piece *pc, const double c[3], double psi0, double psi1) {
  double a[2], b[2], m[2];
  point_at(c, psi0, a);
  point_at(c, psi1, b);
  if (psi0 < -ANG_EPS && psi1 > ANG_EPS) {
    point_at(c, 0.0, m);
    if (c[2] > 0.0 && add_elem(pc, a, m, c) != 0) return -1;
    pc->side = pc->nel;
    if (add_elem(pc, m, m, NULL) != 0) return -1;
    return c[2] > 0.0 ? add_elem(pc, m, b, c) : 0;
  }
  if (pc->side < 0 && fabs(psi0) <= ANG_EPS && psi1 > ANG_EPS) {
    pc->side = pc->nel; /* the side is this arc's first point */
    if (add_elem(pc, a, a, NULL) != 0) return -1;
  }
  if (c[2] > 0.0 && psi1 - psi0 > ANG_EPS && add_elem(pc, a, b, c) != 0) return -1;
  return 0;
}

/* The circle supporting direction psi first, ties broken toward the one that
 * stays on top for larger psi (larger derivative r sin... ). */
static int first_support(const swarf_profile_piece *pc, double psi) {
  int best = 0;
  for (int i = 1; i < pc->ncircle; i++) {
    double hi = support_at(pc->circle[i], psi), hb = support_at(pc->circle[best], psi);
    double di = -pc->circle[i][0] * sin(psi) + pc->circle[i][1] * cos(psi);
    double db = -pc->circle[best][0] * sin(psi) + pc->circle[best][1] * cos(psi);
    if (hi > hb + 1e-12 * (1.0 + fabs(hb)) ||
        (fabs(hi - hb) <= 1e-12 * (1.0 + fabs(hb)) && di > db))
      best = i;
  }
  return best;
}

/* Trace the outline; returns 0 or -1 (too many elements). */
int swarf_profile_hull_build(swarf_profile_piece *pc) {
  double psi = -HALF_PI, p[2], q[2];
  int cur = first_support(pc, psi), guard = 0;
  pc->nel = 0;
  pc->side = -1;
  point_at(pc->circle[cur], psi, p);
  if (p[0] > 0.0) { /* a flat bottom face from the axis */
    double a[2] = {0.0, p[1]};
    if (add_elem(pc, a, p, NULL) != 0) return -1;
  }
  while (psi < HALF_PI && guard++ < 4 * SWARF_PIECE_MAX_CIRCLES) {
    double next = HALF_PI, far = -INFINITY;
    int nj = -1;
    for (int j = 0; j < pc->ncircle; j++) {
      double t, a[2], b[2], along;
      if (j == cur) continue;
      t = takeover(pc->circle[cur], pc->circle[j], psi);
      if (!(t <= HALF_PI + ANG_EPS)) continue;
      point_at(pc->circle[cur], t, a);
      point_at(pc->circle[j], t, b);
      along = (b[0] - a[0]) * -sin(t) + (b[1] - a[1]) * cos(t);
      if (t < next - ANG_EPS || (t <= next + ANG_EPS && along > far)) next = t, nj = j, far = along;
    }
    if (nj < 0) next = HALF_PI;
    if (add_arc(pc, pc->circle[cur], psi, next) != 0) return -1;
    if (nj < 0) break;
    point_at(pc->circle[cur], next, p);
    point_at(pc->circle[nj], next, q);
    if (fabs(next) <= ANG_EPS && pc->side < 0) pc->side = pc->nel;
    if ((p[0] != q[0] || p[1] != q[1]) && add_elem(pc, p, q, NULL) != 0) return -1;
    cur = nj;
    psi = next;
  }
  point_at(pc->circle[cur], HALF_PI, p);
  if (p[0] > 0.0) { /* a flat top face back to the axis */
    double a[2] = {0.0, p[1]};
    if (add_elem(pc, p, a, NULL) != 0) return -1;
  }
  if (pc->side < 0) return -1;
  return 0;
}

/* Extent and the side's span from the outline. */
void swarf_profile_hull_extent(swarf_profile_piece *pc) {
  const swarf_profile_elem *s = &pc->el[pc->side];
  pc->zlo = INFINITY, pc->zhi = -INFINITY;
  for (int i = 0; i < pc->ncircle; i++) {
    pc->zlo = fmin(pc->zlo, pc->circle[i][1] - pc->circle[i][2]);
    pc->zhi = fmax(pc->zhi, pc->circle[i][1] + pc->circle[i][2]);
  }
  pc->rmax = s->r0;
  pc->zw0 = fmin(s->z0, s->z1);
  pc->zw1 = fmax(s->z0, s->z1);
}

/* ---- Hull distance -------------------------------------------------------- */

/* Nearest point of element e to (r, z); returns the squared distance. */
static double elem_nearest(const swarf_profile_elem *e, double r, double z, double y[2]) {
  if (e->rad > 0.0) {
    double dr = r - e->cr, dz = z - e->cz;
    double s0r = e->r0 - e->cr, s0z = e->z0 - e->cz, s1r = e->r1 - e->cr, s1z = e->z1 - e->cz;
    if (s0r * dz - s0z * dr >= 0.0 && dr * s1z - dz * s1r >= 0.0) {
      double m = sqrt(dr * dr + dz * dz), k = m > 0.0 ? e->rad / m : 0.0, d;
      y[0] = m > 0.0 ? e->cr + k * dr : e->r0;
      y[1] = m > 0.0 ? e->cz + k * dz : e->z0;
      d = m - e->rad;
      return d * d;
    } else {
      double d0 = (r - e->r0) * (r - e->r0) + (z - e->z0) * (z - e->z0);
      double d1 = (r - e->r1) * (r - e->r1) + (z - e->z1) * (z - e->z1);
      if (d0 <= d1) {
        y[0] = e->r0, y[1] = e->z0;
        return d0;
      }
      y[0] = e->r1, y[1] = e->z1;
      return d1;
    }
  } else {
    double dr = e->r1 - e->r0, dz = e->z1 - e->z0;
    double t = ((r - e->r0) * dr + (z - e->z0) * dz) * e->inv;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    y[0] = e->r0 + t * dr, y[1] = e->z0 + t * dz;
    return (r - y[0]) * (r - y[0]) + (z - y[1]) * (z - y[1]);
  }
}

/* Height of element e at abscissa r (within its r range). */
static double elem_height(const swarf_profile_elem *e, double r, int upper) {
  if (e->rad > 0.0) {
    double d = e->rad * e->rad - (r - e->cr) * (r - e->cr);
    d = d > 0.0 ? sqrt(d) : 0.0;
    return upper ? e->cz + d : e->cz - d;
  }
  if (e->r1 == e->r0) return upper ? fmax(e->z0, e->z1) : fmin(e->z0, e->z1);
  return e->z0 + (r - e->r0) / (e->r1 - e->r0) * (e->z1 - e->z0);
}

/* Inside the mirrored convex region: r <= rmax and between the chains. */
static int hull_inside(const swarf_profile_piece *pc, double r, double z, double dz) {
  int lo_ok = 0, hi_ok = 0;
  if (r > pc->rmax) return 0;
  for (int i = 0; i < pc->side; i++) {
    const swarf_profile_elem *e = &pc->el[i];
    if (r >= e->r0 && r <= e->r1) {
      lo_ok = z >= elem_height(e, r, 0);
      break;
    }
  }
  if (!lo_ok) return 0;
  for (int i = pc->side + 1; i < pc->nel; i++) {
    const swarf_profile_elem *e = &pc->el[i];
    if (r <= e->r0 && r >= e->r1) {
      hi_ok = z - dz <= elem_height(e, r, 1);
      break;
    }
  }
  return hi_ok;
}

/* The hull's signed distance at (r, z) with the upper chain raised by dz
 * (dz > 0: the hull swept up by dz, a plunge; 0: the hull). */
double swarf_profile_hull_sdf(const swarf_profile_piece *pc, double r, double z, double dz,
                              double g[2]) {
  double best = INFINITY, y[2], by[2] = {0, 0}, d;
  int bi = 0, in;
  for (int i = 0; i < pc->nel; i++) {
    double zz = i > pc->side ? z - dz : z, dd;
    if (i == pc->side) { /* the side, stretched by dz */
      swarf_profile_elem s = pc->el[i];
      double l2;
      s.z1 = s.z1 + dz;
      l2 = (s.z1 - s.z0) * (s.z1 - s.z0);
      s.inv = l2 > 0.0 ? 1.0 / l2 : 0.0;
      dd = elem_nearest(&s, r, z, y);
    } else {
      dd = elem_nearest(&pc->el[i], r, zz, y);
      if (i > pc->side) y[1] += dz;
    }
    if (dd < best) best = dd, by[0] = y[0], by[1] = y[1], bi = i;
  }
  d = sqrt(best);
  in = hull_inside(pc, r, z, dz);
  if (g != NULL) {
    if (d > 0.0) {
      double k = (in ? -1.0 : 1.0) / d;
      g[0] = (r - by[0]) * k, g[1] = (z - by[1]) * k;
    } else { /* on the outline: the element's outward normal */
      const swarf_profile_elem *e = &pc->el[bi];
      double tr = e->r1 - e->r0, tz = e->z1 - e->z0, m = hypot(tr, tz);
      if (e->rad > 0.0) {
        tr = by[0] - e->cr, tz = by[1] - (bi > pc->side ? e->cz + dz : e->cz);
        m = hypot(tr, tz);
        g[0] = m > 0 ? tr / m : 1.0, g[1] = m > 0 ? tz / m : 0.0;
      } else if (m > 0.0) {
        g[0] = tz / m, g[1] = -tr / m;
      } else {
        g[0] = 1.0, g[1] = 0.0;
      }
    }
  }
  return in ? -d : d;
}

/* ---- QSS distance --------------------------------------------------------- */

static double horner(const double *c, int deg, double x) {
  double p = c[deg];
  for (int i = deg - 1; i >= 0; i--)
    p = p * x + c[i];
  return p;
}

/* The sign change of c in (a, b) (f(a), f(b) of opposite signs): Newton
 * steps kept inside the bracket, bisection otherwise, to adjacent doubles. */
static double root_in(const double *c, int deg, double a, double b) {
  double fa = horner(c, deg, a), x = 0.5 * (a + b);
  for (int it = 0; it < 100; it++) {
    double f = 0.0, df = 0.0, m = 0.0, ax = fabs(x), nx;
    for (int i = deg; i >= 0; i--)
      df = df * x + f, f = f * x + c[i], m = m * ax + fabs(c[i]);
    if (fabs(f) <= 8e-16 * m) return x; /* within the rounding of the evaluation */
    if ((f < 0.0) == (fa < 0.0))
      a = x, fa = f;
    else
      b = x;
    nx = df != 0.0 ? x - f / df : 0.5 * (a + b);
    if (!(nx > a && nx < b)) nx = 0.5 * (a + b);
    if (fabs(nx - x) <= 4e-16 * fmax(1.0, ax) || b - a <= 2.5e-16 * fmax(1.0, ax)) return nx;
    x = nx;
  }
  return x;
}

/* Sign changes of the polynomial c (degree <= 4) in (lo, hi), ascending:
 * monotone pieces between the derivative's roots. */
static int roots_fast(const double *c, int deg, double lo, double hi, double *out) {
  double d[4], ends[6];
  int n = 0, ne;
  while (deg > 0 && c[deg] == 0.0)
    deg--;
  if (deg <= 0) return 0;
  if (deg == 1) {
    double x = -c[0] / c[1];
    if (x > lo && x < hi) out[n++] = x;
    return n;
  }
  if (deg == 2) { /* closed form, without cancellation */
    double disc = c[1] * c[1] - 4.0 * c[2] * c[0], q, x0, x1;
    if (!(disc > 0.0)) return 0;
    q = -0.5 * (c[1] + copysign(sqrt(disc), c[1]));
    x0 = q / c[2], x1 = q != 0.0 ? c[0] / q : x0;
    if (x0 > x1) q = x0, x0 = x1, x1 = q;
    if (x0 > lo && x0 < hi) out[n++] = x0;
    if (x1 > lo && x1 < hi) out[n++] = x1;
    return n;
  }
  for (int i = 1; i <= deg; i++)
    d[i - 1] = i * c[i];
  ends[0] = lo;
  ne = 1 + roots_fast(d, deg - 1, lo, hi, ends + 1);
  ends[ne++] = hi;
  for (int i = 0; i + 1 < ne; i++) {
    double fa = horner(c, deg, ends[i]), fb = horner(c, deg, ends[i + 1]);
    if (fa == 0.0 || fb == 0.0 || (fa < 0.0) == (fb < 0.0)) continue;
    out[n++] = root_in(c, deg, ends[i], ends[i + 1]);
  }
  return n;
}

void swarf_profile_qss_point(const swarf_profile_piece *pc, double s, double y[2]) {
  double c2 = 1.0 - s * s;
  y[0] = sqrt(c2 > 0.0 ? c2 : 0.0) * (pc->q0 - pc->q2 * s * s);
  y[1] = (-pc->q2 * s * s + pc->q0 + 2.0 * pc->q2) * s + pc->q1 + pc->lift;
}

/* Crossings of the ray from (r, z) toward r = +inf with the profile curve. */
static int qss_inside(const swarf_profile_piece *pc, double r, double z) {
  double c[4] = {pc->q1 + pc->lift - z, pc->q0 + 2.0 * pc->q2, 0.0, -pc->q2}, s[3];
  int n = roots_fast(c, 3, -1.0, 1.0, s), cross = 0;
  for (int i = 0; i < n; i++) {
    double y[2];
    swarf_profile_qss_point(pc, s[i], y);
    cross += y[0] > r;
  }
  return cross & 1;
}

double swarf_profile_qss_sdf_near(const swarf_profile_piece *pc, double r, double z, double g[2],
                                  double near[2]) {
  double w = z - pc->lift - pc->q1, k = 2.0 * pc->q2;
  double c[5] = {w * w, -2.0 * w * k, k * k - w * w - r * r, 2.0 * w * k, -k * k};
  double cand[10], best = INFINITY, by[2] = {0, 0}, d, cusp;
  int n = roots_fast(c, 4, -1.0, 1.0, cand), in;
  cand[n++] = -1.0;
  cand[n++] = 1.0;
  if (pc->q2 != 0.0 && (cusp = (pc->q0 + 2.0 * pc->q2) / (3.0 * pc->q2)) > 0.0 && cusp < 1.0) {
    cand[n++] = sqrt(cusp);
    cand[n++] = -sqrt(cusp);
  }
  for (int i = 0; i < n; i++) {
    double y[2], dd;
    swarf_profile_qss_point(pc, cand[i], y);
    dd = (r - y[0]) * (r - y[0]) + (z - y[1]) * (z - y[1]);
    if (dd < best) best = dd, by[0] = y[0], by[1] = y[1];
  }
  d = sqrt(best);
  in = qss_inside(pc, r, z);
  if (near != NULL) near[0] = by[0], near[1] = by[1];
  if (g != NULL) {
    double kk = d > 0.0 ? (in ? -1.0 : 1.0) / d : 0.0;
    g[0] = d > 0.0 ? (r - by[0]) * kk : 1.0;
    g[1] = d > 0.0 ? (z - by[1]) * kk : 0.0;
  }
  return in ? -d : d;
}

double swarf_profile_qss_sdf(const swarf_profile_piece *pc, double r, double z, double g[2]) {
  return swarf_profile_qss_sdf_near(pc, r, z, g, NULL);
}

double swarf_profile_piece_sdf(const swarf_profile_piece *pc, double r, double z, double g[2]) {
  if (pc->kind == SWARF_PIECE_QSS) return swarf_profile_qss_sdf(pc, r, z, g);
  return swarf_profile_hull_sdf(pc, r, z, 0.0, g);
}

double swarf_profile_piece_sdf_grad(const swarf_profile_piece *pc, const double q[3], double g[3]) {
  double r = sqrt(q[0] * q[0] + q[1] * q[1]), g2[2], d = swarf_profile_piece_sdf(pc, r, q[2], g2);
  if (r > 0.0) {
    double k = g2[0] / r;
    g[0] = k * q[0], g[1] = k * q[1];
  } else {
    g[0] = g2[0], g[1] = 0.0;
  }
  g[2] = g2[1];
  return d;
}
