/* SPDX-License-Identifier: MPL-2.0 */
/* charqssgen.c -- the characteristic curve of a moving GENERAL QSS,
 * h(n) = n^T Q n + b . n + c (paper eq. 10-11, Theorem 1: a spherical
 * quartic), as closed polylines with a chord error under a tolerance.
 *
 * f(n) = (v + omega x grad h) . n = n^T M n + L . n with M = [omega]x Q -
 * Q [omega]x and L = v + omega x b. charqssgen_sweep.c finds the strands of
 * the sweep and how they meet at the events; here each component is walked
 * strand by strand (turning at its branch points, passing through the other
 * events) and sampled adaptively as charcurve.c does: next to a branch point
 * phi moves quadratically in the step parameter. The curve owns its arrays.
 */
#include <stdlib.h>
#include <string.h>

#include "engine_private.h"

#define MAX_DEPTH 40
#define MAX_POINTS 4000000
#define MARGIN 0.6
#define AIM 0.45
#define MAX_SPLIT 64
#define SPAN_STEPS 16
#define PI 3.14159265358979323846

typedef struct {
  swarf_char_curve *cc;
  const swarf_qss_general *q;
  const swarf_gen_sweep *s;
  const double *t, *U;
  double Qs[9], tol;
  size_t first;
} gbuilder;

/* One strand on interval k, phi(tau) for tau in [0, 1]. */
typedef struct {
  int k, i;
  double s0, s1;
  int root0, root1;
} strand;

static int push(gbuilder *b, const double n[3], const double x[3]) {
  swarf_char_curve *cc = b->cc;
  swarf_char_point *p;
  if (cc->len > b->first) {
    const swarf_char_point *l = &cc->pts[cc->len - 1];
    if (memcmp(l->n, n, 3 * sizeof *n) == 0) return 0;
  }
  if (cc->len == cc->cap) {
    size_t cap = cc->cap ? 2 * cc->cap : 256;
    void *mem = cap <= MAX_POINTS ? realloc(cc->pts, cap * sizeof *cc->pts) : NULL;
    if (mem == NULL) return -1;
    cc->pts = mem, cc->cap = cap;
  }
  p = &cc->pts[cc->len++];
  memcpy(p->n, n, sizeof p->n);
  memcpy(p->x, x, sizeof p->x);
  for (int k = 0; k < 3; k++)
    p->w[k] = b->t[k] + b->U[3 * k] * x[0] + b->U[3 * k + 1] * x[1] + b->U[3 * k + 2] * x[2];
  return 0;
}

static int close_component(gbuilder *b) {
  swarf_char_curve *cc = b->cc;
  if (cc->len == b->first) return 0;
  if (push(b, cc->pts[b->first].n, cc->pts[b->first].x) != 0) return -1;
  if (cc->ncomp + 2 > cc->start_cap) {
    size_t cap = cc->start_cap ? 2 * cc->start_cap : 8;
    void *mem = realloc(cc->start, cap * sizeof *cc->start);
    if (mem == NULL) return -1;
    cc->start = mem, cc->start_cap = cap;
  }
  cc->start[0] = 0;
  cc->start[++cc->ncomp] = cc->len;
  b->first = cc->len;
  return 0;
}

/* x_h(n) = h n + grad h - (grad h . n) n. */
static void surface_point(const gbuilder *b, const double n[3], double x[3]) {
  double g[3], h = b->q->c, gn = 0.0;
  for (int i = 0; i < 3; i++) {
    double qn = b->Qs[3 * i] * n[0] + b->Qs[3 * i + 1] * n[1] + b->Qs[3 * i + 2] * n[2];
    h += n[i] * (qn + b->q->b[i]);
    g[i] = 2.0 * qn + b->q->b[i];
    gn += g[i] * n[i];
  }
  for (int i = 0; i < 3; i++)
    x[i] = (h - gn) * n[i] + g[i];
}

/* phi(tau), exactly s0 at tau = 0 and s1 at tau = 1 and never outside
 * [s0, s1]: an event is bracketed to adjacent doubles, so s0 + (s1 - s0)
 * rounded one ulp past s1 is already on the event's other side. */
