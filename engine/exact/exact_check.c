/* SPDX-License-Identifier: MPL-2.0 */
/* exact_check.c -- points of the exact characteristic curve and the check
 * of Theorem 2's back-projection as polynomial identities.
 *
 * Slice points (Fact 2) are exact in Q(sqrt r_z). The identity check works
 * in the ring Q(sqrt r)[s][w] / (w^2 - l(s)): an element is p0(s) + p1(s) w.
 * The inverse stereographic projection from P of a planar point Q is the
 * reflection n = P - 2 (P.E) E / (E.E), E = Q - P; with Q = R + t d(s) and
 * t = (k + w) / m, E scaled by m is polynomial. Caller-owned values only.
 */
#include <math.h>

#include "exact_private.h"

int swarf_exact_slice_point(const swarf_envelope_exact *E, const fmpq_t z, int s, fmpz_t rz,
                            swarf_qr n[3]) {
  fmpq_t A, B, C, q, d, sq;
  int ok;
  fmpq_init(A), fmpq_init(B), fmpq_init(C), fmpq_init(q), fmpq_init(d), fmpq_init(sq);
  fmpq_poly_evaluate_fmpq(A, E->A, z);
  fmpq_poly_evaluate_fmpq(B, E->B, z);
  fmpq_poly_evaluate_fmpq(C, E->C, z);
  fmpq_poly_evaluate_fmpq(d, E->delta, z);
  fmpq_mul(q, A, A);
  fmpq_addmul(q, B, B);
  ok = !fmpq_is_zero(q) && fmpq_sgn(d) >= 0;
  if (ok) {
    swarf_exact_sqrt_split(rz, sq, d); /* sqrt(Delta) = sq sqrt(rz) */
    if (s < 0) fmpq_neg(sq, sq);
    fmpq_inv(q, q);
    /* x = (-A C + s B sqrt D) / q, y = (-B C - s A sqrt D) / q */
    fmpq_mul(n[0].a, A, C);
    fmpq_neg(n[0].a, n[0].a);
    fmpq_mul(n[0].b, B, sq);
    fmpq_mul(n[1].a, B, C);
    fmpq_neg(n[1].a, n[1].a);
    fmpq_mul(n[1].b, A, sq);
    fmpq_neg(n[1].b, n[1].b);
    for (int k = 0; k < 2; k++) {
      swarf_qr_mul_fmpq(&n[k], &n[k], q);
      if (fmpz_is_one(rz)) fmpq_add(n[k].a, n[k].a, n[k].b), fmpq_zero(n[k].b);
    }
    swarf_qr_set_fmpq(&n[2], z);
  }
  fmpq_clear(A), fmpq_clear(B), fmpq_clear(C), fmpq_clear(q), fmpq_clear(d), fmpq_clear(sq);
  return ok;
}

int swarf_envelope_exact_slice(const swarf_envelope_exact *E, const fmpq_t z, fmpz_t rz,
                               swarf_qr n[2][3]) {
  fmpq_t d;
  int sgn;
  if (E == NULL || E->kind == SWARF_ENV_NOT_REVOLUTION || E->kind == SWARF_ENV_STILL) return 0;
  fmpq_init(d);
  fmpq_poly_evaluate_fmpq(d, E->delta, z);
  sgn = fmpq_sgn(d);
  fmpq_clear(d);
  if (sgn < 0) return 0;
  if (!swarf_exact_slice_point(E, z, 1, rz, n[0])) return 0;
  swarf_exact_slice_point(E, z, -1, rz, n[1]);
  return sgn > 0 ? 2 : 1;
}

