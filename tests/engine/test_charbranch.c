/* SPDX-License-Identifier: MPL-2.0 */
/* test_charbranch.c -- branch points of flat, ball and bull-nose cutters
 * (charcutter.c) on motions built to have pairs of branch points closer than
 * 1e-3 ... 1e-12, checked against an independent exact reference.
 *
 * The reference works in z with the double inputs as exact rationals: on the
 * piece with ruling height c, Delta(z) = E(z) + F(z) sqrt(1 - z^2) with
 *   E = G (1 - z^2) + H z^2,  F = K z,  G = X^2 + Y^2,  H = a^2 (w_x^2 + w_y^2) - v_z^2,
 *   K = 2 a (Y w_x - X w_y),  X = v_x + c w_y,  Y = v_y - c w_x,
 * squared into the even quartic E^2 - F^2 (1 - z^2) over Q, whose real roots
 * arb isolates (per squarefree factor); a root is Delta's where the partner
 * E - F sqrt(1 - z^2) is certified nonzero (or F = 0). The number of components
 * is the number of runs of Delta > 0, with signs from arb between the roots.
 */
#include <arb_fmpz_poly.h>
#include <flint/fmpq_poly.h>
#include <flint/fmpz_poly_factor.h>
#include <stdlib.h>

#include "check.h"
#include "exactkit.h"

#define PREC 512
#define MAXR 8

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double zero3[3] = {0, 0, 0};

static void q_set_d(fmpq_t q, double d) {
  arf_t x;
  fmpz_t m, e;
  arf_init(x), fmpz_init(m), fmpz_init(e);
  arf_set_d(x, d);
  arf_get_fmpz_2exp(m, e, x);
  fmpz_set(fmpq_numref(q), m);
  fmpz_one(fmpq_denref(q));
  if (fmpz_sgn(e) >= 0)
    fmpq_mul_2exp(q, q, fmpz_get_ui(e));
  else
    fmpq_div_2exp(q, q, -fmpz_get_si(e));
  arf_clear(x), fmpz_clear(m), fmpz_clear(e);
}

/* The core radius: the flat part of the end face. */
static double core(const swarf_cutter *c) {
  return 0.5 * c->diameter - c->corner_radius;
}

/* The reference on one piece: G, H, K of the header. */
typedef struct {
  fmpq_t G, H, K;
} refpiece;

static void ref_set(refpiece *r, double a, double c, const double v[3], const double w[3]) {
  fmpq_t A, C, X, Y, t, u;
  fmpq_init(A), fmpq_init(C), fmpq_init(X), fmpq_init(Y), fmpq_init(t), fmpq_init(u);
  fmpq_init(r->G), fmpq_init(r->H), fmpq_init(r->K);
  q_set_d(A, a), q_set_d(C, c);
  q_set_d(t, w[1]), fmpq_mul(t, t, C), q_set_d(X, v[0]), fmpq_add(X, X, t);
  q_set_d(t, w[0]), fmpq_mul(t, t, C), q_set_d(Y, v[1]), fmpq_sub(Y, Y, t);
  fmpq_mul(r->G, X, X), fmpq_mul(t, Y, Y), fmpq_add(r->G, r->G, t);
  q_set_d(t, w[0]), fmpq_mul(u, t, t), q_set_d(t, w[1]), fmpq_mul(t, t, t), fmpq_add(u, u, t);
  fmpq_mul(u, u, A), fmpq_mul(u, u, A), q_set_d(t, v[2]), fmpq_mul(t, t, t);
  fmpq_sub(r->H, u, t);
  q_set_d(t, w[0]), fmpq_mul(u, Y, t), q_set_d(t, w[1]), fmpq_mul(t, X, t), fmpq_sub(u, u, t);
  fmpq_mul(u, u, A), fmpq_mul_2exp(r->K, u, 1);
  fmpq_clear(A), fmpq_clear(C), fmpq_clear(X), fmpq_clear(Y), fmpq_clear(t), fmpq_clear(u);
}

static void ref_clear(refpiece *r) {
  fmpq_clear(r->G), fmpq_clear(r->H), fmpq_clear(r->K);
}

