/* SPDX-License-Identifier: MPL-2.0 */
/* envelope_exact.h -- the exact path of the envelope core (GMP/FLINT/arb).
 *
 * Role: the paper's characteristic curves in exact arithmetic, for rational
 * inputs (shared/paper/, shared/docs/ENVELOPE.md):
 *   - numbers a + b sqrt(r) of Q(sqrt r) and polynomials over that field;
 *   - QSS support functions with rational coefficients (eq. 12 and general
 *     trivariate quadratics), x_h(n) as polynomials (eq. 1-2);
 *   - rational rigid motions: rotation about an axis with rational direction
 *     and length by alpha with rational B = tan(alpha / 2), plus
 *     t(alpha) = alpha tdot; v = U^T tdot and omega exactly;
 *   - f over Q (eq. 11), the point P of Lemma 1, the ELM steps of section 4
 *     (cubic, R, pencil k, l, m, D(s)), the z-slice quartic Delta(z) and its
 *     real roots in [-1, 1] with certified (arb) enclosures.
 * Used by tools/ and tests/ only: engine.h stays free of FLINT types. Every
 * value that owns memory has an init/clear pair; the caller owns everything
 * passed in and out. No global state: thread-safe for distinct values.
 */
#ifndef SWARF_ENVELOPE_EXACT_H
#define SWARF_ENVELOPE_EXACT_H

#include <flint/fmpq.h>
#include <flint/fmpq_mpoly.h>
#include <flint/fmpq_poly.h>

#include <arb.h>

#include "swarf_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Q(sqrt r): a + b sqrt(r), r a squarefree integer (r = 1: b is 0) ---- */

typedef struct {
  fmpq_t a, b;
} swarf_qr;

SWARF_API void swarf_qr_init(swarf_qr *x);
SWARF_API void swarf_qr_clear(swarf_qr *x);
SWARF_API void swarf_qr_set(swarf_qr *z, const swarf_qr *x);
SWARF_API void swarf_qr_set_fmpq(swarf_qr *z, const fmpq_t a);
SWARF_API void swarf_qr_add(swarf_qr *z, const swarf_qr *x, const swarf_qr *y);
SWARF_API void swarf_qr_sub(swarf_qr *z, const swarf_qr *x, const swarf_qr *y);
SWARF_API void swarf_qr_mul(swarf_qr *z, const swarf_qr *x, const swarf_qr *y, const fmpz_t r);
SWARF_API void swarf_qr_mul_fmpq(swarf_qr *z, const swarf_qr *x, const fmpq_t c);
/* z = 1 / x; SWARF_ERR_ARG (z unchanged) when x = 0. */
SWARF_API swarf_status swarf_qr_inv(swarf_qr *z, const swarf_qr *x, const fmpz_t r);
SWARF_API int swarf_qr_is_zero(const swarf_qr *x);
/* Sign of a + b sqrt(r), decided exactly. */
SWARF_API int swarf_qr_sgn(const swarf_qr *x, const fmpz_t r);
SWARF_API double swarf_qr_get_d(const swarf_qr *x, const fmpz_t r);
/* "a + b*sqrt(r)" (or "a" when b = 0); free() the result. */
SWARF_API char *swarf_qr_get_str(const swarf_qr *x, const fmpz_t r);

/* Polynomials over Q(sqrt r): A(s) + B(s) sqrt(r). */
typedef struct {
  fmpq_poly_t a, b;
} swarf_qr_poly;

SWARF_API void swarf_qr_poly_init(swarf_qr_poly *p);
SWARF_API void swarf_qr_poly_clear(swarf_qr_poly *p);
SWARF_API void swarf_qr_poly_set(swarf_qr_poly *z, const swarf_qr_poly *p);
SWARF_API void swarf_qr_poly_add(swarf_qr_poly *z, const swarf_qr_poly *p, const swarf_qr_poly *q);
SWARF_API void swarf_qr_poly_sub(swarf_qr_poly *z, const swarf_qr_poly *p, const swarf_qr_poly *q);
SWARF_API void swarf_qr_poly_mul(swarf_qr_poly *z, const swarf_qr_poly *p, const swarf_qr_poly *q,
                                 const fmpz_t r);
SWARF_API void swarf_qr_poly_scale(swarf_qr_poly *z, const swarf_qr_poly *p, const swarf_qr *c,
                                   const fmpz_t r);
