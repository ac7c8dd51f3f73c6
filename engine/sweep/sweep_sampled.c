/* SPDX-License-Identifier: MPL-2.0 */
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
 * Many turns (x->tn > 0): about a vertical axis the turns near p's height
 * are searched one by one, about a horizontal axis (G18/G19) only the
 * one-turn window level with p (both below).
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "engine_private.h"

#define EPS 1e-9  /* certified accuracy, mm */
#define CACHE 511 /* samples kept between the two steps (bit masks) */
#define WORDS ((CACHE + 64) / 64)
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
  double a0, a1; /* the times searched: samples a0 + i (a1 - a0) / n, i = 0 .. n */
  int n, evals;
  sample best;
  double best_slope;
  sample cache[CACHE + 1], split[CACHE];
  uint64_t cached[WORDS], has_split[WORDS]; /* bit i: cache[i], split[i] valid */
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

static double time_of(const hctx *h, int i) {
  return i == h->n ? h->a1 : h->a0 + (h->a1 - h->a0) * ((double)i / h->n);
}

static sample at(hctx *h, int i) {
  if (h->n > CACHE) return eval(h, time_of(h, i));
  if (!(h->cached[i >> 6] >> (i & 63) & 1u)) {
    h->cache[i] = eval(h, time_of(h, i));
    h->cached[i >> 6] |= (uint64_t)1 << (i & 63);
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
        h->has_split[i >> 6] |= (uint64_t)1 << (i & 63);
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
    if (n <= CACHE && (h->has_split[i >> 6] >> (i & 63) & 1u)) {
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

/* Searches [a0, a1] with n samples (steps 1 and 2), keeping h->best. */
static void search(hctx *h, double a0, double a1, int n) {
  h->a0 = a0;
  h->a1 = a1;
  h->n = n;
  h->step = h->len * (a1 - a0) / n;
  h->evals = 0;
  h->nheap = 0;
  memset(h->cached, 0, sizeof h->cached);
  memset(h->has_split, 0, sizeof h->has_split);
  find(h);
  certify(h);
}

/* ---- Turn by turn: a helix of many turns about a vertical axis ----------
 *
 * The body is of revolution about the vertical axis and convex, so its sdf
 * at horizontal distance r and height z above the tip, f(r, z), grows with r
 * and is convex in z. Every instance of the helix lies at horizontal
 * distance >= r0 = |rho - radius| from p (rho: p's distance to the axis), so
 * over turn k (tip heights Z_k) g >= W_k = min over Z_k of f(r0, pz - z):
 * W_k, a convex function's minimum over consecutive windows, does not
 * decrease away from the turn k0 that holds its minimiser (found by
 * bisection on the slope at the turns' ends). Turn k0 is searched, then the
 * turns outward on each side while their lower bound (the tangent lines at
 * the window's ends) is below the best value: a turn costs what a one-turn
 * helix costs, and only the few turns near p's height are searched. Past
 * MAX_TURNS searched turns, a turn's bound stands for its minimum (the
 * volume then errs on the large side, by less than the rise of a turn). */

#define MAX_TURNS 48

typedef struct {
  double s, F, dF; /* a turn coordinate s = alpha * turns, f there and dF/ds */
} tpoint;

typedef struct {
  hctx *h;
  double r0, turns, dz; /* dz: tip rise per turn */
  int nturn;            /* turns, the last one partial: ceil(turns) */
} tctx;

static tpoint tpoint_at(const tctx *t, double s) {
  const swarf_sweep_helix *x = &swarf_sweep_cdata(t->h->s)->u.helix;
  const double z = t->h->p[2] - (x->c[2] + s * t->dz), q[3] = {t->r0, 0.0, z};
  double g[3];
  tpoint r = {s, 0.0, 0.0};
  r.F = t->h->body(t->h->body_ctx, q, g);
  r.dF = -g[2] * t->dz;
  return r;
}

static double turn_end(const tctx *t, int k) {
  return k >= t->nturn ? t->turns : (double)k;
}

/* The turn k0 whose window holds a minimiser of F. */
static int lowest_turn(const tctx *t) {
  int lo = 0, hi = t->nturn; /* dF < 0 at lo's end, >= 0 at hi's */
  if (tpoint_at(t, 0.0).dF >= 0.0) return 0;
  if (tpoint_at(t, t->turns).dF < 0.0) return t->nturn - 1;
  while (hi - lo > 1) {
    int mid = lo + (hi - lo) / 2;
    if (tpoint_at(t, turn_end(t, mid)).dF < 0.0)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

/* Lower bound of g over turn k from its ends' samples. */
static double turn_bound(const tpoint *A, const tpoint *B) {
  return swarf_semiconvex_bound(A->F, A->dF, B->F, B->dF, B->s - A->s, 0.0);
}

/* Turn k: searched while fewer than MAX_TURNS are, else its bound stands. */
static void take_turn(tctx *t, int k, double lb, int *searched) {
  hctx *h = t->h;
  if (++*searched <= MAX_TURNS) {
    const swarf_sweep_helix *x = &swarf_sweep_cdata(h->s)->u.helix;
    search(h, turn_end(t, k) / t->turns, turn_end(t, k + 1) / t->turns, x->tn);
  } else if (lb < h->best.g) {
    h->best.g = lb;
    h->best.a = 0.5 * (turn_end(t, k) + turn_end(t, k + 1)) / t->turns;
  }
}

/* Turns k0 + dir, k0 + 2 dir, ... while their bounds are below the best. */
static void outward(tctx *t, int k0, int dir, int *searched) {
  int k = k0 + dir;
  tpoint near = tpoint_at(t, turn_end(t, dir > 0 ? k : k + 1));
  for (; k >= 0 && k < t->nturn; k += dir) {
    tpoint far = tpoint_at(t, turn_end(t, dir > 0 ? k + 1 : k));
    double lb = dir > 0 ? turn_bound(&near, &far) : turn_bound(&far, &near);
    if (lb >= t->h->best.g - EPS) return;
    take_turn(t, k, lb, searched);
    near = far;
  }
}

/* The instance of turn k at p's own phase (the nearest one horizontally):
 * a good first best, so that the turn's samples far from it are skipped. */
static void seed(tctx *t, int k) {
  hctx *h = t->h;
  const swarf_sweep_helix *x = &swarf_sweep_cdata(h->s)->u.helix;
  const double two_pi = 6.28318530717958647692;
  double q[2] = {h->p[0] - x->c[0], h->p[1] - x->c[1]}, s;
  double phase = atan2(q[0] * x->e2[0] + q[1] * x->e2[1], q[0] * x->e1[0] + q[1] * x->e1[1]);
  if (phase < 0.0) phase += two_pi;
  s = k + phase / two_pi;
  if (s > t->turns) s = t->turns;
  eval(h, s / t->turns);
}

static void by_turns(hctx *h) {
  const swarf_sweep_helix *x = &swarf_sweep_cdata(h->s)->u.helix;
  const double *ax = h->s->motion->axis, two_pi = 6.28318530717958647692;
  tctx t;
  int k0, searched = 0;
  double nturn;
  t.h = h;
  t.r0 = fabs(hypot(h->p[0] - x->c[0], h->p[1] - x->c[1]) - x->radius);
  t.turns = x->angle / two_pi;
  t.dz = x->rise * ax[2] / t.turns;
  nturn = ceil(t.turns - 1e-9);
  t.nturn = nturn < 1.0 ? 1 : nturn > 1e9 ? 1000000000 : (int)nturn;
  k0 = lowest_turn(&t);
  seed(&t, k0);
  {
    tpoint A = tpoint_at(&t, turn_end(&t, k0)), B = tpoint_at(&t, turn_end(&t, k0 + 1));
    double lb = turn_bound(&A, &B);
    if (lb >= h->best.g - EPS) return; /* nothing below the caller's upper bound */
    take_turn(&t, k0, lb, &searched);
  }
  outward(&t, k0, 1, &searched);
  outward(&t, k0, -1, &searched);
}

/* ---- One window: a helix of more than one turn about a horizontal axis ---
 *
 * Every turn is the same motion translated by dz (the rise of a turn) along
 * the axis a, with the cutter in the same pose (3-axis: its axis stays
 * vertical). So the instances at one phase theta, one per turn, are the
 * points t(theta) + k dz a: they differ only by a horizontal shift along a,
 * since a is horizontal. The body is of revolution about its vertical axis
 * and convex, so its sdf at fixed height grows with the horizontal distance
 * to its axis, and that distance grows with |(p - t) . a| along such a
 * shift: among them the instance axially nearest p is the lowest. With s
 * the turn coordinate (alpha * turns) and s_p p's own (the axial offset of p
 * over dz), that instance lies within half a turn of s_p, or in the first
 * or last whole turn when s_p is within half a turn of an end or beyond it.
 * So the one-turn window about s_p, clamped into [0, turns], holds the
 * minimum over the whole helix: it alone is searched (certified as above),
 * at the cost of a one-turn helix whatever the number of turns. rise = 0:
 * every turn is the first one. */

#define WINDOW_PAD 1e-6 /* turns added on each side against rounding in s_p */

static void by_window(hctx *h) {
  const swarf_sweep_helix *x = &swarf_sweep_cdata(h->s)->u.helix;
  const double *ax = h->s->motion->axis, two_pi = 6.28318530717958647692;
  double turns = x->angle / two_pi, dz = x->rise / turns, lo = 0.0, hi = 1.0, n;
  if (dz != 0.0) {
    double sp =
        ((h->p[0] - x->c[0]) * ax[0] + (h->p[1] - x->c[1]) * ax[1] + (h->p[2] - x->c[2]) * ax[2]) /
        dz;
    lo = sp - 0.5 - WINDOW_PAD;
    hi = sp + 0.5 + WINDOW_PAD;
    if (lo < 0.0) hi -= lo, lo = 0.0;
    if (hi > turns) lo -= hi - turns, hi = turns;
    if (lo < 0.0) lo = 0.0;
  }
  if (hi > turns) hi = turns;
  n = ceil(x->tn * (hi - lo));
  search(h, lo / turns, hi / turns, n < 2.0 ? 2 : (int)n);
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
  h.best.a = 0.0;
  h.best.g = upper;
  h.best.dg = 0.0;
  h.best_slope = INFINITY;
  if (x->tn > 0 && s->motion->axis[2] == 0.0)
    by_window(&h);
  else if (x->tn > 0)
    by_turns(&h);
  else
    search(&h, 0.0, 1.0, x->n);
  if (alpha != NULL) *alpha = h.best.a;
  return h.best.g;
}

double swarf_sweep_helix_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  return swarf_sweep_helix_body_sdf(s, cutter_body, s->cutter, p, INFINITY, alpha);
}
