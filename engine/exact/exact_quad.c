/* SPDX-License-Identifier: MPL-2.0 */
/* exact_quad.c -- rational quadratic polynomials in n = (x, y, z): QSS
 * support functions (eq. 12 and general ones), their surface points
 * x_h(n) (eq. 1-2) as polynomials, convexity, and the characteristic
 * polynomial f of eq. 11.
 *
 * A swarf_xquad owns its ten coefficients (init/clear).
 */
#include <stdlib.h>

#include "envelope_exact.h"

static const char *const vars[] = {"x", "y", "z"};

/* Exponents of each term, in the order of the enum. */
static const int expo[SWARF_QUAD_TERMS][3] = {{2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {1, 1, 0},
                                              {1, 0, 1}, {0, 1, 1}, {1, 0, 0}, {0, 1, 0},
                                              {0, 0, 1}, {0, 0, 0}};

void swarf_xquad_init(swarf_xquad *q) {
  for (int i = 0; i < SWARF_QUAD_TERMS; i++)
    fmpq_init(q->c + i);
}

void swarf_xquad_clear(swarf_xquad *q) {
  for (int i = 0; i < SWARF_QUAD_TERMS; i++)
    fmpq_clear(q->c + i);
}

void swarf_xquad_set_revolution(swarf_xquad *q, const fmpq *abcdef) {
  for (int i = 0; i < SWARF_QUAD_TERMS; i++)
    fmpq_zero(q->c + i);
  fmpq_set(q->c + SWARF_XX, abcdef + 0);
  fmpq_set(q->c + SWARF_YY, abcdef + 0);
  fmpq_set(q->c + SWARF_ZZ, abcdef + 1);
  fmpq_set(q->c + SWARF_X, abcdef + 2);
  fmpq_set(q->c + SWARF_Y, abcdef + 3);
  fmpq_set(q->c + SWARF_Z, abcdef + 4);
  fmpq_set(q->c + SWARF_ONE, abcdef + 5);
}

void swarf_xquad_eval(swarf_qr *out, const swarf_xquad *q, const swarf_qr *n, const fmpz_t r) {
  swarf_qr acc, mono;
  swarf_qr_init(&acc);
  swarf_qr_init(&mono);
  for (int i = 0; i < SWARF_QUAD_TERMS; i++) {
    fmpq_one(mono.a);
    fmpq_zero(mono.b);
    for (int k = 0; k < 3; k++)
      for (int e = 0; e < expo[i][k]; e++)
        swarf_qr_mul(&mono, &mono, n + k, r);
    swarf_qr_mul_fmpq(&mono, &mono, q->c + i);
    swarf_qr_add(&acc, &acc, &mono);
  }
  swarf_qr_set(out, &acc);
  swarf_qr_clear(&acc);
  swarf_qr_clear(&mono);
}

/* q as a FLINT multivariate polynomial in x, y, z. */
static void to_mpoly(fmpq_mpoly_t p, const swarf_xquad *q, const fmpq_mpoly_ctx_t ctx) {
  fmpq_mpoly_zero(p, ctx);
  for (int i = 0; i < SWARF_QUAD_TERMS; i++) {
    ulong e[3] = {expo[i][0], expo[i][1], expo[i][2]};
    fmpq_mpoly_set_coeff_fmpq_ui(p, q->c + i, e, ctx);
  }
}

char *swarf_xquad_get_str(const swarf_xquad *q) {
  fmpq_mpoly_ctx_t ctx;
  fmpq_mpoly_t p;
  char *s;
  fmpq_mpoly_ctx_init(ctx, 3, ORD_DEGLEX);
  fmpq_mpoly_init(p, ctx);
  to_mpoly(p, q, ctx);
  s = fmpq_mpoly_get_str_pretty(p, (const char **)vars, ctx);
  fmpq_mpoly_clear(p, ctx);
  fmpq_mpoly_ctx_clear(ctx);
  return s;
}

void swarf_xquad_point_mpoly(fmpq_mpoly_t X[3], const swarf_xquad *h, const fmpq_mpoly_ctx_t ctx) {
  fmpq_mpoly_t hp, g[3], n[3], gn, t;
  fmpq_mpoly_init(hp, ctx);
  fmpq_mpoly_init(gn, ctx);
  fmpq_mpoly_init(t, ctx);
  to_mpoly(hp, h, ctx);
  for (int k = 0; k < 3; k++) {
    fmpq_mpoly_init(g[k], ctx);
    fmpq_mpoly_init(n[k], ctx);
    fmpq_mpoly_gen(n[k], k, ctx);
    fmpq_mpoly_derivative(g[k], hp, k, ctx);
    fmpq_mpoly_mul(t, g[k], n[k], ctx);
    fmpq_mpoly_add(gn, gn, t, ctx);
  }
  for (int k = 0; k < 3; k++) { /* h n + grad h - (grad h . n) n */
    fmpq_mpoly_sub(t, hp, gn, ctx);
    fmpq_mpoly_mul(t, t, n[k], ctx);
    fmpq_mpoly_add(X[k], t, g[k], ctx);
  }
  for (int k = 0; k < 3; k++) {
    fmpq_mpoly_clear(g[k], ctx);
    fmpq_mpoly_clear(n[k], ctx);
  }
  fmpq_mpoly_clear(hp, ctx);
  fmpq_mpoly_clear(gn, ctx);
  fmpq_mpoly_clear(t, ctx);
}

/* The radii matrix is 2 M|_T + (c0 - n.M n) I_T; its minimum over the sphere
 * is c0 + 2 m_min - m_max for the eigenvalues of M (diag(a, a, b) here). */
int swarf_xquad_is_convex_revolution(const swarf_xquad *h) {
  const fmpq *c = h->c;
  fmpq_t t;
  int ok;
  if (!fmpq_is_zero(c + SWARF_XY) || !fmpq_is_zero(c + SWARF_XZ) || !fmpq_is_zero(c + SWARF_YZ) ||
      !fmpq_equal(c + SWARF_XX, c + SWARF_YY))
    return -1;
  fmpq_init(t);
  if (fmpq_cmp(c + SWARF_XX, c + SWARF_ZZ) <= 0) {
    fmpq_mul_2exp(t, c + SWARF_XX, 1);
    fmpq_sub(t, t, c + SWARF_ZZ);
  } else {
    fmpq_mul_2exp(t, c + SWARF_ZZ, 1);
    fmpq_sub(t, t, c + SWARF_XX);
  }
  fmpq_add(t, t, c + SWARF_ONE);
  ok = fmpq_sgn(t) >= 0;
  fmpq_clear(t);
  return ok;
}

/* f = v.n + omega . (grad h x n), grad h = (2 xx x + xy y + xz z + x1, ...).
 * Collects the coefficient of each monomial of (grad h x n) . omega. */
void swarf_xquad_char(swarf_xquad *f, const swarf_xquad *h, const fmpq *v, const fmpq *omega) {
  /* grad h as a 3x4 matrix G: row i = d h / d n_i = sum_j G[i][j] n_j + G[i][3]. */
  fmpq_t G[3][4], t;
  const fmpq *c = h->c;
  fmpq_init(t);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 4; j++)
      fmpq_init(G[i][j]);
  fmpq_mul_2exp(G[0][0], c + SWARF_XX, 1);
  fmpq_mul_2exp(G[1][1], c + SWARF_YY, 1);
  fmpq_mul_2exp(G[2][2], c + SWARF_ZZ, 1);
  fmpq_set(G[0][1], c + SWARF_XY);
  fmpq_set(G[1][0], c + SWARF_XY);
  fmpq_set(G[0][2], c + SWARF_XZ);
  fmpq_set(G[2][0], c + SWARF_XZ);
  fmpq_set(G[1][2], c + SWARF_YZ);
  fmpq_set(G[2][1], c + SWARF_YZ);
  fmpq_set(G[0][3], c + SWARF_X);
  fmpq_set(G[1][3], c + SWARF_Y);
  fmpq_set(G[2][3], c + SWARF_Z);
  for (int i = 0; i < SWARF_QUAD_TERMS; i++)
    fmpq_zero(f->c + i);
  for (int k = 0; k < 3; k++)
    fmpq_set(f->c + SWARF_X + k, v + k);
  /* (g x n) . omega = sum over (i, j, l) cyclic of omega_l (g_i n_j - g_j n_i). */
  for (int l = 0; l < 3; l++) {
    int i = (l + 1) % 3, j = (l + 2) % 3;
    for (int src = 0; src < 4; src++) { /* term G[i][src] n_src n_j - G[j][src] n_src n_i */
      for (int side = 0; side < 2; side++) {
        int gi = side ? j : i, nj = side ? i : j;
        static const int pair[3][3] = {{SWARF_XX, SWARF_XY, SWARF_XZ},
                                       {SWARF_XY, SWARF_YY, SWARF_YZ},
                                       {SWARF_XZ, SWARF_YZ, SWARF_ZZ}};
        int term = src == 3 ? SWARF_X + nj : pair[src][nj];
        fmpq_mul(t, G[gi][src], omega + l);
        if (side)
          fmpq_sub(f->c + term, f->c + term, t);
        else
          fmpq_add(f->c + term, f->c + term, t);
      }
    }
  }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 4; j++)
      fmpq_clear(G[i][j]);
  fmpq_clear(t);
}
