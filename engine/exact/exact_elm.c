/* SPDX-License-Identifier: MPL-2.0 */
/* exact_elm.c -- the Enhanced Levin's method of the paper's section 4 in
 * Q(sqrt r): the point P of Lemma 1 on a rational slice z0, the planar cubic
 * of the stereographic projection from P (eq. 14: the resultant of the two
 * linear-in-t polynomials f/t, g/t is F1 G0 - F0 G1), the point R where the
 * curve tangent at P meets z = 0, and the pencil through R (eq. 15-16) giving
 * t(s) = (k +- sqrt l) / m, with D(s) = m in the paper's normalization.
 *
 * Bivariate polynomials here are dense 4x4 arrays (degree <= 3 in each
 * variable), enough for a cubic and its pencil substitution. Everything is
 * written into the caller's swarf_envelope_exact.
 */
#include <flint/ulong_extras.h>

#include "exact_private.h"

typedef struct {
  swarf_qr c[4][4]; /* c[i][j]: coefficient of u^i w^j */
} bipoly;

static void bp_init(bipoly *p) {
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      swarf_qr_init(&p->c[i][j]);
}

static void bp_clear(bipoly *p) {
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      swarf_qr_clear(&p->c[i][j]);
}

static void bp_add(bipoly *z, const bipoly *p, const bipoly *q, int sign) {
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) {
      if (sign > 0)
        swarf_qr_add(&z->c[i][j], &p->c[i][j], &q->c[i][j]);
      else
        swarf_qr_sub(&z->c[i][j], &p->c[i][j], &q->c[i][j]);
    }
}

/* z += p q (terms beyond degree 3 in a variable must not occur). */
static void bp_addmul(bipoly *z, const bipoly *p, const bipoly *q, const fmpz_t r) {
  swarf_qr t;
  swarf_qr_init(&t);
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) {
      if (swarf_qr_is_zero(&p->c[i][j])) continue;
      for (int k = 0; i + k < 4; k++)
        for (int l = 0; j + l < 4; l++) {
          swarf_qr_mul(&t, &p->c[i][j], &q->c[k][l], r);
          swarf_qr_add(&z->c[i + k][j + l], &z->c[i + k][j + l], &t);
        }
    }
  swarf_qr_clear(&t);
}

static void bp_mul(bipoly *z, const bipoly *p, const bipoly *q, const fmpz_t r) {
  bipoly acc;
  bp_init(&acc);
  bp_addmul(&acc, p, q, r);
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      swarf_qr_set(&z->c[i][j], &acc.c[i][j]);
  bp_clear(&acc);
}

static void bp_scale(bipoly *z, const bipoly *p, const swarf_qr *c, const fmpz_t r) {
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      swarf_qr_mul(&z->c[i][j], &p->c[i][j], c, r);
}

/* Gradient of f at a point of Q(sqrt r)^3. */
static void quad_grad(swarf_qr g[3], const swarf_xquad *f, const swarf_qr *n, const fmpz_t r) {
  static const int sq[3] = {SWARF_XX, SWARF_YY, SWARF_ZZ}, lin[3] = {SWARF_X, SWARF_Y, SWARF_Z};
  static const int mix[3][3] = {
      {-1, SWARF_XY, SWARF_XZ}, {SWARF_XY, -1, SWARF_YZ}, {SWARF_XZ, SWARF_YZ, -1}};
  swarf_qr t;
  fmpq_t two;
  swarf_qr_init(&t);
  fmpq_init(two);
  for (int i = 0; i < 3; i++) {
    swarf_qr_set_fmpq(&g[i], f->c + lin[i]);
    for (int j = 0; j < 3; j++) {
      if (j == i) {
        fmpq_mul_2exp(two, f->c + sq[i], 1);
        swarf_qr_mul_fmpq(&t, n + j, two);
      } else {
        swarf_qr_mul_fmpq(&t, n + j, f->c + mix[i][j]);
      }
      swarf_qr_add(&g[i], &g[i], &t);
    }
  }
  swarf_qr_clear(&t);
  fmpq_clear(two);
}

