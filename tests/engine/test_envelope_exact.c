/* SPDX-License-Identifier: MPL-2.0 */
/* test_envelope_exact.c -- the exact path against the paper's printed
 * numbers (Examples 1 and 2) and exact properties on random rational
 * inputs (fixed seed): slice points satisfy f = g = 0 exactly, the ELM
 * back-projection is a polynomial identity, dH/dalpha = f (ENVELOPE.md
 * Fact 1) computed from h and U alone, convexity against sampling, and the
 * sign of a + b sqrt r against e-antic's embedded number fields.
 */
#include <stdlib.h>
#include <string.h>

#include <e-antic/renf_elem.h>

#include "check.h"
#include "exactkit.h"

static const long ex2_h[6] = {1, -1, 0, 0, 0, 0}, ex2_w[3] = {2, 1, 2}, ex2_td[3] = {1, 1, 0};

/* Set E from eq. 12 coefficients, axis, tdot and B = bn/bd. */
static void setup(swarf_envelope_exact *E, const long h6[6], const long w3[3], const long td3[3],
                  long bn, long bd) {
  fmpq h[6], w[3], td[3];
  fmpq_t B;
  swarf_xquad q;
  swarf_xmotion m;
  ek_vec_init(h, 6), ek_vec_init(w, 3), ek_vec_init(td, 3), fmpq_init(B);
  ek_vec_si(h, h6, 6), ek_vec_si(w, w3, 3), ek_vec_si(td, td3, 3);
  fmpq_set_si(B, bn, (ulong)bd);
  swarf_xquad_init(&q);
  swarf_xquad_set_revolution(&q, h);
  swarf_xmotion_init(&m);
  CHECK(swarf_xmotion_set(&m, w, td, B) == 0, "motion");
  CHECK(swarf_envelope_exact_compute(E, &q, m.v, m.omega) == 0, "compute");
  swarf_xmotion_clear(&m);
  swarf_xquad_clear(&q);
  ek_vec_clear(h, 6), ek_vec_clear(w, 3), ek_vec_clear(td, 3), fmpq_clear(B);
}

static int qr_is(const swarf_qr *x, const char *a, const char *b) {
  fmpq_t qa, qb;
  int ok;
  fmpq_init(qa), fmpq_init(qb);
  fmpq_set_str(qa, a, 10), fmpq_set_str(qb, b, 10);
  ok = fmpq_equal(x->a, qa) && fmpq_equal(x->b, qb);
  fmpq_clear(qa), fmpq_clear(qb);
  return ok;
}

/* Eq. 4 as polynomial identities (no use of n.n = 1), and convexity. */
static void test_example1(void) {
  static const char *eq4[2][3] = {
      {"-x^3-x*y^2-3/2*x*z^2+2*x", "-y*x^2-y^3-3/2*y*z^2+2*y", "-z*x^2-z*y^2-3/2*z^3+3*z"},
      {"-x^3-x*y^2+x*z^2+2*x", "-y*x^2-y^3+y*z^2+2*y", "-z*x^2-z*y^2+z^3-2*z"}};
  static const long h[2][6] = {{2, 3, 0, 0, 0, 0}, {1, -1, 0, 0, 0, 0}}; /* halves for [0] */
  const char *vars[] = {"x", "y", "z"};
  fmpq_mpoly_ctx_t ctx;
  fmpq_mpoly_ctx_init(ctx, 3, ORD_DEGLEX);
  for (int e = 0; e < 2; e++) {
    fmpq c[6];
    swarf_xquad q;
    fmpq_mpoly_t X[3], want;
    ek_vec_init(c, 6);
    for (int i = 0; i < 6; i++)
      fmpq_set_si(c + i, h[e][i], e == 0 ? 2 : 1);
    swarf_xquad_init(&q);
    swarf_xquad_set_revolution(&q, c);
    fmpq_mpoly_init(want, ctx);
    for (int k = 0; k < 3; k++) {
      fmpq_mpoly_init(X[k], ctx);
      fmpq_mpoly_set_str_pretty(want, eq4[e][k], vars, ctx);
    }
    swarf_xquad_point_mpoly(X, &q, ctx);
    for (int k = 0; k < 3; k++) {
      fmpq_mpoly_set_str_pretty(want, eq4[e][k], vars, ctx);
      CHECK(fmpq_mpoly_equal(X[k], want, ctx), "Example 1 surface %d, coordinate %d", e + 1, k);
      fmpq_mpoly_clear(X[k], ctx);
    }
    CHECK(swarf_xquad_is_convex_revolution(&q) == (e == 0), "Example 1 surface %d convexity",
          e + 1);
    fmpq_mpoly_clear(want, ctx);
    swarf_xquad_clear(&q);
    ek_vec_clear(c, 6);
  }
  fmpq_mpoly_ctx_clear(ctx);
}