/* E(z) and F(z) sqrt(1 - z^2) in arb. */
static void mul_q(arb_t z, const arb_t x, const fmpq_t q) {
  arb_t t;
  arb_init(t);
  arb_set_fmpq(t, q, PREC);
  arb_mul(z, x, t, PREC);
  arb_clear(t);
}

static void ref_ef(const refpiece *r, const arb_t z, arb_t E, arb_t Fs) {
  arb_t z2, t;
  arb_init(z2), arb_init(t);
  arb_mul(z2, z, z, PREC);
  arb_sub_si(t, z2, 1, PREC), arb_neg(t, t);
  mul_q(E, t, r->G);
  mul_q(z2, z2, r->H), arb_add(E, E, z2, PREC);
  arb_sqrtpos(t, t, PREC), arb_mul(t, t, z, PREC), mul_q(Fs, t, r->K);
  arb_clear(z2), arb_clear(t);
}

/* Sign of Delta at z (exact double), or 0 if undecided. */
static int ref_sign(const refpiece *r, double z) {
  arb_t x, E, Fs;
  int s;
  arb_init(x), arb_init(E), arb_init(Fs);
  arb_set_d(x, z);
  ref_ef(r, x, E, Fs);
  arb_add(E, E, Fs, PREC);
  s = arb_is_positive(E) ? 1 : arb_is_negative(E) ? -1 : 0;
  arb_clear(x), arb_clear(E), arb_clear(Fs);
  return s;
}

/* Whether the real root x of E^2 - F^2 (1 - z^2) is Delta's: 1, 0, or -1
 * when undecided. */
static int is_delta_root(const refpiece *r, const arb_t x) {
  arb_t E, Fs, m;
  int res = -1;
  arb_init(E), arb_init(Fs), arb_init(m);
  ref_ef(r, x, E, Fs);
  arb_sub(m, E, Fs, PREC);
  if (!arb_contains_zero(m) || arb_is_zero(Fs))
    res = 1; /* E - F sqrt(1 - z^2) != 0 (or F = 0): Delta = 0 */
  else if (arb_add(m, E, Fs, PREC), !arb_contains_zero(m))
    res = 0;
  arb_clear(E), arb_clear(Fs), arb_clear(m);
  return res;
}

