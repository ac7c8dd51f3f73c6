/* sweep_sampled.c -- the swept volume of any helix the closed forms do not
 * cover: rise != 0, or an axis not parallel to the cutter's (G18/G19 arcs).
 *
 * g(alpha) = cutter_sdf(p - t(alpha)) is not convex along a curved path, but
 * it is Lipschitz (|g'| <= LEN, the path length) and semiconvex: the sdf of
 * a convex body is a convex function, so g'' >= -grad . t'' >= -K with
 * K = radius * angle^2 = |t''|. From g and g' at the ends of an interval these
 * give a lower bound of g on it: the larger of the Lipschitz bound and the
 * minimum of the upper envelope of the two concave parabolas through the end
 * data (tight: that envelope is itself semiconvex).
 *
 *  1. find: samples every STEP mm of path, skipping intervals that the
 *     Lipschitz bound of an earlier sample puts above the best value, and
 *     Illinois regula falsi to g' = 0 in every interval where g' goes from
 *     - to + and that could hold a lower value.
 *  2. certify: every interval whose bound is below best - EPS goes to a heap,
 *     lowest bound first, and is split at its stationary point (if it
 *     brackets one) or its middle until all bounds are >= best - EPS.
 * The result is the minimum over instances to EPS, i.e. exact outside the
 * volume, unless the work caps stop step 2 (HEAP intervals, MAX_EVALS
 * evaluations, MAX_DEPTH splits); then it is still within STEP / 2 (the
 * Lipschitz bound of the sampling). Pure function of the sweep and p.
 */
#include <math.h>
#include <stdint.h>

#include "engine_private.h"

#define EPS 1e-9      /* certified accuracy, mm */
#define CACHE 63      /* samples kept between the two steps (bit masks) */
#define HEAP 96       /* intervals waiting in step 2 */
#define MAX_DEPTH 40  /* splits of one sample interval */
#define MAX_EVALS 600 /* evaluations of g per call */

typedef swarf_tsample sample; /* time, g(a), g'(a) */
typedef swarf_tspan span;

typedef struct {
  const swarf_sweep *s;
  swarf_body_sdf_fn body;
  const void *body_ctx;
  const double *p;
  double K, len, step;
  int n, evals;
  sample best;
  double best_slope;
  sample cache[CACHE + 1], split[CACHE];
  uint64_t cached, has_split; /* bit i: cache[i], split[i] valid */
  span heap[HEAP];
  int nheap;
} hctx;

/* g and g' at a; the best value is kept (among values equal to rounding, the
 * flatter point: the converged stationary point rather than an iterate). */
static sample eval(hctx *h, double a) {
  const swarf_sweep_helix *x = &swarf_sweep_cdata(h->s)->u.helix;
  const double *ax = h->s->motion->axis;
  double th = a * x->angle, c = cos(th), sn = sin(th), q[3], td[3], gr[3];
  sample r = {a, 0.0, 0.0, 0.0};
  for (int k = 0; k < 3; k++) {
    double u = c * x->e1[k] + sn * x->e2[k];
    double du = c * x->e2[k] - sn * x->e1[k];
    q[k] = h->p[k] - x->c[k] - x->radius * u - a * x->rise * ax[k];
    td[k] = x->radius * x->angle * du + x->rise * ax[k];
  }
  r.g = h->body(h->body_ctx, q, gr);
  r.dg = -(gr[0] * td[0] + gr[1] * td[1] + gr[2] * td[2]);
  h->evals++;
  {
    double tie = 1e-14 * (1.0 + fabs(r.g));
    if (r.g < h->best.g - tie || (r.g <= h->best.g + tie && fabs(r.dg) < h->best_slope)) {
      h->best = r;
      h->best_slope = fabs(r.dg);
    }
  }
  return r;
}

static sample at(hctx *h, int i) {
  if (h->n > CACHE) return eval(h, (double)i / h->n);
  if (!(h->cached >> i & 1u)) {
    h->cache[i] = eval(h, (double)i / h->n);
    h->cached |= (uint64_t)1 << i;
  }
  return h->cache[i];
}

/* lo.dg < 0 < hi.dg: Illinois regula falsi to g' = 0; returns the last point. */
static sample refine(hctx *h, sample lo, sample hi) {
  double tol = 1e-13 * h->len, flo = lo.dg, fhi = hi.dg;
  sample m = lo;
  int side = 0;
  for (int it = 0; it < 60 && hi.a - lo.a > 1e-15; it++) {
    double a = (lo.a * fhi - hi.a * flo) / (fhi - flo);
    if (!(a > lo.a && a < hi.a)) a = 0.5 * (lo.a + hi.a);
    m = eval(h, a);
    if (fabs(m.dg) <= tol) break;
    if (m.dg < 0.0) {
      lo = m;
      flo = m.dg;
      if (side < 0) fhi *= 0.5;
      side = -1;
    } else {
      hi = m;
      fhi = m.dg;
      if (side > 0) flo *= 0.5;
      side = 1;
    }
  }
  return m;
}