static void test_example2(void) {
  static const char *D[4][2] = {{"24121304410", "10293044615"},
                                {"46260368554", "4537170456"},
                                {"7806587880", "7828867480"},
                                {"5032323912", "0"}};
  static const long eq19[SWARF_QUAD_TERMS] = {0, 0, 0, 0, -20, 40, 15, -9, 12, 0};
  static const long delta[5] = {-153, 660, -775, -660, 1000};
  swarf_envelope_exact E;
  fmpq_t ratio, t;
  swarf_qr c;
  swarf_envelope_exact_init(&E);
  fmpq_init(ratio), fmpq_init(t);
  swarf_qr_init(&c);
  setup(&E, ex2_h, ex2_w, ex2_td, 2, 1);
  CHECK(E.kind == SWARF_ENV_CURVE, "a curve (kind %d)", E.kind);
  fmpq_div_fmpz(ratio, E.f.c + SWARF_X, (fmpz_t){15}); /* eq. 19 up to a rational factor */
  for (int i = 0; i < SWARF_QUAD_TERMS; i++) {
    fmpq_set_si(t, eq19[i], 1);
    fmpq_mul(t, t, ratio);
    CHECK(fmpq_equal(t, E.f.c + i), "eq. 19 term %d", i);
  }
  CHECK(fmpz_equal_si(E.r, 6), "Q(sqrt 6)");
  CHECK(fmpz_is_one(fmpq_numref(E.z0)) && fmpz_equal_si(fmpq_denref(E.z0), 2), "z0 = 1/2");
  CHECK(qr_is(&E.P[0], "-15/73", "77/292") && qr_is(&E.P[1], "-33/73", "-35/292") &&
            qr_is(&E.P[2], "1/2", "0"),
        "eq. 20");
  CHECK(swarf_qr_poly_degree(&E.k) == 2 && swarf_qr_poly_degree(&E.l) == 4 &&
            swarf_qr_poly_degree(&E.m) == 3,
        "deg k, l, m = 2, 4, 3");
  for (int i = 0; i < 4; i++) {
    swarf_qr_poly_get_coeff(&c, &E.D, i);
    CHECK(qr_is(&c, D[i][0], D[i][1]), "eq. 22, coefficient of s^%d", i);
  }
  for (int i = 0; i < 5; i++)
    CHECK(fmpz_equal_si(E.delta_prim->coeffs + i, delta[i]), "Delta %d", i);
  CHECK(E.delta_factors == 1, "Delta irreducible over Q");
  CHECK(E.nroots == 2 && E.ncomp == 1, "two branch points, one component");
  if (E.nroots == 2) {
    CHECK_NEAR(arf_get_d(arb_midref(E.roots[0].z), ARF_RND_NEAR), -0.980159130274109, 1e-14, "z1");
    CHECK_NEAR(arf_get_d(arb_midref(E.roots[1].z), ARF_RND_NEAR), 0.918957355604119, 1e-14, "z2");
    CHECK(mag_cmp_2exp_si(arb_radref(E.roots[0].z), -100) < 0, "z1 certified tightly");
  }
  CHECK(swarf_envelope_exact_check_elm(&E) == 1, "Theorem 2 back-projection is an identity");
  swarf_qr_clear(&c);
  fmpq_clear(ratio), fmpq_clear(t);
  swarf_envelope_exact_clear(&E);
}

/* ENVELOPE.md: 3(1+B^2) f = x(-4B^2 z + B^2 + 4B - 4z + 3) + y(8B^2 z - B^2 - 4B + 8z + 3)
 * + 2Bz(2B - 1), for any B. */
