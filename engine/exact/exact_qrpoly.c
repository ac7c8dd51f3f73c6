/* SPDX-License-Identifier: MPL-2.0 */
/* exact_qrpoly.c -- polynomials over Q(sqrt r): A(s) + B(s) sqrt(r).
 *
 * A pair of FLINT rational polynomials; products fold sqrt(r)^2 = r. The
 * caller owns every value (init/clear); outputs may alias inputs.
 */
#define _POSIX_C_SOURCE 200809L /* strdup */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envelope_exact.h"

void swarf_qr_poly_init(swarf_qr_poly *p) {
  fmpq_poly_init(p->a);
  fmpq_poly_init(p->b);
}

void swarf_qr_poly_clear(swarf_qr_poly *p) {
  fmpq_poly_clear(p->a);
  fmpq_poly_clear(p->b);
}

void swarf_qr_poly_set(swarf_qr_poly *z, const swarf_qr_poly *p) {
  fmpq_poly_set(z->a, p->a);
  fmpq_poly_set(z->b, p->b);
}

void swarf_qr_poly_add(swarf_qr_poly *z, const swarf_qr_poly *p, const swarf_qr_poly *q) {
  fmpq_poly_add(z->a, p->a, q->a);
  fmpq_poly_add(z->b, p->b, q->b);
}

void swarf_qr_poly_sub(swarf_qr_poly *z, const swarf_qr_poly *p, const swarf_qr_poly *q) {
  fmpq_poly_sub(z->a, p->a, q->a);
  fmpq_poly_sub(z->b, p->b, q->b);
}

void swarf_qr_poly_mul(swarf_qr_poly *z, const swarf_qr_poly *p, const swarf_qr_poly *q,
                       const fmpz_t r) {
  fmpq_poly_t a, b, t;
  fmpq_poly_init(a);
  fmpq_poly_init(b);
  fmpq_poly_init(t);
  fmpq_poly_mul(a, p->a, q->a);
  fmpq_poly_mul(t, p->b, q->b);
  fmpq_poly_scalar_mul_fmpz(t, t, r);
  fmpq_poly_add(a, a, t);
  fmpq_poly_mul(b, p->a, q->b);
  fmpq_poly_mul(t, p->b, q->a);
  fmpq_poly_add(b, b, t);
  fmpq_poly_swap(z->a, a);
  fmpq_poly_swap(z->b, b);
  fmpq_poly_clear(a);
  fmpq_poly_clear(b);
  fmpq_poly_clear(t);
}

void swarf_qr_poly_scale(swarf_qr_poly *z, const swarf_qr_poly *p, const swarf_qr *c,
                         const fmpz_t r) {
  swarf_qr_poly k;
  swarf_qr_poly_init(&k);
  fmpq_poly_set_fmpq(k.a, c->a);
  fmpq_poly_set_fmpq(k.b, c->b);
  swarf_qr_poly_mul(z, p, &k, r);
  swarf_qr_poly_clear(&k);
}

void swarf_qr_poly_get_coeff(swarf_qr *c, const swarf_qr_poly *p, slong i) {
  fmpq_poly_get_coeff_fmpq(c->a, p->a, i);
  fmpq_poly_get_coeff_fmpq(c->b, p->b, i);
}

void swarf_qr_poly_set_coeff(swarf_qr_poly *p, slong i, const swarf_qr *c) {
  fmpq_poly_set_coeff_fmpq(p->a, i, c->a);
  fmpq_poly_set_coeff_fmpq(p->b, i, c->b);
}

slong swarf_qr_poly_degree(const swarf_qr_poly *p) {
  slong da = fmpq_poly_degree(p->a), db = fmpq_poly_degree(p->b);
  return da > db ? da : db;
}

int swarf_qr_poly_is_zero(const swarf_qr_poly *p) {
  return fmpq_poly_is_zero(p->a) && fmpq_poly_is_zero(p->b);
}

