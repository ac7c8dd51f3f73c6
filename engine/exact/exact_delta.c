/* SPDX-License-Identifier: MPL-2.0 */
/* exact_delta.c -- the z-slice quartic Delta(z) of ENVELOPE.md Fact 2 over Q
 * and its real roots in [-1, 1], isolated with certified arb enclosures: they
 * fix the number of components of the characteristic curve and where its
 * branches meet.
 *
 * Delta is factored over Z (FLINT); a linear factor gives an exact rational
 * root, every other irreducible factor goes to arb's certified complex root
 * isolation, refined until each real enclosure is disjoint from the others
 * and from z = +-1. Results are written into the caller's
 * swarf_envelope_exact, which owns them.
 */
#include <stdlib.h>

#include <arb_fmpz_poly.h>
#include <flint/fmpz_poly_factor.h>
#include <flint/ulong_extras.h>

#include "exact_private.h"

#define MAX_PREC 8192
#define SMALL_PRIMES 1000

/* Square factors are pulled out by trial division up to SMALL_PRIMES and a
 * final perfect-square test, never by full factorization (which can take
 * forever on the large integers of arbitrary rational slices): r is then
 * not a square, which is all the field arithmetic needs. */
void swarf_exact_sqrt_split(fmpz_t r, fmpq_t q, const fmpq_t x) {
  fmpz_t nd, sq, p, t;
  fmpz_init(nd), fmpz_init(sq), fmpz_init(p), fmpz_init(t);
  fmpz_mul(nd, fmpq_numref(x), fmpq_denref(x)); /* sqrt(n/d) = sqrt(n d) / d */
  fmpz_one(r);
  fmpz_one(sq);
  if (fmpz_is_zero(nd)) fmpz_zero(sq);
  for (ulong pr = 2; pr < SMALL_PRIMES && !fmpz_is_zero(nd) && !fmpz_is_one(nd);
       pr = n_nextprime(pr, 1)) {
    slong e;
    fmpz_set_ui(p, pr);
    e = fmpz_remove(nd, nd, p);
    if (e & 1) fmpz_mul_ui(r, r, pr);
    fmpz_pow_ui(t, p, (ulong)(e / 2));
    fmpz_mul(sq, sq, t);
  }
  if (!fmpz_is_zero(nd)) {
    if (fmpz_is_square(nd)) {
      fmpz_sqrt(t, nd);
      fmpz_mul(sq, sq, t);
    } else {
      fmpz_mul(r, r, nd);
    }
  }
  fmpq_set_fmpz_frac(q, sq, fmpq_denref(x));
  fmpz_clear(nd), fmpz_clear(sq), fmpz_clear(p), fmpz_clear(t);
}

int swarf_exact_slice_lines(swarf_envelope_exact *E) {
  const fmpq *c = E->f.c;
  if (!fmpq_is_zero(c + SWARF_XX) || !fmpq_is_zero(c + SWARF_YY) || !fmpq_is_zero(c + SWARF_XY))
    return -1;
  fmpq_poly_zero(E->A);
  fmpq_poly_zero(E->B);
  fmpq_poly_zero(E->C);
  fmpq_poly_set_coeff_fmpq(E->A, 0, c + SWARF_X);
  fmpq_poly_set_coeff_fmpq(E->A, 1, c + SWARF_XZ);
  fmpq_poly_set_coeff_fmpq(E->B, 0, c + SWARF_Y);
  fmpq_poly_set_coeff_fmpq(E->B, 1, c + SWARF_YZ);
  fmpq_poly_set_coeff_fmpq(E->C, 0, c + SWARF_ONE);
  fmpq_poly_set_coeff_fmpq(E->C, 1, c + SWARF_Z);
  fmpq_poly_set_coeff_fmpq(E->C, 2, c + SWARF_ZZ);
  return 0;
}