static void test_example2_any_B(void) {
  for (long bn = -5; bn <= 5; bn++) {
    swarf_envelope_exact E;
    fmpq_t B, s, want;
    long bd = 3;
    swarf_envelope_exact_init(&E);
    fmpq_init(B), fmpq_init(s), fmpq_init(want);
    setup(&E, ex2_h, ex2_w, ex2_td, bn, bd);
    fmpq_set_si(B, bn, bd);
    fmpq_mul(s, B, B);
    fmpq_add_si(s, s, 1);
    fmpq_mul_si(s, s, 3); /* 3 (1 + B^2) */
    {
      fmpq_t B2;
      const fmpq *c = E.f.c;
      fmpq_init(B2);
      fmpq_mul(B2, B, B);
#define COEF(term, expr)                                                                           \
  do {                                                                                             \
    fmpq_mul(want, c + term, s);                                                                   \
    CHECK(fmpq_equal(want, expr), "B = %ld/3, term %d", bn, term);                                 \
  } while (0)
      fmpq_t e;
      fmpq_init(e);
      fmpq_mul_si(e, B2, -4), fmpq_sub_si(e, e, 4); /* xz: -4B^2 - 4 */
      COEF(SWARF_XZ, e);
      fmpq_add(e, B2, B), fmpq_add(e, e, B), fmpq_add(e, e, B), fmpq_add(e, e, B);
      fmpq_add_si(e, e, 3); /* x: B^2 + 4B + 3 */
      COEF(SWARF_X, e);
      fmpq_mul_si(e, B2, 8), fmpq_add_si(e, e, 8);
      COEF(SWARF_YZ, e);
      fmpq_neg(e, B2), fmpq_submul(e, B, (fmpq_t){{4, 1}}), fmpq_add_si(e, e, 3);
      COEF(SWARF_Y, e);
      fmpq_mul_si(e, B, 2), fmpq_sub_si(e, e, 1), fmpq_mul(e, e, B), fmpq_mul_si(e, e, 2);
      COEF(SWARF_Z, e);
#undef COEF
      fmpq_clear(e);
      fmpq_clear(B2);
    }
    fmpq_clear(B), fmpq_clear(s), fmpq_clear(want);
    swarf_envelope_exact_clear(&E);
  }
}

/* f(n) exactly, n in Q(sqrt r)^3, and g(n). */
static int on_curve(const swarf_xquad *f, const swarf_qr n[3], const fmpz_t r) {
  swarf_qr v, s, t;
  int ok;
  swarf_qr_init(&v), swarf_qr_init(&s), swarf_qr_init(&t);
  swarf_xquad_eval(&v, f, n, r);
  for (int k = 0; k < 3; k++) {
    swarf_qr_mul(&t, n + k, n + k, r);
    swarf_qr_add(&s, &s, &t);
  }
  fmpq_sub_si(s.a, s.a, 1);
  ok = swarf_qr_is_zero(&v) && swarf_qr_is_zero(&s);
  swarf_qr_clear(&v), swarf_qr_clear(&s), swarf_qr_clear(&t);
  return ok;
}

