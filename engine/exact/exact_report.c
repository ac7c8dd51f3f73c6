/* SPDX-License-Identifier: MPL-2.0 */
/* exact_report.c -- the exact envelope's lifecycle (init/clear), the
 * top-level compute that names the case, and the text report that prints
 * every intermediate result for checking against the paper.
 *
 * A swarf_envelope_exact owns all of its fields; compute replaces them.
 */
#define _POSIX_C_SOURCE 200809L /* strdup */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "exact_private.h"

void swarf_envelope_exact_init(swarf_envelope_exact *E) {
  memset(E, 0, sizeof *E);
  swarf_xquad_init(&E->f);
  fmpq_poly_init(E->A), fmpq_poly_init(E->B), fmpq_poly_init(E->C);
  fmpq_poly_init(E->delta);
  fmpz_poly_init(E->delta_prim);
  fmpz_init_set_ui(E->r, 1);
  fmpq_init(E->z0);
  for (int k = 0; k < 3; k++)
    swarf_qr_init(&E->P[k]), swarf_qr_init(&E->T[k]);
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      swarf_qr_init(&E->cubic[i][j]);
  swarf_qr_init(&E->R[0]), swarf_qr_init(&E->R[1]);
  swarf_qr_poly_init(&E->k), swarf_qr_poly_init(&E->l), swarf_qr_poly_init(&E->m);
  swarf_qr_poly_init(&E->D);
}

void swarf_envelope_exact_clear(swarf_envelope_exact *E) {
  swarf_xquad_clear(&E->f);
  fmpq_poly_clear(E->A), fmpq_poly_clear(E->B), fmpq_poly_clear(E->C);
  fmpq_poly_clear(E->delta);
  fmpz_poly_clear(E->delta_prim);
  for (int i = 0; i < E->nroots; i++)
    arb_clear(E->roots[i].z), fmpq_clear(E->roots[i].q);
  free(E->roots);
  free(E->comp_lo);
  free(E->comp_hi);
  fmpz_clear(E->r);
  fmpq_clear(E->z0);
  for (int k = 0; k < 3; k++)
    swarf_qr_clear(&E->P[k]), swarf_qr_clear(&E->T[k]);
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      swarf_qr_clear(&E->cubic[i][j]);
  swarf_qr_clear(&E->R[0]), swarf_qr_clear(&E->R[1]);
  swarf_qr_poly_clear(&E->k), swarf_qr_poly_clear(&E->l), swarf_qr_poly_clear(&E->m);
  swarf_qr_poly_clear(&E->D);
  memset(E, 0, sizeof *E);
}

static int all_zero(const fmpq *x, int n) {
  for (int i = 0; i < n; i++)
    if (!fmpq_is_zero(x + i)) return 0;
  return 1;
}

/* f = 0 identically: a sphere (isotropic quadratic part) turning about its
 * centre, or a body of revolution spinning about its own axis. */
static swarf_env_kind kind_of_zero_f(const swarf_xquad *h) {
  const fmpq *c = h->c;
  int iso = fmpq_equal(c + SWARF_XX, c + SWARF_YY) && fmpq_equal(c + SWARF_XX, c + SWARF_ZZ) &&
            all_zero(c + SWARF_XY, 3);
  return iso ? SWARF_ENV_SPHERE : SWARF_ENV_SPIN;
}

swarf_status swarf_envelope_exact_compute(swarf_envelope_exact *E, const swarf_xquad *h,
                                          const fmpq *v, const fmpq *omega) {
  if (E == NULL || h == NULL || v == NULL || omega == NULL) return SWARF_ERR_ARG;
  E->ncomp = 0;
  if (all_zero(v, 3) && all_zero(omega, 3)) {
    E->kind = SWARF_ENV_STILL;
    return SWARF_OK;
  }
  swarf_xquad_char(&E->f, h, v, omega);
  if (all_zero(E->f.c, SWARF_QUAD_TERMS)) {
    E->kind = kind_of_zero_f(h);
    return SWARF_OK;
  }
  if (swarf_exact_slice_lines(E) != 0) {
    E->kind = SWARF_ENV_NOT_REVOLUTION;
    return SWARF_OK;
  }
  if (swarf_exact_delta_roots(E) != 0) return SWARF_ERR_MEMORY;
  if (fmpq_poly_is_zero(E->A) && fmpq_poly_is_zero(E->B))
    E->kind = SWARF_ENV_CIRCLES;
  else if (all_zero(E->f.c, SWARF_X))
    E->kind = SWARF_ENV_GREAT_CIRCLE;
  else if (E->ncomp > 0)
    E->kind = SWARF_ENV_CURVE;
  else
    E->kind = E->nroots > 0 ? SWARF_ENV_POINTS : SWARF_ENV_EMPTY;
  if (E->kind == SWARF_ENV_CURVE && swarf_exact_elm(E) != 0) E->kind = SWARF_ENV_POINTS;
  return SWARF_OK;
}

/* ---- Report --------------------------------------------------------------- */

typedef struct {
  char *buf;
  size_t len, cap;
  int err;
} text;

static void put(text *t, const char *s) {
  size_t n = s ? strlen(s) : 0;
  if (t->err || s == NULL) {
    t->err = 1;
    return;
  }
  if (t->len + n + 1 > t->cap) {
    size_t cap = 2 * (t->len + n + 1);
    char *mem = realloc(t->buf, cap);
    if (mem == NULL) {
      t->err = 1;
      return;
    }
    t->buf = mem;
    t->cap = cap;
  }
  memcpy(t->buf + t->len, s, n + 1);
  t->len += n;
}

/* put() a string that the callee allocated, then free it. */
static void put_own(text *t, char *s) {
  put(t, s);
  free(s);
}