static void make_delta(swarf_envelope_exact *E) {
  fmpq_poly_t q, t;
  fmpq_poly_init(q);
  fmpq_poly_init(t);
  fmpq_poly_mul(q, E->A, E->A);
  fmpq_poly_mul(t, E->B, E->B);
  fmpq_poly_add(q, q, t);
  fmpq_poly_zero(t);
  fmpq_poly_set_coeff_si(t, 0, 1);
  fmpq_poly_set_coeff_si(t, 2, -1);
  fmpq_poly_mul(q, q, t);
  fmpq_poly_mul(t, E->C, E->C);
  fmpq_poly_sub(E->delta, q, t);
  fmpq_poly_get_numerator(E->delta_prim, E->delta);
  fmpz_poly_primitive_part(E->delta_prim, E->delta_prim);
  fmpq_poly_clear(q);
  fmpq_poly_clear(t);
}

static int push_root(swarf_envelope_exact *E, int mult) {
  void *mem = realloc(E->roots, (E->nroots + 1) * sizeof *E->roots);
  swarf_env_root *rt;
  if (mem == NULL) return -1;
  E->roots = mem;
  rt = E->roots + E->nroots++;
  arb_init(rt->z);
  fmpq_init(rt->q);
  rt->multiplicity = mult;
  rt->rational = 0;
  return 0;
}

/* Real roots of an irreducible factor of degree >= 2, in (-1, 1), at a
 * precision where the enclosures exclude +-1. Returns -1 on memory failure. */
static int factor_roots(swarf_envelope_exact *E, const fmpz_poly_t p, int mult, slong prec) {
  slong d = fmpz_poly_degree(p);
  acb_ptr z = _acb_vec_init(d);
  int ok = 0;
  for (;; prec *= 2) {
    int clear = 1;
    arb_fmpz_poly_complex_roots(z, p, 0, prec);
    for (slong i = 0; i < d && arb_is_zero(acb_imagref(z + i)); i++)
      if (arb_contains_si(acb_realref(z + i), 1) || arb_contains_si(acb_realref(z + i), -1))
        clear = 0;
    if (clear || prec >= MAX_PREC) break;
  }
  for (slong i = 0; i < d && arb_is_zero(acb_imagref(z + i)) && ok == 0; i++) {
    arb_srcptr x = acb_realref(z + i);
    arb_t one;
    arb_init(one);
    arb_set_si(one, 1);
    if (arb_lt(x, one)) {
      arb_neg(one, one);
      if (arb_gt(x, one)) {
        ok = push_root(E, mult);
        if (ok == 0) arb_set(E->roots[E->nroots - 1].z, x);
      }
    }
    arb_clear(one);
  }
  _acb_vec_clear(z, d);
  return ok;
}

static int linear_root(swarf_envelope_exact *E, const fmpz_poly_t p, int mult) {
  fmpq_t q;
  int ok = 0;
  fmpq_init(q);
  fmpq_set_fmpz_frac(q, p->coeffs + 0, p->coeffs + 1);
  fmpq_neg(q, q);
  if (fmpz_cmpabs(fmpq_numref(q), fmpq_denref(q)) <= 0) {
    ok = push_root(E, mult);
    if (ok == 0) {
      swarf_env_root *rt = E->roots + E->nroots - 1;
      rt->rational = 1;
      fmpq_set(rt->q, q);
      arb_set_fmpq(rt->z, q, 128);
    }
  }
  fmpq_clear(q);
  return ok;
}

static int by_mid(const void *a, const void *b) {
  const swarf_env_root *x = a, *y = b;
  return arf_cmp(arb_midref(x->z), arb_midref(y->z));
}

/* A rational strictly between roots i - 1 and i (i = 0: above -1; i = n: below 1). */
static void gap_point(const swarf_envelope_exact *E, int i, fmpq_t out) {
  fmpq_t lo, hi;
  arf_t t;
  fmpq_init(lo);
  fmpq_init(hi);
  arf_init(t);
  fmpq_set_si(lo, -1, 1);
  fmpq_set_si(hi, 1, 1);
  if (i > 0) {
    arb_get_ubound_arf(t, E->roots[i - 1].z, 256);
    arf_get_fmpq(lo, t);
  }
  if (i < E->nroots) {
    arb_get_lbound_arf(t, E->roots[i].z, 256);
    arf_get_fmpq(hi, t);
  }
  fmpq_add(out, lo, hi);
  fmpq_div_2exp(out, out, 1);
  fmpq_clear(lo);
  fmpq_clear(hi);
  arf_clear(t);
}