/* The quadratic part of f applied to a vector of bipolys. */
static void quad_form(bipoly *out, const swarf_xquad *f, const bipoly u[3], const fmpz_t r) {
  static const int ti[6] = {SWARF_XX, SWARF_YY, SWARF_ZZ, SWARF_XY, SWARF_XZ, SWARF_YZ};
  static const int a[6] = {0, 1, 2, 0, 0, 1}, b[6] = {0, 1, 2, 1, 2, 2};
  bipoly t;
  swarf_qr c;
  bp_init(&t);
  swarf_qr_init(&c);
  for (int k = 0; k < 6; k++) {
    if (fmpq_is_zero(f->c + ti[k])) continue;
    bp_mul(&t, &u[a[k]], &u[b[k]], r);
    swarf_qr_set_fmpq(&c, f->c + ti[k]);
    bp_scale(&t, &t, &c, r);
    bp_add(out, out, &t, 1);
  }
  bp_clear(&t);
  swarf_qr_clear(&c);
}

/* The cubic F1 G0 - F0 G1 in (xi, eta), with u = Q - P. */
static void make_cubic(swarf_envelope_exact *E) {
  const fmpz *r = E->r;
  bipoly u[3], F0, F1, G0, G1, t, cub;
  swarf_qr g[3], two;
  for (int k = 0; k < 3; k++) {
    bp_init(&u[k]);
    swarf_qr_init(&g[k]);
    swarf_qr_sub(&u[k].c[0][0], &u[k].c[0][0], &E->P[k]);
  }
  fmpq_one(u[0].c[1][0].a);
  fmpq_one(u[1].c[0][1].a);
  bp_init(&F0), bp_init(&F1), bp_init(&G0), bp_init(&G1), bp_init(&t), bp_init(&cub);
  swarf_qr_init(&two);
  fmpq_set_si(two.a, 2, 1);
  quad_grad(g, &E->f, E->P, r);
  for (int k = 0; k < 3; k++) {
    bp_scale(&t, &u[k], &g[k], r);
    bp_add(&F0, &F0, &t, 1);
    bp_scale(&t, &u[k], &E->P[k], r);
    bp_scale(&t, &t, &two, r);
    bp_add(&G0, &G0, &t, 1);
    bp_addmul(&G1, &u[k], &u[k], r);
  }
  quad_form(&F1, &E->f, u, r);
  bp_addmul(&cub, &F1, &G0, r);
  bp_mul(&t, &F0, &G1, r);
  bp_add(&cub, &cub, &t, -1);
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      swarf_qr_set(&E->cubic[i][j], &cub.c[i][j]);
  for (int k = 0; k < 3; k++) {
    bp_clear(&u[k]);
    swarf_qr_clear(&g[k]);
  }
  bp_clear(&F0), bp_clear(&F1), bp_clear(&G0), bp_clear(&G1), bp_clear(&t), bp_clear(&cub);
  swarf_qr_clear(&two);
}

/* T = grad f(P) x P and R = P - (P_z / T_z) T. Returns -1 when T_z = 0. */
static int tangent_point(swarf_envelope_exact *E) {
  const fmpz *r = E->r;
  swarf_qr g[3], a, b, lam;
  int ok = 0;
  for (int k = 0; k < 3; k++)
    swarf_qr_init(&g[k]);
  swarf_qr_init(&a), swarf_qr_init(&b), swarf_qr_init(&lam);
  quad_grad(g, &E->f, E->P, r);
  for (int k = 0; k < 3; k++) {
    int i = (k + 1) % 3, j = (k + 2) % 3;
    swarf_qr_mul(&a, &g[i], &E->P[j], r);
    swarf_qr_mul(&b, &g[j], &E->P[i], r);
    swarf_qr_sub(&E->T[k], &a, &b);
  }
  if (swarf_qr_inv(&lam, &E->T[2], r) == SWARF_OK) {
    swarf_qr_mul(&lam, &lam, &E->P[2], r);
    for (int k = 0; k < 2; k++) {
      swarf_qr_mul(&a, &lam, &E->T[k], r);
      swarf_qr_sub(&E->R[k], &E->P[k], &a);
    }
  } else {
    ok = -1;
  }
  for (int k = 0; k < 3; k++)
    swarf_qr_clear(&g[k]);
  swarf_qr_clear(&a), swarf_qr_clear(&b), swarf_qr_clear(&lam);
  return ok;
}

/* Substitute xi = R0 + t (1 - R0), eta = R1 + t (s - R1) into the cubic:
 * c(t, s) = sum_i t^i c_i(s); c_0 = 0 since R is on the cubic. Sets k, l, m.
 * Returns -1 when R is not on the cubic or m = 0. */
