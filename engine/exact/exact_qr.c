/* SPDX-License-Identifier: MPL-2.0 */
/* exact_qr.c -- arithmetic in Q(sqrt r) and polynomials over it.
 *
 * An element is a pair (a, b) of rationals meaning a + b sqrt(r); r is the
 * squarefree integer of the field, passed to the operations that need it
 * (mul, inv, sgn). With r = 1 (a rational point) callers keep b = 0. The
 * caller owns every value (init/clear); outputs may alias inputs.
 */
#define _POSIX_C_SOURCE 200809L /* strdup */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envelope_exact.h"

void swarf_qr_init(swarf_qr *x) {
  fmpq_init(x->a);
  fmpq_init(x->b);
}

void swarf_qr_clear(swarf_qr *x) {
  fmpq_clear(x->a);
  fmpq_clear(x->b);
}

void swarf_qr_set(swarf_qr *z, const swarf_qr *x) {
  fmpq_set(z->a, x->a);
  fmpq_set(z->b, x->b);
}

void swarf_qr_set_fmpq(swarf_qr *z, const fmpq_t a) {
  fmpq_set(z->a, a);
  fmpq_zero(z->b);
}

void swarf_qr_add(swarf_qr *z, const swarf_qr *x, const swarf_qr *y) {
  fmpq_add(z->a, x->a, y->a);
  fmpq_add(z->b, x->b, y->b);
}

void swarf_qr_sub(swarf_qr *z, const swarf_qr *x, const swarf_qr *y) {
  fmpq_sub(z->a, x->a, y->a);
  fmpq_sub(z->b, x->b, y->b);
}

void swarf_qr_mul(swarf_qr *z, const swarf_qr *x, const swarf_qr *y, const fmpz_t r) {
  fmpq_t a, b, t;
  fmpq_init(a);
  fmpq_init(b);
  fmpq_init(t);
  fmpq_mul(a, x->a, y->a);
  fmpq_mul(t, x->b, y->b);
  fmpq_mul_fmpz(t, t, r);
  fmpq_add(a, a, t);
  fmpq_mul(b, x->a, y->b);
  fmpq_mul(t, x->b, y->a);
  fmpq_add(b, b, t);
  fmpq_swap(z->a, a);
  fmpq_swap(z->b, b);
  fmpq_clear(a);
  fmpq_clear(b);
  fmpq_clear(t);
}

void swarf_qr_mul_fmpq(swarf_qr *z, const swarf_qr *x, const fmpq_t c) {
  fmpq_mul(z->a, x->a, c);
  fmpq_mul(z->b, x->b, c);
}

int swarf_qr_is_zero(const swarf_qr *x) {
  return fmpq_is_zero(x->a) && fmpq_is_zero(x->b);
}

/* a^2 - r b^2, the norm. */
static void qr_norm(fmpq_t out, const swarf_qr *x, const fmpz_t r) {
  fmpq_t t;
  fmpq_init(t);
  fmpq_mul(out, x->a, x->a);
  fmpq_mul(t, x->b, x->b);
  fmpq_mul_fmpz(t, t, r);
  fmpq_sub(out, out, t);
  fmpq_clear(t);
}

swarf_status swarf_qr_inv(swarf_qr *z, const swarf_qr *x, const fmpz_t r) {
  fmpq_t nrm;
  if (swarf_qr_is_zero(x)) return SWARF_ERR_ARG;
  fmpq_init(nrm);
  qr_norm(nrm, x, r);
  fmpq_inv(nrm, nrm);
  fmpq_mul(z->a, x->a, nrm);
  fmpq_mul(z->b, x->b, nrm);
  fmpq_neg(z->b, z->b);
  fmpq_clear(nrm);
  return SWARF_OK;
}

int swarf_qr_sgn(const swarf_qr *x, const fmpz_t r) {
  int sa = fmpq_sgn(x->a), sb = fmpq_sgn(x->b), c;
  fmpq_t nrm;
  if (sb == 0 || fmpz_is_zero(r)) return sa;
  if (sa == 0) return sb;
  if (sa == sb) return sa;
  fmpq_init(nrm);
  qr_norm(nrm, x, r); /* > 0: |a| dominates */
  c = fmpq_sgn(nrm);
  fmpq_clear(nrm);
  return c > 0 ? sa : c < 0 ? sb : 0;
}

double swarf_qr_get_d(const swarf_qr *x, const fmpz_t r) {
  return fmpq_get_d(x->a) + fmpq_get_d(x->b) * sqrt(fmpz_get_d(r));
}

char *swarf_qr_get_str(const swarf_qr *x, const fmpz_t r) {
  char *a = fmpq_get_str(NULL, 10, x->a), *b, *rs, *out;
  size_t n;
  if (fmpq_is_zero(x->b)) {
    out = strdup(a);
    flint_free(a);
    return out;
  }
  b = fmpq_get_str(NULL, 10, x->b);
  rs = fmpz_get_str(NULL, 10, r);
  n = strlen(a) + strlen(b) + strlen(rs) + 32;
  out = malloc(n);
  if (out != NULL) {
    if (fmpq_is_zero(x->a))
      snprintf(out, n, "%s*sqrt(%s)", b, rs);
    else
      snprintf(out, n, "%s %s %s*sqrt(%s)", a, b[0] == '-' ? "-" : "+", b[0] == '-' ? b + 1 : b,
               rs);
  }
  flint_free(a);
  flint_free(b);
  flint_free(rs);
  return out;
}