static double max2(double a, double b) {
  return a > b ? a : b;
}

/* Lower bound of g over [A.a, B.a]: the semiconvex bound (engine_private.h)
 * or the Lipschitz one, whichever is higher. */
static double bound(const hctx *h, const sample *A, const sample *B) {
  double w = B->a - A->a, lip = 0.5 * (A->g + B->g - h->len * w);
  return max2(swarf_semiconvex_bound(A->g, A->dg, B->g, B->dg, w, h->K), lip);
}

static void push(hctx *h, sample lo, sample hi, int depth) {
  span sp = {lo, hi, 0.0, depth};
  sp.lb = bound(h, &lo, &hi);
  if (sp.lb >= h->best.g - EPS || h->nheap == HEAP) return;
  swarf_tspan_push(h->heap, &h->nheap, sp);
}

static span pop(hctx *h) {
  return swarf_tspan_pop(h->heap, &h->nheap);
}

/* From sample i (value *si), skip the samples that the Lipschitz bound of
 * an earlier one puts above best - margin: returns the first index whose
 * interval [i, i + 1] could hold a lower value (*si its sample), or n. */
static int next_candidate(hctx *h, int i, double margin, sample *si) {
  for (;;) {
    int skip = (int)ceil((si->g - h->best.g + margin) / h->step) - 1;
    if (skip <= 0) return i;
    if (skip >= h->n - i) return h->n;
    i += skip;
    *si = at(h, i);
  }
}

/* Step 1: samples, skipping, and the stationary points of the brackets. */
static void find(hctx *h) {
  int i = 0, n = h->n;
  sample si = at(h, 0);
  at(h, n);
  while ((i = next_candidate(h, i, 0.0, &si)) < n) {
    sample s1 = at(h, i + 1);
    if (si.dg < 0.0 && s1.dg > 0.0 && 0.5 * (si.g + s1.g - h->step) < h->best.g) {
      sample m = refine(h, si, s1);
      if (n <= CACHE && m.a > si.a && m.a < s1.a) {
        h->split[i] = m;
        h->has_split |= (uint64_t)1 << i;
      }
    }
    i++;
    si = s1;
  }
}

/* Step 2, first half: queue every sample interval that could hold a value
 * below best - EPS (split at the stationary point found in step 1). */
static void queue_intervals(hctx *h) {
  int i = 0, n = h->n;
  sample si = at(h, 0);
  while ((i = next_candidate(h, i, EPS, &si)) < n) {
    sample s1 = at(h, i + 1);
    if (n <= CACHE && (h->has_split >> i & 1u)) {
      push(h, si, h->split[i], 1);
      push(h, h->split[i], s1, 1);
    } else {
      push(h, si, s1, 0);
    }
    i++;
    si = s1;
  }
}

/* Step 2, second half: split the queued intervals, lowest bound first. */
static void certify(hctx *h) {
  double tol = 1e-13 * h->len;
  queue_intervals(h);
  while (h->nheap > 0 && h->evals < MAX_EVALS) {
    span sp = pop(h);
    double mid = 0.5 * (sp.lo.a + sp.hi.a);
    sample m;
    if (sp.lb >= h->best.g - EPS) break;
    if (sp.depth >= MAX_DEPTH) continue;
    if (sp.lo.dg < -tol && sp.hi.dg > tol)
      m = refine(h, sp.lo, sp.hi);
    else
      m = eval(h, mid);
    if (!(m.a > sp.lo.a && m.a < sp.hi.a)) m = eval(h, mid);
    push(h, sp.lo, m, sp.depth + 1);
    push(h, m, sp.hi, sp.depth + 1);
  }
}

static double cutter_body(const void *ctx, const double q[3], double grad[3]) {
  return swarf_cutter_sdf_grad((const swarf_cutter *)ctx, q, grad);
}

double swarf_sweep_helix_body_sdf(const swarf_sweep *s, swarf_body_sdf_fn body, const void *ctx,
                                  const double p[3], double upper, double *alpha) {
  hctx h;
  const swarf_sweep_helix *x = &swarf_sweep_cdata(s)->u.helix;
  h.s = s;
  h.body = body;
  h.body_ctx = ctx;
  h.p = p;
  h.K = x->radius * x->angle * x->angle;
  h.len = x->len;
  h.step = x->step;
  h.n = x->n;
  h.evals = 0;
  h.best.a = 0.0;
  h.best.g = upper;
  h.best.dg = 0.0;
  h.best_slope = INFINITY;
  h.nheap = 0;
  h.cached = h.has_split = 0;
  find(&h);
  certify(&h);
  if (alpha != NULL) *alpha = h.best.a;
  return h.best.g;
}

double swarf_sweep_helix_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  return swarf_sweep_helix_body_sdf(s, cutter_body, s->cutter, p, INFINITY, alpha);
}
