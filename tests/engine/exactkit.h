/* SPDX-License-Identifier: MPL-2.0 */
/* exactkit.h -- helpers for the exact-path tests (header only): rationals
 * from small integers, random rational QSS of revolution and motions with
 * a fixed seed, rational points of the unit sphere.
 */
#ifndef SWARF_TESTS_ENGINE_EXACTKIT_H
#define SWARF_TESTS_ENGINE_EXACTKIT_H

#include "envelope_exact.h"
#include "testkit.h"

/* Axes with rational length (Pythagorean quadruples). */
static const long ek_axes[][3] = {{2, 1, 2}, {1, 2, 2}, {2, 3, 6}, {1, 4, 8}, {2, 6, 9},
                                  {0, 3, 4}, {4, 4, 7}, {6, 2, 3}, {0, 0, 1}, {1, 0, 0}};

static inline long ek_int(tk_rng *r, long lo, long hi) {
  long v = lo + (long)tk_uniform(r, 0.0, (double)(hi - lo + 1));
  return v > hi ? hi : v;
}

/* p/q with |p| <= pmax, 1 <= q <= qmax. */
static inline void ek_rand(fmpq_t x, tk_rng *r, long pmax, long qmax) {
  fmpq_set_si(x, ek_int(r, -pmax, pmax), (ulong)ek_int(r, 1, qmax));
}

static inline void ek_vec_init(fmpq *x, int n) {
  for (int i = 0; i < n; i++)
    fmpq_init(x + i);
}

static inline void ek_vec_clear(fmpq *x, int n) {
  for (int i = 0; i < n; i++)
    fmpq_clear(x + i);
}

static inline void ek_vec_si(fmpq *x, const long *v, int n) {
  for (int i = 0; i < n; i++)
    fmpq_set_si(x + i, v[i], 1);
}

static inline void ek_vec_get_d(double *out, const fmpq *x, int n) {
  for (int i = 0; i < n; i++)
    out[i] = fmpq_get_d(x + i);
}

/* A random QSS of revolution (c = d = 0 unless offaxis) and rational motion
 * (axis from the table with random signs, tdot and B random). */
static inline void ek_random_case(tk_rng *r, fmpq *abcdef, swarf_xmotion *m, int offaxis) {
  fmpq w[3], td[3];
  fmpq_t B;
  int a = (int)ek_int(r, 0, (long)(sizeof ek_axes / sizeof ek_axes[0]) - 1);
  ek_vec_init(w, 3), ek_vec_init(td, 3), fmpq_init(B);
  for (int i = 0; i < 6; i++)
    ek_rand(abcdef + i, r, 5, 3);
  if (!offaxis) fmpq_zero(abcdef + 2), fmpq_zero(abcdef + 3);
  for (int i = 0; i < 3; i++) {
    int p = (a + i) % 3; /* rotate the axis' components too */
    fmpq_set_si(w + i, ek_axes[a][p] * (tk_uniform(r, 0, 1) < 0.5 ? -1 : 1), 1);
    ek_rand(td + i, r, 4, 3);
  }
  ek_rand(B, r, 7, 4);
  swarf_xmotion_set(m, w, td, B);
  ek_vec_clear(w, 3), ek_vec_clear(td, 3), fmpq_clear(B);
}

/* Rational point of the sphere: inverse stereographic image of (p, q). */
static inline void ek_sphere_point(fmpq N[3], const fmpq_t p, const fmpq_t q) {
  fmpq_t d;
  fmpq_init(d);
  fmpq_mul(d, p, p);
  fmpq_addmul(d, q, q);
  fmpq_mul_2exp(N + 0, p, 1);
  fmpq_mul_2exp(N + 1, q, 1);
  fmpq_sub_si(N + 2, d, 1);
  fmpq_add_si(d, d, 1);
  for (int k = 0; k < 3; k++)
    fmpq_div(N + k, N + k, d);
  fmpq_clear(d);
}

#endif