SWARF_API void swarf_qr_poly_get_coeff(swarf_qr *c, const swarf_qr_poly *p, slong i);
SWARF_API void swarf_qr_poly_set_coeff(swarf_qr_poly *p, slong i, const swarf_qr *c);
SWARF_API slong swarf_qr_poly_degree(const swarf_qr_poly *p);
SWARF_API int swarf_qr_poly_is_zero(const swarf_qr_poly *p);
SWARF_API double swarf_qr_poly_evaluate_d(const swarf_qr_poly *p, const fmpz_t r, double s);
/* Scale by a nonzero rational so that all coefficients lie in Z[sqrt r] with
 * content 1 and the leading coefficient's rational part (or, if 0, its sqrt r
 * part) is positive. */
SWARF_API void swarf_qr_poly_primitive(swarf_qr_poly *z, const swarf_qr_poly *p);
/* "c3*s^3 + (a + b*sqrt(r))*s^2 + ..." in the variable `var`; free() it. */
SWARF_API char *swarf_qr_poly_get_str(const swarf_qr_poly *p, const fmpz_t r, const char *var);

/* ---- Quadratic polynomials in n = (x, y, z) over Q ---------------------- */

/* Coefficients, in this order, of x^2 y^2 z^2 xy xz yz x y z 1. */
enum {
  SWARF_XX,
  SWARF_YY,
  SWARF_ZZ,
  SWARF_XY,
  SWARF_XZ,
  SWARF_YZ,
  SWARF_X,
  SWARF_Y,
  SWARF_Z,
  SWARF_ONE,
  SWARF_QUAD_TERMS
};

typedef struct {
  fmpq c[SWARF_QUAD_TERMS];
} swarf_xquad;

SWARF_API void swarf_xquad_init(swarf_xquad *q);
SWARF_API void swarf_xquad_clear(swarf_xquad *q);
/* QSS of revolution, eq. 12: a (x^2 + y^2) + b z^2 + c x + d y + e z + f. */
SWARF_API void swarf_xquad_set_revolution(swarf_xquad *q, const fmpq *abcdef);
/* Value at a point of Q(sqrt r)^3. */
SWARF_API void swarf_xquad_eval(swarf_qr *out, const swarf_xquad *q, const swarf_qr *n,
                                const fmpz_t r);
/* "15*x - 20*x*z + ..." (FLINT's pretty form); free() it. */
SWARF_API char *swarf_xquad_get_str(const swarf_xquad *q);
/* The QSS point x_h(n) = h n + grad h - (grad h . n) n (eq. 1-2) as three
 * cubic polynomials in x, y, z (ctx: 3 variables), without using n.n = 1. */
SWARF_API void swarf_xquad_point_mpoly(fmpq_mpoly_t X[3], const swarf_xquad *h,
                                       const fmpq_mpoly_ctx_t ctx);
/* Convexity of the QSS (principal radii h + Hess_S h >= 0 on the sphere),
 * decided exactly for a QSS of revolution: 2 min(a, b) - max(a, b) + f >= 0.
 * Returns 1 convex, 0 not, -1 when h is not of revolution (xy, xz, yz, or
 * unequal x^2, y^2 terms). */
SWARF_API int swarf_xquad_is_convex_revolution(const swarf_xquad *h);

/* ---- Rational rigid motions -------------------------------------------- */

/* U(alpha): rotation by alpha about the axis through the origin with
 * direction w (its length |w| must be rational), at unit angular speed;
 * t(alpha) = alpha tdot. At B = tan(alpha/2): U, v = U^T tdot, omega = w/|w|. */
typedef struct {
  fmpq U[9]; /* row-major */
  fmpq v[3], omega[3], tdot[3];
  fmpq_t B;
} swarf_xmotion;

SWARF_API void swarf_xmotion_init(swarf_xmotion *m);
SWARF_API void swarf_xmotion_clear(swarf_xmotion *m);
/* SWARF_ERR_ARG when w = 0 or |w| is irrational. */
SWARF_API swarf_status swarf_xmotion_set(swarf_xmotion *m, const fmpq *w, const fmpq *tdot,
                                         const fmpq_t B);

/* f(n) = (v + omega x grad h(n)) . n, eq. 11 (ENVELOPE.md: grad h x n order). */
SWARF_API void swarf_xquad_char(swarf_xquad *f, const swarf_xquad *h, const fmpq *v,
                                const fmpq *omega);

/* ---- The exact characteristic curve ------------------------------------- */