/* Slice points, ELM identity and ELM float points on random rational cases. */
static void test_random_exact(void) {
  tk_rng rng = {0x5eed1234abcdULL};
  int curves = 0, slices = 0, bad_slice = 0, bad_elm = 0, bad_float = 0;
  for (int it = 0; it < 300; it++) {
    fmpq h6[6];
    swarf_xquad q;
    swarf_xmotion m;
    swarf_envelope_exact E;
    ek_vec_init(h6, 6);
    swarf_xquad_init(&q), swarf_xmotion_init(&m), swarf_envelope_exact_init(&E);
    ek_random_case(&rng, h6, &m, it % 2);
    swarf_xquad_set_revolution(&q, h6);
    swarf_envelope_exact_compute(&E, &q, m.v, m.omega);
    if (E.kind == SWARF_ENV_CURVE) {
      curves++;
      for (int c = 0; c < E.ncomp; c++)
        for (int j = 1; j < 8; j++) { /* rational slices inside the component */
          fmpq_t z;
          fmpz_t rz;
          swarf_qr n[2][3];
          double zd = E.comp_lo[c] + (E.comp_hi[c] - E.comp_lo[c]) * j / 8.0;
          fmpq_init(z), fmpz_init(rz);
          for (int b = 0; b < 2; b++)
            for (int k = 0; k < 3; k++)
              swarf_qr_init(&n[b][k]);
          fmpq_set_si(z, lround(zd * 4096.0), 4096);
          if (swarf_envelope_exact_slice(&E, z, rz, n) == 2) {
            slices++;
            bad_slice += !on_curve(&E.f, n[0], rz) || !on_curve(&E.f, n[1], rz);
          }
          for (int b = 0; b < 2; b++)
            for (int k = 0; k < 3; k++)
              swarf_qr_clear(&n[b][k]);
          fmpq_clear(z), fmpz_clear(rz);
        }
      bad_elm += swarf_envelope_exact_check_elm(&E) != 1;
      for (double s = -4.0; s <= 4.0; s += 0.25) {
        double n[3], v[3], w[3], fv;
        if (swarf_envelope_exact_elm_point(&E, s, 1, n) != 0) continue;
        ek_vec_get_d(v, m.v, 3), ek_vec_get_d(w, m.omega, 3);
        fv = n[0] * fmpq_get_d(E.f.c + SWARF_X) + n[1] * fmpq_get_d(E.f.c + SWARF_Y) +
             n[2] * fmpq_get_d(E.f.c + SWARF_Z) + n[0] * n[2] * fmpq_get_d(E.f.c + SWARF_XZ) +
             n[1] * n[2] * fmpq_get_d(E.f.c + SWARF_YZ) +
             n[2] * n[2] * fmpq_get_d(E.f.c + SWARF_ZZ);
        bad_float += fabs(fv) > 1e-8 * (1.0 + fabs(fmpq_get_d(E.f.c + SWARF_XZ)) + 10.0) ||
                     fabs(tk_dot(n, n) - 1.0) > 1e-9;
      }
    }
    swarf_xquad_clear(&q), swarf_xmotion_clear(&m), swarf_envelope_exact_clear(&E);
    ek_vec_clear(h6, 6);
  }
  printf("random exact: %d curves, %d slices\n", curves, slices);
  CHECK(curves > 150 && slices > 1000, "enough curves (%d) and slices (%d)", curves, slices);
  CHECK(bad_slice == 0, "%d slices with f, g != 0 exactly", bad_slice);
  CHECK(bad_elm == 0, "%d ELM parameterizations fail the identity", bad_elm);
  CHECK(bad_float == 0, "%d ELM float points off the curve", bad_float);
}

/* dH/dalpha = f(U^T N) (Fact 1), from H(N, alpha) = alpha tdot.N + h(U^T N)
 * with U(B) = ((1 - B^2) I + 2B [k]x + 2B^2 k k^T) / (1 + B^2), differentiated
 * exactly in B (dB/dalpha = (1 + B^2) / 2). Independent of swarf_xquad_char. */