swarf_status swarf_envelope_exact_elm_point(const swarf_envelope_exact *E, double s, int sign,
                                            double n[3]) {
  const fmpz *r = E->r;
  double k, l, m, t, P[3], Q[3], e[3], pe = 0.0, ee = 0.0;
  if (E->kind != SWARF_ENV_CURVE) return SWARF_ERR_ARG;
  k = swarf_qr_poly_evaluate_d(&E->k, r, s);
  l = swarf_qr_poly_evaluate_d(&E->l, r, s);
  m = swarf_qr_poly_evaluate_d(&E->m, r, s);
  if (l < 0.0 || m == 0.0) return SWARF_ERR_ARG;
  t = (k + sign * sqrt(l)) / m;
  for (int i = 0; i < 3; i++)
    P[i] = swarf_qr_get_d(&E->P[i], r);
  Q[0] = swarf_qr_get_d(&E->R[0], r);
  Q[1] = swarf_qr_get_d(&E->R[1], r);
  Q[0] += t * (1.0 - Q[0]);
  Q[1] += t * (s - Q[1]);
  Q[2] = 0.0;
  for (int i = 0; i < 3; i++) {
    e[i] = Q[i] - P[i];
    pe += P[i] * e[i];
    ee += e[i] * e[i];
  }
  if (!(ee > 0.0)) return SWARF_ERR_ARG;
  for (int i = 0; i < 3; i++)
    n[i] = P[i] - 2.0 * pe / ee * e[i];
  return SWARF_OK;
}

/* ---- The ring Q(sqrt r)[s][w] / (w^2 - l) -------------------------------- */

typedef struct {
  swarf_qr_poly p0, p1;
} relt;

static void re_init(relt *x) {
  swarf_qr_poly_init(&x->p0);
  swarf_qr_poly_init(&x->p1);
}

static void re_clear(relt *x) {
  swarf_qr_poly_clear(&x->p0);
  swarf_qr_poly_clear(&x->p1);
}

static void re_add(relt *z, const relt *x, const relt *y) {
  swarf_qr_poly_add(&z->p0, &x->p0, &y->p0);
  swarf_qr_poly_add(&z->p1, &x->p1, &y->p1);
}

static void re_sub(relt *z, const relt *x, const relt *y) {
  swarf_qr_poly_sub(&z->p0, &x->p0, &y->p0);
  swarf_qr_poly_sub(&z->p1, &x->p1, &y->p1);
}

static void re_mul(relt *z, const relt *x, const relt *y, const swarf_qr_poly *l, const fmpz_t r) {
  swarf_qr_poly a, b, t;
  swarf_qr_poly_init(&a), swarf_qr_poly_init(&b), swarf_qr_poly_init(&t);
  swarf_qr_poly_mul(&a, &x->p0, &y->p0, r);
  swarf_qr_poly_mul(&t, &x->p1, &y->p1, r);
  swarf_qr_poly_mul(&t, &t, l, r);
  swarf_qr_poly_add(&a, &a, &t);
  swarf_qr_poly_mul(&b, &x->p0, &y->p1, r);
  swarf_qr_poly_mul(&t, &x->p1, &y->p0, r);
  swarf_qr_poly_add(&b, &b, &t);
  swarf_qr_poly_set(&z->p0, &a);
  swarf_qr_poly_set(&z->p1, &b);
  swarf_qr_poly_clear(&a), swarf_qr_poly_clear(&b), swarf_qr_poly_clear(&t);
}

static void re_scale(relt *z, const relt *x, const swarf_qr *c, const fmpz_t r) {
  swarf_qr_poly_scale(&z->p0, &x->p0, c, r);
  swarf_qr_poly_scale(&z->p1, &x->p1, c, r);
}

static int re_is_zero(const relt *x) {
  return swarf_qr_poly_is_zero(&x->p0) && swarf_qr_poly_is_zero(&x->p1);
}

/* E = m (R - P) + (k + w) d with d = (1 - R0, s - R1, 0) (R_z = 0). */
static void make_E(relt e[3], const swarf_envelope_exact *E) {
  const fmpz *r = E->r;
  swarf_qr c;
  swarf_qr_poly d;
  swarf_qr_init(&c);
  swarf_qr_poly_init(&d);
  for (int i = 0; i < 3; i++) {
    if (i < 2) {
      swarf_qr_sub(&c, &E->R[i], &E->P[i]);
    } else {
      swarf_qr_set(&c, &E->P[2]);
      fmpq_neg(c.a, c.a);
      fmpq_neg(c.b, c.b);
    }
    swarf_qr_poly_scale(&e[i].p0, &E->m, &c, r);
    if (i == 2) break;
    fmpq_poly_zero(d.a);
    fmpq_poly_zero(d.b);
    swarf_qr_set(&c, &E->R[i]);
    fmpq_neg(c.a, c.a);
    fmpq_neg(c.b, c.b);
    if (i == 0) fmpq_add_si(c.a, c.a, 1);
    swarf_qr_poly_set_coeff(&d, 0, &c);
    if (i == 1) fmpq_poly_set_coeff_si(d.a, 1, 1);
    swarf_qr_poly_set(&e[i].p1, &d);
    swarf_qr_poly_mul(&d, &d, &E->k, r);
    swarf_qr_poly_add(&e[i].p0, &e[i].p0, &d);
  }
  swarf_qr_clear(&c);
  swarf_qr_poly_clear(&d);
}