double swarf_qr_poly_evaluate_d(const swarf_qr_poly *p, const fmpz_t r, double s) {
  double a = 0.0, b = 0.0;
  fmpq_t c;
  fmpq_init(c);
  for (slong i = swarf_qr_poly_degree(p); i >= 0; i--) {
    fmpq_poly_get_coeff_fmpq(c, p->a, i);
    a = a * s + fmpq_get_d(c);
    fmpq_poly_get_coeff_fmpq(c, p->b, i);
    b = b * s + fmpq_get_d(c);
  }
  fmpq_clear(c);
  return a + b * sqrt(fmpz_get_d(r));
}

/* The rational c with p / c primitive in Z[sqrt r][s]: lcm of denominators
 * over gcd of numerators, signed by the leading coefficient. */
void swarf_qr_poly_primitive(swarf_qr_poly *z, const swarf_qr_poly *p) {
  fmpz_t g, l, t;
  fmpq_t c;
  slong d = swarf_qr_poly_degree(p);
  int sign;
  if (d < 0) {
    swarf_qr_poly_set(z, p);
    return;
  }
  fmpz_init(g);
  fmpz_init(l);
  fmpz_init(t);
  fmpq_init(c);
  fmpz_one(l);
  for (int part = 0; part < 2; part++) {
    const fmpq_poly_struct *q = part ? p->b : p->a;
    fmpq_poly_content(c, q);
    fmpz_gcd(g, g, fmpq_numref(c));
    fmpz_lcm(l, l, fmpq_denref(c));
  }
  fmpq_poly_get_coeff_fmpq(c, p->a, d);
  sign = fmpq_sgn(c);
  if (sign == 0) {
    fmpq_poly_get_coeff_fmpq(c, p->b, d);
    sign = fmpq_sgn(c);
  }
  fmpq_set_fmpz_frac(c, l, g);
  if (sign < 0) fmpq_neg(c, c);
  fmpq_poly_scalar_mul_fmpq(z->a, p->a, c);
  fmpq_poly_scalar_mul_fmpq(z->b, p->b, c);
  fmpz_clear(g);
  fmpz_clear(l);
  fmpz_clear(t);
  fmpq_clear(c);
}

/* Append src to the growing string *buf (size *cap); returns -1 when out of memory. */
static int append(char **buf, size_t *len, size_t *cap, const char *src) {
  size_t n = strlen(src);
  if (*len + n + 1 > *cap) {
    size_t cap2 = 2 * (*len + n + 1);
    char *mem = realloc(*buf, cap2);
    if (mem == NULL) return -1;
    *buf = mem;
    *cap = cap2;
  }
  memcpy(*buf + *len, src, n + 1);
  *len += n;
  return 0;
}

char *swarf_qr_poly_get_str(const swarf_qr_poly *p, const fmpz_t r, const char *var) {
  char *buf = NULL, mono[64];
  size_t len = 0, cap = 0;
  int first = 1, err = append(&buf, &len, &cap, "");
  swarf_qr c;
  swarf_qr_init(&c);
  for (slong i = swarf_qr_poly_degree(p); i >= 0 && !err; i--) {
    char *cs;
    int paren;
    swarf_qr_poly_get_coeff(&c, p, i);
    if (swarf_qr_is_zero(&c)) continue;
    cs = swarf_qr_get_str(&c, r);
    if (cs == NULL) {
      err = 1;
      break;
    }
    paren = !fmpq_is_zero(c.a) && !fmpq_is_zero(c.b);
    if (!first) err |= append(&buf, &len, &cap, " + ");
    err |= append(&buf, &len, &cap, paren ? "(" : "");
    err |= append(&buf, &len, &cap, cs);
    err |= append(&buf, &len, &cap, paren ? ")" : "");
    if (i > 0) {
      snprintf(mono, sizeof mono, i > 1 ? "*%s^%ld" : "*%s", var, (long)i);
      err |= append(&buf, &len, &cap, mono);
    }
    free(cs);
    first = 0;
  }
  if (!err && first) err = append(&buf, &len, &cap, "0");
  swarf_qr_clear(&c);
  if (err) {
    free(buf);
    return NULL;
  }
  return buf;
}