static void test_fact1(void) {
  tk_rng rng = {0xfac71ULL};
  int bad = 0;
  for (int it = 0; it < 200; it++) {
    fmpq h6[6], N[3], pq[2];
    swarf_xquad q;
    swarf_xmotion m;
    fmpq_poly_t Un[9], u[3], p, t, one_b2, dp;
    fmpq_t val, lhs, rhs;
    swarf_qr n[3], fval;
    swarf_xquad f;
    fmpz_t one;
    ek_vec_init(h6, 6), ek_vec_init(N, 3), ek_vec_init(pq, 2);
    swarf_xquad_init(&q), swarf_xmotion_init(&m), swarf_xquad_init(&f);
    ek_random_case(&rng, h6, &m, 1);
    swarf_xquad_set_revolution(&q, h6);
    ek_rand(pq + 0, &rng, 5, 4), ek_rand(pq + 1, &rng, 5, 4);
    ek_sphere_point(N, pq + 0, pq + 1);
    fmpq_poly_init(p), fmpq_poly_init(t), fmpq_poly_init(one_b2), fmpq_poly_init(dp);
    fmpq_init(val), fmpq_init(lhs), fmpq_init(rhs);
    fmpq_poly_set_coeff_si(one_b2, 0, 1), fmpq_poly_set_coeff_si(one_b2, 2, 1);
    for (int i = 0; i < 9; i++) { /* numerator of U(B), k = omega */
      int r = i / 3, c = i % 3;
      fmpq_poly_init(Un[i]);
      fmpq_mul(val, m.omega + r, m.omega + c);
      fmpq_mul_2exp(val, val, 1);
      fmpq_poly_set_coeff_fmpq(Un[i], 2, val);
      if (r == c) {
        fmpq_poly_set_coeff_si(t, 0, 1), fmpq_poly_set_coeff_si(t, 2, -1);
        fmpq_poly_add(Un[i], Un[i], t);
        fmpq_poly_zero(t);
      } else {
        int l = 3 - r - c, sg = ((c - r + 3) % 3 == 1) ? -1 : 1;
        fmpq_mul_si(val, m.omega + l, 2 * sg);
        fmpq_poly_set_coeff_fmpq(t, 1, val);
        fmpq_poly_add(Un[i], Un[i], t);
        fmpq_poly_zero(t);
      }
    }
    for (int j = 0; j < 3; j++) { /* u = Un^T N */
      fmpq_poly_init(u[j]);
      for (int i = 0; i < 3; i++) {
        fmpq_poly_scalar_mul_fmpq(t, Un[3 * i + j], N + i);
        fmpq_poly_add(u[j], u[j], t);
      }
    }
    /* p = a (u0^2 + u1^2) + b u2^2 + (c u0 + d u1 + e u2)(1 + B^2) + f (1 + B^2)^2 */
    fmpq_poly_zero(p);
    for (int j = 0; j < 3; j++) {
      fmpq_poly_mul(t, u[j], u[j]);
      fmpq_poly_scalar_mul_fmpq(t, t, h6 + (j < 2 ? 0 : 1));
      fmpq_poly_add(p, p, t);
      fmpq_poly_mul(t, u[j], one_b2);
      fmpq_poly_scalar_mul_fmpq(t, t, h6 + 2 + j);
      fmpq_poly_add(p, p, t);
    }
    fmpq_poly_mul(t, one_b2, one_b2);
    fmpq_poly_scalar_mul_fmpq(t, t, h6 + 5);
    fmpq_poly_add(p, p, t);
    /* d/dalpha [p / (1+B^2)^2] = (p' (1+B^2) - 4 B p) / (2 (1+B^2)^2) */
    fmpq_poly_derivative(dp, p);
    fmpq_poly_mul(dp, dp, one_b2);
    fmpq_poly_shift_left(t, p, 1);
    fmpq_poly_scalar_mul_si(t, t, 4);
    fmpq_poly_sub(dp, dp, t);
    fmpq_poly_evaluate_fmpq(lhs, dp, m.B);
    fmpq_poly_evaluate_fmpq(val, one_b2, m.B);
    fmpq_mul(val, val, val);
    fmpq_mul_2exp(val, val, 1);
    fmpq_div(lhs, lhs, val);
    for (int i = 0; i < 3; i++)
      fmpq_addmul(lhs, m.tdot + i, N + i);
    /* f at n = U^T N */
    fmpz_init_set_ui(one, 1);
    for (int j = 0; j < 3; j++) {
      swarf_qr_init(&n[j]);
      for (int i = 0; i < 3; i++)
        fmpq_addmul(n[j].a, m.U + 3 * i + j, N + i);
    }
    swarf_qr_init(&fval);
    swarf_xquad_char(&f, &q, m.v, m.omega);
    swarf_xquad_eval(&fval, &f, n, one);
    fmpq_set(rhs, fval.a);
    bad += !fmpq_equal(lhs, rhs);
    for (int j = 0; j < 3; j++)
      swarf_qr_clear(&n[j]), fmpq_poly_clear(u[j]);
    for (int i = 0; i < 9; i++)
      fmpq_poly_clear(Un[i]);
    swarf_qr_clear(&fval);
    fmpz_clear(one);
    fmpq_poly_clear(p), fmpq_poly_clear(t), fmpq_poly_clear(one_b2), fmpq_poly_clear(dp);
    fmpq_clear(val), fmpq_clear(lhs), fmpq_clear(rhs);
    swarf_xquad_clear(&q), swarf_xmotion_clear(&m), swarf_xquad_clear(&f);
    ek_vec_clear(h6, 6), ek_vec_clear(N, 3), ek_vec_clear(pq, 2);
  }
  CHECK(bad == 0, "dH/dalpha != f exactly in %d of 200 cases", bad);
}