typedef enum {
  SWARF_ENV_CURVE,          /* a curve: components > 0, ELM done */
  SWARF_ENV_STILL,          /* v = omega = 0: no motion */
  SWARF_ENV_SPIN,           /* rotation about the QSS's own axis: no characteristic */
  SWARF_ENV_SPHERE,         /* f = 0: the whole sphere is characteristic */
  SWARF_ENV_EMPTY,          /* Delta < 0 on (-1, 1): empty Gauss image */
  SWARF_ENV_POINTS,         /* Delta <= 0, zero only at isolated points */
  SWARF_ENV_NOT_REVOLUTION, /* f is not linear per z-slice */
  SWARF_ENV_CIRCLES,        /* A = B = 0: f depends on z only; latitude circles at the
                             * roots of C (a translation along the axis: the equator) */
  SWARF_ENV_GREAT_CIRCLE    /* f is linear (a pure translation, or a sphere): the Gauss
                             * image is the great circle f = 0, no ELM needed */
} swarf_env_kind;

/* A real root of Delta in [-1, 1]: a certified enclosure (ball), the exact
 * value when it is rational, and its multiplicity (2: a tangential branch
 * point). */
typedef struct {
  arb_t z;
  int multiplicity;
  int rational; /* 1: q holds the exact root */
  fmpq_t q;
} swarf_env_root;

/* Everything the exact path finds, in the paper's order. */
typedef struct {
  swarf_env_kind kind;
  swarf_xquad f;          /* eq. 11 over Q */
  fmpq_poly_t A, B, C;    /* f = A(z) x + B(z) y + C(z) */
  fmpq_poly_t delta;      /* Delta(z) = (1 - z^2)(A^2 + B^2) - C^2 */
  fmpz_poly_t delta_prim; /* Delta scaled to a primitive integer polynomial */
  int delta_factors;      /* irreducible factors over Q (with multiplicity) */
  swarf_env_root *roots;  /* real roots in [-1, 1], ascending */
  int nroots;
  int ncomp;                 /* components: intervals of [-1, 1] where Delta > 0 */
  double *comp_lo, *comp_hi; /* their z ranges (rounded) */
  /* ELM (kind == SWARF_ENV_CURVE): */
  fmpz_t r; /* P, cubic, ... lie in Q(sqrt r) */
  fmpq_t z0;
  swarf_qr P[3], T[3];   /* the point of Lemma 1 and the curve tangent there */
  swarf_qr cubic[4][4];  /* cubic[i][j]: coefficient of xi^i eta^j */
  swarf_qr R[2];         /* tangent at P meets z = 0 */
  swarf_qr_poly k, l, m; /* t(s) = (k +- sqrt l) / m */
  swarf_qr_poly D;       /* m in the paper's normalization (eq. 22) */
} swarf_envelope_exact;

SWARF_API void swarf_envelope_exact_init(swarf_envelope_exact *E);
SWARF_API void swarf_envelope_exact_clear(swarf_envelope_exact *E);

/* Compute f, Delta and its roots, and (for a curve) the ELM steps, for the
 * support function h moving with v and omega (rational); E->kind names the
 * case. SWARF_ERR_MEMORY when out of memory, SWARF_ERR_ARG for a NULL
 * argument. */
SWARF_API swarf_status swarf_envelope_exact_compute(swarf_envelope_exact *E, const swarf_xquad *h,
                                                    const fmpq *v, const fmpq *omega);

/* The slice z (rational): the Gauss points in Q(sqrt r_z) (r_z returned in
 * rz), n[0] on branch s = +1, n[1] on s = -1 (Fact 2's formula). Returns 2,
 * 1 (tangent slice, Delta = 0), 0 (no real point, or A = B = 0). */
SWARF_API int swarf_envelope_exact_slice(const swarf_envelope_exact *E, const fmpq_t z, fmpz_t rz,
                                         swarf_qr n[2][3]);

/* A point of the ELM parameterization (double precision from the exact
 * coefficients): pencil parameter s, root sign (+1/-1). SWARF_ERR_ARG where
 * there is no point (l(s) < 0 or m(s) = 0, or no ELM). */
SWARF_API swarf_status swarf_envelope_exact_elm_point(const swarf_envelope_exact *E, double s,
                                                      int sign, double n[3]);

/* The back-projection of Theorem 2 checked as polynomial identities in
 * Q(sqrt r)[s, w] / (w^2 - l(s)): with Q(s) = R + (k + w)/m (1 - R_xi, s - R_eta),
 * n = N / Den (stereographic inverse from P), checks f_hom(N, Den) = 0 and
 * N.N = Den^2. Returns 1 when both hold, 0 when not, -1 when no ELM. */
SWARF_API int swarf_envelope_exact_check_elm(const swarf_envelope_exact *E);

/* A text report of everything above, as a person would check it against the
 * paper: one "name: value" per line. free() it. */
SWARF_API char *swarf_envelope_exact_report(const swarf_envelope_exact *E);

#ifdef __cplusplus
}
#endif
#endif