static double strand_phi(const strand *p, double tau) {
  double d = p->s1 - p->s0, phi;
  if (tau <= 0.0) return p->s0;
  if (tau >= 1.0) return p->s1;
  if (p->root0 && p->root1)
    phi = p->s0 + d * tau * tau * (3.0 - 2.0 * tau);
  else if (p->root0)
    phi = p->s0 + d * tau * tau;
  else if (p->root1)
    phi = p->s1 - d * (1.0 - tau) * (1.0 - tau);
  else
    phi = p->s0 + d * tau;
  return fmin(fmax(phi, p->s0), p->s1);
}

/* The strand's point at tau; -1 if the slice there has the wrong root count
 * (the caller fails: a point it cannot evaluate is never skipped). */
static int eval_point(const gbuilder *b, const strand *p, double tau, double n[3], double x[3]) {
  double phi = strand_phi(p, tau), th[4];
  if (swarf_gen_slice_roots(b->s, phi, th) != b->s->nroot[p->k]) return -1;
  swarf_gen_normal(b->s, phi, th[p->i], n);
  surface_point(b, n, x);
  return 0;
}

static double seg_dist(const double p[3], const double a[3], const double c[3]) {
  double d[3], w[3], dd = 0.0, t = 0.0, r = 0.0;
  for (int k = 0; k < 3; k++) {
    d[k] = c[k] - a[k], w[k] = p[k] - a[k];
    dd += d[k] * d[k], t += d[k] * w[k];
  }
  t = dd > 0.0 ? t / dd : 0.0;
  t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
  for (int k = 0; k < 3; k++)
    r += (w[k] - t * d[k]) * (w[k] - t * d[k]);
  return sqrt(r);
}

/* Points after (tau0, x0) up to (tau1, n1, x1): charcurve.c's rule. A
 * segment is emitted only once its midpoint is within the tolerance; a
 * midpoint that cannot be evaluated, or no convergence by MAX_DEPTH, fails. */
static int refine(gbuilder *b, const strand *p, double tau0, const double x0[3], double tau1,
                  const double n1[3], const double x1[3], int depth) {
  double tm = 0.5 * (tau0 + tau1), nm[3], xm[3], d, prev = tau0, xp[3];
  int k;
  if (depth >= MAX_DEPTH || eval_point(b, p, tm, nm, xm) != 0) return -1;
  if ((d = seg_dist(xm, x0, x1)) <= MARGIN * b->tol) return push(b, n1, x1);
  k = (int)ceil(sqrt(d / (AIM * b->tol)));
  k = k < 2 ? 2 : k > MAX_SPLIT ? MAX_SPLIT : k;
  memcpy(xp, x0, sizeof xp);
  for (int j = 1; j <= k; j++) {
    double tau = tau0 + (tau1 - tau0) * j / k, n[3], x[3];
    if (j == k)
      memcpy(n, n1, sizeof n), memcpy(x, x1, sizeof x), tau = tau1;
    else if (eval_point(b, p, tau, n, x) != 0)
      return -1;
    if (refine(b, p, prev, xp, tau, n, x, depth + 1) != 0) return -1;
    memcpy(xp, x, sizeof xp);
    prev = tau;
  }
  return 0;
}

/* The whole strand, forward (dir > 0) or backward, from its end at tau = 0
 * (dir > 0) or 1 through every span: no span is skipped. */
static int strand_points(gbuilder *b, const strand *p, int dir) {
  int m = (int)ceil(SPAN_STEPS * (p->s1 - p->s0) / PI);
  double x0[3], n0[3], prev = dir > 0 ? 0.0 : 1.0;
  if (m < 2) m = 2;
  if (eval_point(b, p, prev, n0, x0) != 0 || push(b, n0, x0) != 0) return -1;
  for (int j = 1; j <= m; j++) {
    double tau = dir > 0 ? (double)j / m : (double)(m - j) / m, n1[3], x1[3];
    if (eval_point(b, p, tau, n1, x1) != 0 || refine(b, p, prev, x0, tau, n1, x1, 0) != 0)
      return -1;
    memcpy(x0, x1, sizeof x0);
    prev = tau;
  }
  return 0;
}

static strand make_strand(const swarf_gen_sweep *s, int k, int i) {
  strand p = {k, i, s->a[k], s->b[k], 0, 0};
  p.root0 = k > 0 && s->map_l[k - 1][i] < 0;
  p.root1 = k + 1 < s->nint && s->map_r[k][i] < 0;
  return p;
}

