/* SPDX-License-Identifier: MPL-2.0 */
/* charqss.c -- the fast path for the full revolution form of eq. 12,
 * h = a (x^2 + y^2) + b z^2 + c x + d y + e z + f: the linear part c x + d y
 * moves the body by p = (c, d, 0), so its characteristic curve is that of
 * swarf_qss {a, b, e, f} with v + omega x p, its points shifted by p.
 * Caller-owned values only.
 */
#include "engine_private.h"

swarf_status swarf_char_curve_compute_qss12(swarf_char_curve *cc, const double coef[6],
                                            const double t[3], const double U[9], const double v[3],
                                            const double omega[3], double tol) {
  swarf_qss q;
  double p[3], vp[3], tp[3];
  swarf_status n;
  if (cc == NULL || coef == NULL || t == NULL || U == NULL || v == NULL || omega == NULL)
    return SWARF_ERR_ARG;
  q.a = coef[0], q.b = coef[1], q.e = coef[4], q.f = coef[5];
  p[0] = coef[2], p[1] = coef[3], p[2] = 0.0;
  vp[0] = v[0] + omega[1] * p[2] - omega[2] * p[1];
  vp[1] = v[1] + omega[2] * p[0] - omega[0] * p[2];
  vp[2] = v[2] + omega[0] * p[1] - omega[1] * p[0];
  for (int i = 0; i < 3; i++)
    tp[i] = t[i] + U[3 * i] * p[0] + U[3 * i + 1] * p[1];
  n = swarf_char_curve_compute_qss(cc, &q, tp, U, vp, omega, tol);
  for (size_t i = 0; n == SWARF_OK && i < cc->len; i++)
    for (int k = 0; k < 2; k++)
      cc->pts[i].x[k] += p[k];
  return n;
}