static int by_value(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

/* Real roots of the squarefree factors of p in (zlo, zhi) that are Delta's,
 * appended to out[n...]; returns the new count, or -1 if undecided. */
static int factor_roots(const refpiece *r, const fmpz_poly_t p, double zlo, double zhi, double *out,
                        int n) {
  slong d = fmpz_poly_degree(p);
  acb_ptr roots = _acb_vec_init(d);
  arb_fmpz_poly_complex_roots(roots, p, 0, PREC);
  for (slong i = 0; i < d && n >= 0 && arb_is_zero(acb_imagref(roots + i)); i++) {
    double zd = arf_get_d(arb_midref(acb_realref(roots + i)), ARF_RND_NEAR);
    int k;
    if (!(zd > zlo && zd < zhi)) continue;
    k = is_delta_root(r, acb_realref(roots + i));
    if (k < 0 || n >= MAXR)
      n = -1;
    else if (k)
      out[n++] = zd;
  }
  _acb_vec_clear(roots, d);
  return n;
}

/* Roots of Delta on the piece z in (zlo, zhi), ascending; -1 if undecided. */
static int ref_roots(const refpiece *r, double zlo, double zhi, double *out) {
  fmpq_poly_t P, E, F;
  fmpz_poly_t Z;
  fmpz_poly_factor_t fac;
  fmpq_t t;
  int n = 0;
  fmpq_poly_init(P), fmpq_poly_init(E), fmpq_poly_init(F), fmpz_poly_init(Z), fmpq_init(t);
  fmpz_poly_factor_init(fac);
  fmpq_poly_set_coeff_fmpq(E, 0, r->G);
  fmpq_sub(t, r->H, r->G), fmpq_poly_set_coeff_fmpq(E, 2, t);
  fmpq_poly_mul(P, E, E);
  fmpq_mul(t, r->K, r->K);
  fmpq_poly_set_coeff_fmpq(F, 2, t), fmpq_neg(t, t), fmpq_poly_set_coeff_fmpq(F, 4, t);
  fmpq_poly_sub(P, P, F); /* E^2 - K^2 z^2 (1 - z^2) */
  fmpq_poly_get_numerator(Z, P);
  fmpz_poly_factor_squarefree(fac, Z);
  for (slong j = 0; j < fac->num && n >= 0; j++)
    if (fmpz_poly_degree(fac->p + j) > 0) n = factor_roots(r, fac->p + j, zlo, zhi, out, n);
  if (n > 0) qsort(out, (size_t)n, sizeof *out, by_value);
  fmpz_poly_factor_clear(fac);
  fmpq_poly_clear(P), fmpq_poly_clear(E), fmpq_poly_clear(F), fmpz_poly_clear(Z), fmpq_clear(t);
  return n;
}

/* Reference branch points over the whole cutter and its number of components. */
static int ref_all(const swarf_cutter *c, const double v[3], const double w[3], double *z,
                   int *ncomp) {
  double a = core(c), R = c->corner_radius, L = c->length, cut[MAXR + 2];
  refpiece lo, hi;
  int n0, n1, runs = 0, prev = 0;
  ref_set(&lo, a, R, v, w), ref_set(&hi, a, L - R, v, w);
  n0 = ref_roots(&lo, -1.0, 0.0, z);
  n1 = n0 < 0 ? -1 : ref_roots(&hi, 0.0, 1.0, z + n0);
  cut[0] = -1.0;
  for (int i = 0; n1 >= 0 && i < n0 + n1; i++)
    cut[i + 1] = z[i];
  cut[n0 + n1 + 1] = 1.0;
  for (int i = 0; n1 >= 0 && i <= n0 + n1; i++) {
    double m = 0.5 * (cut[i] + cut[i + 1]);
    int s = ref_sign(m < 0.0 ? &lo : &hi, m);
    if (s == 0) n1 = -1;
    if (s > 0 && prev <= 0) runs++;
    prev = s;
  }
  *ncomp = runs;
  ref_clear(&lo), ref_clear(&hi);
  return n1 < 0 ? -1 : n0 + n1;
}

/* A motion whose Delta on the piece with ruling height c has its zeros at
 * z0 -+ sep / 2 (z0 on that piece's side of the equator): Delta / sin^2 is
 * k (t - t1)(t - t2) in t = cot(theta) = -z / sqrt(1 - z^2) (charcutter.c). */
static void pair_motion(double a, double c, double z0, double sep, double v[3], double w[3]) {
  double z1 = z0 - 0.5 * sep, z2 = z0 + 0.5 * sep;
  double t1 = -z1 / sqrt(1 - z1 * z1), t2 = -z2 / sqrt(1 - z2 * z2), k = 1.0 / (t1 * t2);
  w[1] = -k * (t1 + t2) / (2.0 * a); /* X = 1, Y = 0: ga = 1, be = a w_y */
  w[0] = sqrt(k / (a * a) + 0.25);
  w[2] = 0.2;
  v[0] = 1.0 - c * w[1];
  v[1] = c * w[0];
  v[2] = sqrt(a * a * (w[0] * w[0] + w[1] * w[1]) - k);
}

/* A plunge with a slight drift e and tilt: v = (e, e / 2, 1), omega =
 * (3 e / 10, -e / 5, 1 / 2). ga is of order e^2 on both pieces and al ~ -1,
 * so Delta has one zero on each side of the equator, at z ~ -+sqrt(ga): a thin
 * band; e is chosen so that they are about sep apart. */
static void plunge_motion(const swarf_cutter *c, double sep, double v[3], double w[3]) {
  double R = c->corner_radius, T = c->length - R;
  double g = hypot(1.0 - 0.2 * R, 0.5 - 0.3 * R) + hypot(1.0 - 0.2 * T, 0.5 - 0.3 * T);
  double e = sep / g;
  v[0] = e, v[1] = 0.5 * e, v[2] = 1.0;
  w[0] = 0.3 * e, w[1] = -0.2 * e, w[2] = 0.5;
}

static void check_case(const swarf_cutter *c, const double v[3], const double w[3], double sep,
                       const char *what) {
  double zr[MAXR], zf[MAXR], minsep = 2.0;
  int ncomp, nr = ref_all(c, v, w, zr, &ncomp), nf = swarf_char_branch_points(c, v, w, zf, MAXR);
  swarf_char_curve cc;
  CHECK(nr >= (sep > 0.0 ? 2 : 0), "%s: the reference decides (%d roots)", what, nr);
  for (int i = 1; i < nr; i++)
    minsep = fmin(minsep, zr[i] - zr[i - 1]);
  if (sep > 0.0)
    CHECK(minsep < 1.5 * sep && minsep > 0.5 * sep, "%s: built pair %.3g apart (%.3g)", what, sep,
          minsep);
  CHECK(nf == nr, "%s: %d branch points (reference %d)", what, nf, nr);
  for (int i = 0; i < nf && i < nr; i++)
    CHECK(fabs(zf[i] - zr[i]) < 1e-14 + 1e-3 * minsep, "%s: z%d %.17g vs %.17g", what, i, zf[i],
          zr[i]);
  swarf_char_curve_init(&cc);
  if (hypot(hypot(v[0], v[1]), hypot(w[0], w[1]) * c->length) > 1e-10 * hypot(v[2], w[2]))
    CHECK((swarf_char_curve_compute(&cc, c, zero3, I3, v, w, 1e-3) == SWARF_OK ? (int)cc.ncomp
                                                                               : -1) == ncomp,
          "%s: %d components (got %zu)", what, ncomp, cc.ncomp);
  /* else within engine.h's plunge threshold: the rim circles, not the band */
  swarf_char_curve_clear(&cc);
  printf("%-34s sep %.0e: %d branch points, %d components, min gap %.3g\n", what, sep, nf, ncomp,
         minsep);
}

/* Pairs on one piece: the built doubles carry rounding of relative size
 * 1e-16 into D, so they reach separations down to ~1e-8; below that (exact)
 * only agreement with the reference is asked (the pair may have become a
 * nearby pair or none). */
static void piece_cases(const swarf_cutter *c, double sep, int built) {
  double v[3], w[3], a = core(c), R = c->corner_radius;
  char what[64];
  snprintf(what, sizeof what, "%s, pair below the ruling", c->corner_radius > 0 ? "bull" : "flat");
  pair_motion(a, R, -0.4 - 0.5 * R / c->diameter, sep, v, w);
  check_case(c, v, w, built ? sep : 0.0, what);
  snprintf(what, sizeof what, "%s, pair above the ruling", c->corner_radius > 0 ? "bull" : "flat");
  pair_motion(a, c->length - R, 0.3 + R / c->diameter, sep, v, w);
  check_case(c, v, w, built ? sep : 0.0, what);
}

int main(void) {
  swarf_cutter flat, ball, bull, sphere;
  static const double seps[] = {1e-3, 1e-5, 1e-7, 1e-9, 1e-12};
  const char *names[4] = {"flat", "ball", "bull", "sphere"};
  const swarf_cutter *cs[4] = {&flat, &ball, &bull, &sphere};
  swarf_cutter_init(&flat, SWARF_CUTTER_FLAT, 6.0, 0.0, 20.0, NULL);
  swarf_cutter_init(&ball, SWARF_CUTTER_BALL, 6.0, 0.0, 20.0, NULL);
  swarf_cutter_init(&bull, SWARF_CUTTER_BULL, 10.0, 2.0, 25.0, NULL);
  swarf_cutter_init(&sphere, SWARF_CUTTER_BALL, 4.0, 0.0, 4.0, NULL);
  for (size_t i = 0; i < sizeof seps / sizeof seps[0]; i++) {
    double v[3], w[3], s = seps[i];
    piece_cases(&flat, s, s >= 1e-7);
    piece_cases(&bull, s, s >= 1e-7);
    for (int k = 0; k < 4; k++) {
      char what[64];
      snprintf(what, sizeof what, "%s, pair across the equator", names[k]);
      plunge_motion(cs[k], s, v, w);
      check_case(cs[k], v, w, s, what);
    }
  }
  flint_cleanup();
  return check_done();
}