static int pencil(swarf_envelope_exact *E) {
  const fmpz *r = E->r;
  bipoly xi, eta, xp[4], ep[4], acc, t;
  swarf_qr_poly c[4], tmp;
  int ok = 0;
  bp_init(&xi), bp_init(&eta), bp_init(&acc), bp_init(&t);
  swarf_qr_set(&xi.c[0][0], &E->R[0]);
  fmpq_one(xi.c[1][0].a);
  swarf_qr_sub(&xi.c[1][0], &xi.c[1][0], &E->R[0]);
  swarf_qr_set(&eta.c[0][0], &E->R[1]);
  swarf_qr_sub(&eta.c[1][0], &eta.c[1][0], &E->R[1]);
  fmpq_one(eta.c[1][1].a);
  for (int p = 0; p < 4; p++) {
    bp_init(&xp[p]), bp_init(&ep[p]);
    if (p == 0)
      fmpq_one(xp[0].c[0][0].a), fmpq_one(ep[0].c[0][0].a);
    else
      bp_mul(&xp[p], &xp[p - 1], &xi, r), bp_mul(&ep[p], &ep[p - 1], &eta, r);
  }
  for (int i = 0; i < 4; i++)
    for (int j = 0; i + j < 4; j++) {
      if (swarf_qr_is_zero(&E->cubic[i][j])) continue;
      bp_mul(&t, &xp[i], &ep[j], r);
      bp_scale(&t, &t, &E->cubic[i][j], r);
      bp_add(&acc, &acc, &t, 1);
    }
  for (int i = 0; i < 4; i++) {
    swarf_qr_poly_init(&c[i]);
    for (int j = 0; j < 4; j++)
      swarf_qr_poly_set_coeff(&c[i], j, &acc.c[i][j]);
  }
  swarf_qr_poly_init(&tmp);
  if (!swarf_qr_poly_is_zero(&c[0]) || swarf_qr_poly_is_zero(&c[3])) ok = -1;
  fmpq_poly_neg(E->k.a, c[2].a); /* k = -c2, l = c2^2 - 4 c1 c3, m = 2 c3 */
  fmpq_poly_neg(E->k.b, c[2].b);
  swarf_qr_poly_mul(&E->l, &c[2], &c[2], r);
  swarf_qr_poly_mul(&tmp, &c[1], &c[3], r);
  fmpq_poly_scalar_mul_si(tmp.a, tmp.a, 4);
  fmpq_poly_scalar_mul_si(tmp.b, tmp.b, 4);
  swarf_qr_poly_sub(&E->l, &E->l, &tmp);
  fmpq_poly_scalar_mul_si(E->m.a, c[3].a, 2);
  fmpq_poly_scalar_mul_si(E->m.b, c[3].b, 2);
  swarf_qr_poly_primitive(&E->D, &E->m);
  for (int i = 0; i < 4; i++)
    swarf_qr_poly_clear(&c[i]);
  swarf_qr_poly_clear(&tmp);
  for (int p = 0; p < 4; p++)
    bp_clear(&xp[p]), bp_clear(&ep[p]);
  bp_clear(&xi), bp_clear(&eta), bp_clear(&acc), bp_clear(&t);
  return ok;
}

/* Candidate slices z0: 1/2 first (the paper's choice), then p/q by growing q. */
static int next_z0(fmpq_t z0, int idx) {
  int n = 0;
  for (int q = 2; q <= 64; q++)
    for (int p = 1; p < q; p++)
      for (int sgn = 1; sgn >= -1; sgn -= 2) {
        if (n_gcd(p, q) != 1) continue;
        if (n++ == idx) {
          fmpq_set_si(z0, sgn * p, q);
          return 0;
        }
      }
  return -1;
}

/* Past the simple candidates: the middle of each component's z range. */
static int fallback_z0(fmpq_t z0, const swarf_envelope_exact *E, int idx) {
  arf_t t;
  if (idx >= E->ncomp) return -1;
  arf_init(t);
  arf_set_d(t, 0.5 * (E->comp_lo[idx] + E->comp_hi[idx]));
  arf_get_fmpq(z0, t);
  arf_clear(t);
  return 0;
}

int swarf_exact_elm(swarf_envelope_exact *E) {
  int simple = 1;
  for (int idx = 0;; idx++) {
    if (simple && next_z0(E->z0, idx) != 0) simple = 0, idx = 0;
    if (!simple && fallback_z0(E->z0, E, idx) != 0) break;
    if (fmpq_is_zero(E->z0)) continue;
    if (!swarf_exact_slice_point(E, E->z0, 1, E->r, E->P)) continue;
    if (tangent_point(E) != 0) continue;
    make_cubic(E);
    if (pencil(E) == 0) return 0;
  }
  return -1;
}