/* Convexity 2 min(a,b) - max(a,b) + f >= 0 against the smallest principal
 * radius sampled over the sphere: h + Hess_S h on the tangent plane, here
 * 2 M|_T + (f - n.M n) I_T with M = diag(a, a, b). */
static void test_convexity(void) {
  tk_rng rng = {0xc0417ULL};
  int bad = 0;
  for (int it = 0; it < 300; it++) {
    fmpq c[6];
    swarf_xquad q;
    double a, b, f, lo = INFINITY;
    ek_vec_init(c, 6);
    for (int i = 0; i < 6; i++)
      ek_rand(c + i, &rng, 5, 2);
    swarf_xquad_init(&q);
    swarf_xquad_set_revolution(&q, c);
    a = fmpq_get_d(c + 0), b = fmpq_get_d(c + 1), f = fmpq_get_d(c + 5);
    for (int i = 0; i <= 400; i++) {
      double z = -1.0 + i / 200.0, rho = 1.0 - z * z; /* n = (sqrt(rho), 0, z) */
      double nmn = a * rho + b * z * z;
      double t1 = 2.0 * a, t2 = 2.0 * (a * z * z + b * rho); /* M on (0,1,0), (-z, 0, sqrt rho) */
      double r1 = t1 + f - nmn, r2 = t2 + f - nmn;
      lo = fmin(lo, fmin(r1, r2));
    }
    if (fabs(lo) > 1e-9) bad += swarf_xquad_is_convex_revolution(&q) != (lo > 0.0);
    swarf_xquad_clear(&q);
    ek_vec_clear(c, 6);
  }
  CHECK(bad == 0, "convexity disagrees with sampling in %d cases", bad);
}

/* swarf_qr_sgn against e-antic: the number field Q[x]/(x^2 - r) embedded at
 * the positive root. */
static void test_sign_eantic(void) {
  tk_rng rng = {0x5167ULL};
  int bad = 0;
  for (int it = 0; it < 400; it++) {
    static const long rs[] = {2, 3, 5, 6, 7, 10, 11, 13, 15};
    long rv = rs[ek_int(&rng, 0, 8)];
    fmpz_t r;
    fmpq_poly_t mp;
    arb_t emb;
    renf_t K;
    renf_elem_t x;
    swarf_qr q;
    fmpz_init_set_si(r, rv);
    fmpq_poly_init(mp);
    fmpq_poly_set_coeff_si(mp, 0, -rv), fmpq_poly_set_coeff_si(mp, 2, 1);
    arb_init(emb);
    arb_set_si(emb, rv);
    arb_sqrt(emb, emb, 64);
    renf_init(K, mp, emb, 64);
    renf_elem_init(x, K);
    swarf_qr_init(&q);
    ek_rand(q.a, &rng, 200, 50), ek_rand(q.b, &rng, 60, 50);
    { /* x = a + b * gen */
      fmpq_poly_t p;
      fmpq_poly_init(p);
      fmpq_poly_set_coeff_fmpq(p, 0, q.a), fmpq_poly_set_coeff_fmpq(p, 1, q.b);
      renf_elem_set_fmpq_poly(x, p, K);
      fmpq_poly_clear(p);
    }
    bad += swarf_qr_sgn(&q, r) != renf_elem_sgn(x, K);
    swarf_qr_clear(&q);
    renf_elem_clear(x, K);
    renf_clear(K);
    arb_clear(emb);
    fmpq_poly_clear(mp);
    fmpz_clear(r);
  }
  CHECK(bad == 0, "sign of a + b sqrt r disagrees with e-antic in %d cases", bad);
}

int main(void) {
  test_example1();
  test_example2();
  test_example2_any_B();
  test_random_exact();
  test_fact1();
  test_convexity();
  test_sign_eantic();
  flint_cleanup();
  return check_done();
}