static double root_d(const swarf_envelope_exact *E, int i) {
  return i < 0 ? -1.0 : i >= E->nroots ? 1.0 : arf_get_d(arb_midref(E->roots[i].z), ARF_RND_NEAR);
}

/* Components: maximal runs of gaps where Delta > 0; two positive gaps in a
 * row meet at a root of even multiplicity (a tangential branch point) and
 * stay one connected component. */
static int components(swarf_envelope_exact *E) {
  fmpq_t z, val;
  int open = 0, err = 0;
  fmpq_init(z);
  fmpq_init(val);
  E->ncomp = 0;
  for (int i = 0; i <= E->nroots && !err; i++) {
    int pos;
    gap_point(E, i, z);
    fmpq_poly_evaluate_fmpq(val, E->delta, z);
    pos = fmpq_sgn(val) > 0;
    if (pos && !open) {
      double *lo = realloc(E->comp_lo, (E->ncomp + 1) * sizeof *lo), *hi;
      if (lo != NULL) E->comp_lo = lo;
      hi = lo ? realloc(E->comp_hi, (E->ncomp + 1) * sizeof *hi) : NULL;
      if (hi != NULL) E->comp_hi = hi;
      if (hi == NULL)
        err = -1;
      else
        E->comp_lo[E->ncomp++] = root_d(E, i - 1);
    }
    if (pos && !err) E->comp_hi[E->ncomp - 1] = root_d(E, i);
    open = pos;
  }
  fmpq_clear(z);
  fmpq_clear(val);
  return err;
}

static void drop_roots(swarf_envelope_exact *E) {
  for (int i = 0; i < E->nroots; i++) {
    arb_clear(E->roots[i].z);
    fmpq_clear(E->roots[i].q);
  }
  E->nroots = 0;
}

/* 1 when two sorted enclosures overlap (roots of different factors too close
 * for the precision). */
static int overlapping(const swarf_envelope_exact *E) {
  for (int i = 1; i < E->nroots; i++)
    if (arb_overlaps(E->roots[i - 1].z, E->roots[i].z)) return 1;
  return 0;
}

static int find_roots(swarf_envelope_exact *E, const fmpz_poly_factor_t fac, slong prec) {
  int err = 0;
  for (slong i = 0; i < fac->num && !err; i++) {
    const fmpz_poly_struct *p = fac->p + i;
    if (fmpz_poly_degree(p) == 1)
      err = linear_root(E, p, (int)fac->exp[i]);
    else if (fmpz_poly_degree(p) > 1)
      err = factor_roots(E, p, (int)fac->exp[i], prec);
  }
  if (err == 0) qsort(E->roots, E->nroots, sizeof *E->roots, by_mid);
  return err;
}

int swarf_exact_delta_roots(swarf_envelope_exact *E) {
  fmpz_poly_factor_t fac;
  int err = 0;
  make_delta(E);
  fmpz_poly_factor_init(fac);
  drop_roots(E);
  E->delta_factors = 0;
  if (fmpz_poly_is_zero(E->delta_prim)) {
    fmpz_poly_factor_clear(fac);
    return 0;
  }
  fmpz_poly_factor(fac, E->delta_prim);
  for (slong i = 0; i < fac->num; i++)
    E->delta_factors += (int)fac->exp[i];
  for (slong prec = 128;; prec *= 4) {
    err = find_roots(E, fac, prec);
    if (err || !overlapping(E) || prec >= MAX_PREC) break;
    drop_roots(E);
  }
  fmpz_poly_factor_clear(fac);
  if (err) return -1;
  return components(E);
}
