/* SPDX-License-Identifier: MPL-2.0 */
/* charpoly.c -- real roots of a small double-precision polynomial on an
 * interval, for the fast path's branch points of a QSS (Delta(z) is a
 * quartic): the critical points (roots of the derivative, recursively)
 * split the interval into monotone pieces, and each sign change is bisected
 * to adjacent doubles. Roots of even multiplicity (no sign change) are not
 * reported. Pure function of its arguments.
 */
#include "engine_private.h"

#define MAX_DEG 8

static double horner(const double *c, int deg, double x) {
  double p = c[deg];
  for (int i = deg - 1; i >= 0; i--)
    p = p * x + c[i];
  return p;
}

static double bisect(const double *c, int deg, double lo, double hi) {
  int slo = horner(c, deg, lo) > 0.0;
  for (;;) {
    double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) return mid;
    if ((horner(c, deg, mid) > 0.0) == slo)
      lo = mid;
    else
      hi = mid;
  }
}

int swarf_char_poly_roots(const double *c, int deg, double lo, double hi, double *roots, int max) {
  double d[MAX_DEG], ends[MAX_DEG + 1];
  int ncrit, n = 0;
  while (deg > 0 && c[deg] == 0.0)
    deg--;
  if (deg <= 0 || deg > MAX_DEG) return 0;
  for (int i = 1; i <= deg; i++)
    d[i - 1] = i * c[i];
  ends[0] = lo;
  ncrit = swarf_char_poly_roots(d, deg - 1, lo, hi, ends + 1, MAX_DEG - 1);
  ends[ncrit + 1] = hi;
  for (int i = 0; i <= ncrit; i++) {
    double a = ends[i], b = ends[i + 1], pa = horner(c, deg, a), pb = horner(c, deg, b);
    if (!(b > a) || (pa > 0.0) == (pb > 0.0) || pa == 0.0 || pb == 0.0) continue;
    if (n < max) roots[n] = bisect(c, deg, a, b);
    n++;
  }
  return n < max ? n : max;
}