/* f_hom(N, Den) = f2(N) + f1(N) Den + f0 Den^2. */
static void f_hom(relt *out, const swarf_xquad *f, const relt N[3], const relt *den,
                  const swarf_qr_poly *l, const fmpz_t r) {
  static const int ti[6] = {SWARF_XX, SWARF_YY, SWARF_ZZ, SWARF_XY, SWARF_XZ, SWARF_YZ};
  static const int a[6] = {0, 1, 2, 0, 0, 1}, b[6] = {0, 1, 2, 1, 2, 2};
  relt t, lin;
  swarf_qr c;
  re_init(&t), re_init(&lin);
  swarf_qr_init(&c);
  re_sub(out, out, out);
  for (int k = 0; k < 6; k++) {
    swarf_qr_set_fmpq(&c, f->c + ti[k]);
    re_mul(&t, &N[a[k]], &N[b[k]], l, r);
    re_scale(&t, &t, &c, r);
    re_add(out, out, &t);
  }
  for (int k = 0; k < 3; k++) {
    swarf_qr_set_fmpq(&c, f->c + SWARF_X + k);
    re_scale(&t, &N[k], &c, r);
    re_add(&lin, &lin, &t);
  }
  swarf_qr_set_fmpq(&c, f->c + SWARF_ONE);
  re_scale(&t, den, &c, r);
  re_add(&lin, &lin, &t);
  re_mul(&t, &lin, den, l, r);
  re_add(out, out, &t);
  re_clear(&t), re_clear(&lin);
  swarf_qr_clear(&c);
}

int swarf_envelope_exact_check_elm(const swarf_envelope_exact *E) {
  const fmpz *r = E->r;
  relt e[3], N[3], den, pe, t, fh;
  swarf_qr two;
  int ok;
  if (E == NULL || E->kind != SWARF_ENV_CURVE) return -1;
  for (int i = 0; i < 3; i++)
    re_init(&e[i]), re_init(&N[i]);
  re_init(&den), re_init(&pe), re_init(&t), re_init(&fh);
  swarf_qr_init(&two);
  fmpq_set_si(two.a, 2, 1);
  make_E(e, E);
  for (int i = 0; i < 3; i++) {
    re_mul(&t, &e[i], &e[i], &E->l, r);
    re_add(&den, &den, &t);
    re_scale(&t, &e[i], &E->P[i], r);
    re_add(&pe, &pe, &t);
  }
  re_scale(&pe, &pe, &two, r);
  for (int i = 0; i < 3; i++) { /* N = P Den - 2 (P.E) E */
    re_scale(&N[i], &den, &E->P[i], r);
    re_mul(&t, &pe, &e[i], &E->l, r);
    re_sub(&N[i], &N[i], &t);
  }
  f_hom(&fh, &E->f, N, &den, &E->l, r);
  ok = re_is_zero(&fh);
  re_mul(&fh, &den, &den, &E->l, r); /* N.N - Den^2 */
  for (int i = 0; i < 3; i++) {
    re_mul(&t, &N[i], &N[i], &E->l, r);
    re_sub(&fh, &fh, &t);
  }
  ok = ok && re_is_zero(&fh) && !re_is_zero(&den);
  for (int i = 0; i < 3; i++)
    re_clear(&e[i]), re_clear(&N[i]);
  re_clear(&den), re_clear(&pe), re_clear(&t), re_clear(&fh);
  swarf_qr_clear(&two);
  return ok;
}