/* Walk the component through strand (k, i) forward, marking strands seen. */
static int walk(gbuilder *b, int k, int i, unsigned char (*seen)[4]) {
  const swarf_gen_sweep *s = b->s;
  int k0 = k, i0 = i, d = 1, steps = 0;
  do {
    strand p = make_strand(s, k, i);
    int m;
    if (++steps > 4 * s->nint + 4) return -2;
    seen[k][i] = 1;
    if (strand_points(b, &p, d) != 0) return -1;
    m = d > 0 ? s->map_r[k][i] : s->map_l[k - 1][i];
    if (m < 0)
      i = -1 - m, d = -d; /* turn at the branch point */
    else
      k += d, i = m;
  } while (!(k == k0 && i == i0 && d == 1));
  return close_component(b);
}

static int trace(gbuilder *b) {
  unsigned char seen[SWARF_GEN_MAX_EVENTS + 1][4];
  memset(seen, 0, sizeof seen);
  for (int k = 0; k < b->s->nint; k++)
    for (int i = 0; i < b->s->nroot[k]; i++)
      if (!seen[k][i]) {
        int r = walk(b, k, i, seen);
        if (r != 0) return r;
      }
  return 0;
}

/* M = [omega]x Q - Q [omega]x (Q symmetrized), L = v + omega x b. */
static void char_form(const double Qs[9], const double bv[3], const double v[3], const double w[3],
                      double M[9], double L[3]) {
  double W[9] = {0, -w[2], w[1], w[2], 0, -w[0], -w[1], w[0], 0};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double a = 0.0;
      for (int p = 0; p < 3; p++)
        a += W[3 * i + p] * Qs[3 * p + j] - Qs[3 * i + p] * W[3 * p + j];
      M[3 * i + j] = a;
    }
  L[0] = v[0] + w[1] * bv[2] - w[2] * bv[1];
  L[1] = v[1] + w[2] * bv[0] - w[0] * bv[2];
  L[2] = v[2] + w[0] * bv[1] - w[1] * bv[0];
}

/* Size of the surface, mm: for the default tolerance and the f = 0 test. */
static double qss_scale(const swarf_qss_general *q) {
  double s = fabs(q->c);
  for (int i = 0; i < 9; i++)
    s += fabs(q->Q[i]);
  for (int i = 0; i < 3; i++)
    s += fabs(q->b[i]);
  return s > 0.0 ? s : 1.0;
}

swarf_status swarf_char_curve_compute_qss_general(swarf_char_curve *cc, const swarf_qss_general *q,
                                                  const double t[3], const double U[9],
                                                  const double v[3], const double omega[3],
                                                  double tol) {
  swarf_gen_sweep s;
  gbuilder b = {cc, q, &s, t, U, {0}, 0.0, 0};
  double M[9], L[3], big = 0.0, tiny = 0.0, sc;
  int r;
  if (cc == NULL || q == NULL || t == NULL || U == NULL || v == NULL || omega == NULL)
    return SWARF_ERR_ARG;
  cc->len = cc->ncomp = 0;
  if (cc->start_cap == 0) {
    if ((cc->start = malloc(8 * sizeof *cc->start)) == NULL) return SWARF_ERR_MEMORY;
    cc->start_cap = 8;
  }
  cc->start[0] = 0;
  sc = qss_scale(q);
  b.tol = tol > 0.0 ? tol : 1e-3 * sc;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      b.Qs[3 * i + j] = 0.5 * (q->Q[3 * i + j] + q->Q[3 * j + i]);
  char_form(b.Qs, q->b, v, omega, M, L);
  for (int i = 0; i < 3; i++)
    big += fabs(v[i]) + fabs(omega[i]) * sc, tiny += fabs(L[i]);
  for (int i = 0; i < 9; i++)
    tiny += fabs(M[i]);
  if (!(tiny > 1e-13 * big)) return SWARF_OK; /* still, or the whole sphere: no component */
  if (swarf_gen_sweep_init(&s, M, L) != 0) return SWARF_ERR_INTERNAL;
  r = trace(&b);
  return r == 0 ? SWARF_OK : SWARF_ERR_INTERNAL;
}