static const char *kind_name(swarf_env_kind k) {
  static const char *names[] = {"curve",
                                "still (no motion)",
                                "spin about the own axis (no characteristic)",
                                "whole sphere (degenerate)",
                                "empty Gauss image",
                                "isolated points",
                                "not a QSS of revolution",
                                "latitude circles (A = B = 0)",
                                "great circle (f linear: translation or sphere)"};
  return names[k];
}

static void put_qr_vec(text *t, const char *name, const swarf_qr *x, int n, const fmpz_t r) {
  put(t, name);
  put(t, ": (");
  for (int i = 0; i < n; i++) {
    if (i) put(t, ", ");
    put_own(t, swarf_qr_get_str(x + i, r));
  }
  put(t, ")\n");
}

static void put_poly(text *t, const char *name, const swarf_qr_poly *p, const fmpz_t r) {
  put(t, name);
  put(t, ": ");
  put_own(t, swarf_qr_poly_get_str(p, r, "s"));
  put(t, "\n");
}

static void put_cubic(text *t, const swarf_envelope_exact *E) {
  int first = 1;
  char mono[32];
  put(t, "cubic: ");
  for (int d = 3; d >= 0; d--)
    for (int i = d; i >= 0; i--) {
      const swarf_qr *c = &E->cubic[i][d - i];
      if (swarf_qr_is_zero(c)) continue;
      put(t, first ? "(" : " + (");
      put_own(t, swarf_qr_get_str(c, E->r));
      put(t, ")");
      mono[0] = 0;
      if (i) snprintf(mono, sizeof mono, i > 1 ? "*xi^%d" : "*xi", i);
      if (d - i)
        snprintf(mono + strlen(mono), sizeof mono - strlen(mono), d - i > 1 ? "*eta^%d" : "*eta",
                 d - i);
      put(t, mono);
      first = 0;
    }
  put(t, first ? "0\n" : "\n");
}

static void put_fmpq_poly(text *t, const char *name, const fmpq_poly_t p, const char *var) {
  put(t, name);
  put(t, ": ");
  put_own(t, fmpq_poly_get_str_pretty(p, var));
  put(t, "\n");
}

static void put_roots(text *t, const swarf_envelope_exact *E) {
  char line[128];
  fmpz_poly_t p;
  fmpz_poly_init(p);
  put(t, "Delta(z) primitive: ");
  put_own(t, fmpz_poly_get_str_pretty(E->delta_prim, "z"));
  snprintf(line, sizeof line, "\nDelta factors over Q: %d\nDelta roots in [-1, 1]: %d\n",
           E->delta_factors, E->nroots);
  put(t, line);
  for (int i = 0; i < E->nroots; i++) {
    const swarf_env_root *rt = E->roots + i;
    snprintf(line, sizeof line, "  z%d = ", i + 1);
    put(t, line);
    if (rt->rational)
      put_own(t, fmpq_get_str(NULL, 10, rt->q));
    else
      put_own(t, arb_get_str(rt->z, 30, 0));
    snprintf(line, sizeof line, "%s (multiplicity %d)\n", rt->rational ? " exactly" : "",
             rt->multiplicity);
    put(t, line);
  }
  snprintf(line, sizeof line, "components: %d\n", E->ncomp);
  put(t, line);
  for (int i = 0; i < E->ncomp; i++) {
    snprintf(line, sizeof line, "  component %d: z in [%.15g, %.15g]\n", i + 1, E->comp_lo[i],
             E->comp_hi[i]);
    put(t, line);
  }
  fmpz_poly_clear(p);
}

static void put_elm(text *t, const swarf_envelope_exact *E) {
  char line[64];
  put(t, "z0: ");
  put_own(t, fmpq_get_str(NULL, 10, E->z0));
  put(t, "\nr: ");
  put_own(t, fmpz_get_str(NULL, 10, E->r));
  put(t, "\n");
  put_qr_vec(t, "P", E->P, 3, E->r);
  put_qr_vec(t, "tangent at P", E->T, 3, E->r);
  put_cubic(t, E);
  put_qr_vec(t, "R", E->R, 2, E->r);
  put_poly(t, "k", &E->k, E->r);
  put_poly(t, "l", &E->l, E->r);
  put_poly(t, "m", &E->m, E->r);
  snprintf(line, sizeof line, "deg k, l, m: %ld, %ld, %ld\n", (long)swarf_qr_poly_degree(&E->k),
           (long)swarf_qr_poly_degree(&E->l), (long)swarf_qr_poly_degree(&E->m));
  put(t, line);
  put_poly(t, "D", &E->D, E->r);
}

char *swarf_envelope_exact_report(const swarf_envelope_exact *E) {
  text t = {NULL, 0, 0, 0};
  if (E == NULL) return NULL;
  put(&t, "case: ");
  put(&t, kind_name(E->kind));
  put(&t, "\n");
  if (E->kind != SWARF_ENV_STILL) {
    put(&t, "f: ");
    put_own(&t, swarf_xquad_get_str(&E->f));
    put(&t, "\ng: x^2+y^2+z^2-1\n");
  }
  if (E->kind != SWARF_ENV_STILL && E->kind != SWARF_ENV_SPIN && E->kind != SWARF_ENV_SPHERE &&
      E->kind != SWARF_ENV_NOT_REVOLUTION) {
    put_fmpq_poly(&t, "A(z)", E->A, "z");
    put_fmpq_poly(&t, "B(z)", E->B, "z");
    put_fmpq_poly(&t, "C(z)", E->C, "z");
    put_fmpq_poly(&t, "Delta(z)", E->delta, "z");
    put_roots(&t, E);
  }
  if (E->kind == SWARF_ENV_CURVE) put_elm(&t, E);
  if (t.err) {
    free(t.buf);
    return NULL;
  }
  return t.buf;
}
