/* SPDX-License-Identifier: MPL-2.0 */
/* sweep_rigid.c -- the volume swept by a cutter under a rigid motion with
 * rotation (RIGID motions of rotary machines, toolpath.h).
 *
 * sdf(p) = min over alpha of g(alpha), g = body_sdf(q), q = U^T (p - t): the
 * cutter's distance at each instance. The body is convex, so its sdf is a
 * convex function of q with unit gradient n, and
 *   g'  = n . q',  q' = -(omega x q) - v        (|g'| <= V + W |q|)
 *   g'' >= -|q''|, |q''| <= (W' + W^2) |q| + W V + V'
 * with V, W, V', W' bounds of |v|, |omega| and their alpha-derivatives over
 * the move. g' = 0 is the characteristic condition of the paper, f(n) =
 * (v + omega x x) . n = 0 at the nearest surface point x (ENVELOPE.md Fact
 * 1): the minimiser of g is a point of the characteristic curve at that time.
 *
 *  0. the two ends: where the lower bound over the whole move from them (step
 *     3's) is at or above the value to beat, nothing can beat it and the
 *     search ends there (76 % of the calls on the impeller at 0.2 mm with a
 *     flat end mill).
 *  1. time steps: N + 1 poses, N chosen so that no point of the cutter moves
 *     more than STEP = sqrt(8 r tol) between two poses (the spacing at which
 *     balls of radius r leave scallops of depth tol): from the rotation
 *     angle (W, times the cutter's reach), the path's speed and curvature
 *     (V and V') and the voxel (tol = voxel / 10). Their poses come from
 *     the per-thread pose table (swarf_motion_pose_table: computed once per
 *     move, not per voxel). Coarse to fine: every S-th step (S ~ sqrt(N))
 *     first; the steps inside a coarse interval are sampled only if its
 *     lower bound (step 3's) is below the best value so far, lowest first.
 *     The others cannot hold a value below best - EPS: step 3 drops them.
 *  2. between steps the envelope is resolved on the characteristic curve:
 *     every interval where g' goes from - to + is refined (Illinois regula
 *     falsi) to g' = 0, or until the bracket left is certified (its bound
 *     at or above best - EPS); every piece a sample cuts off the bracket
 *     goes to step 3 with both ends known.
 *  3. certification: intervals whose lower bound (Lipschitz, and the upper
 *     envelope of the two concave parabolas of curvature -K through the end
 *     data) is below best - EPS are split, lowest first, within caps: next
 *     to their lower end, at the distance d where g(end) - K d^2 / 2 meets
 *     best - EPS (the piece beside a minimum is certified at once instead
 *     of by a bisection per halving), or in the middle when d is half the
 *     interval or more. (2.4x fewer evaluations here, the same
 *     certificate.)
 * A ball end mill takes sweep_rigid_ball.c first (the characteristic
 * circles at the time steps, a local refinement certified by convexity) and
 * comes here only where that path cannot certify its preconditions; a flat
 * or bull end mill takes it for the capsule that holds it, and comes here
 * where the capsule's value is not its own (the bottom or a corner nearest).
 * Beyond FAR (72 voxels, more than any narrow band plus a block) the value
 * is the lower bound of the coarse intervals only. Nothing allocates here
 * (the pose table belongs to the thread's cache); pure function of the sweep
 * and p.
 */
#include <math.h>
#include <string.h>

#include "engine_private.h"

#define EPS 1e-6      /* certified accuracy, mm */
#define MAXN 512      /* time steps per move at most */
#define HEAP 64       /* intervals waiting in step 3 */
#define MAX_EVALS 400 /* evaluations of g per call beyond the steps */
#define PROBE 64      /* poses probed at init for the bounds */

typedef swarf_tsample rsample; /* time, g, g', |p - t| */
typedef swarf_tspan rspan;

typedef struct {
  const swarf_sweep *s;
  swarf_body_sdf_fn body;
  const void *body_ctx;
  const double *p;
  double floor; /* stop once a value at or below it is found (-inf: never) */
  int evals;
  rsample best;
  rspan heap[HEAP];
  int nheap;
} rctx;

static inline double min2(double a, double b) {
  return a < b ? a : b;
}

static inline double max2(double a, double b) {
  return a > b ? a : b;
}

static double norm3(const double a[3]) {
  return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

static double cutter_body(const void *ctx, const double q[3], double grad[3]) {
  return swarf_cutter_sdf_grad((const swarf_cutter *)ctx, q, grad);
}

/* g and g' at time a from the pose there. */
static rsample rsample_at(rctx *h, double a, const swarf_pose *P) {
  const double *U = P->U, *v = P->v, *w = P->omega;
  double d[3], q[3], gr[3], dq[3];
  rsample r;
  for (int k = 0; k < 3; k++)
    d[k] = h->p[k] - P->t[k];
  for (int k = 0; k < 3; k++)
    q[k] = U[k] * d[0] + U[3 + k] * d[1] + U[6 + k] * d[2];
  r.a = a;
  r.g = h->body(h->body_ctx, q, gr);
  dq[0] = -(w[1] * q[2] - w[2] * q[1]) - v[0];
  dq[1] = -(w[2] * q[0] - w[0] * q[2]) - v[1];
  dq[2] = -(w[0] * q[1] - w[1] * q[0]) - v[2];
  r.dg = gr[0] * dq[0] + gr[1] * dq[1] + gr[2] * dq[2];
  r.dist = norm3(d);
  h->evals++;
  if (r.g < h->best.g) h->best = r;
  return r;
}

static rsample reval(rctx *h, double a) {
  swarf_pose P;
  swarf_motion_pose(h->s->motion, a, &P);
  return rsample_at(h, a, &P);
}

/* The Lipschitz part of the lower bound over [A.a, B.a]. */
static inline double rbound_lip(const rctx *h, const rsample *A, const rsample *B) {
  const swarf_sweep_rigid *x = &swarf_sweep_cdata(h->s)->u.rigid;
  double w = B->a - A->a, Q = max2(A->dist, B->dist) + 0.5 * x->v * w;
  return 0.5 * (A->g + B->g - (x->v + x->w * Q) * w);
}

/* K with g'' >= -K over [A.a, B.a] (see the top of the file). */
static inline double rcurv(const rctx *h, const rsample *A, const rsample *B) {
  const swarf_sweep_rigid *x = &swarf_sweep_cdata(h->s)->u.rigid;
  double Q = max2(A->dist, B->dist) + 0.5 * x->v * (B->a - A->a);
  return (x->wd + x->w * x->w) * Q + x->w * x->v + x->vd;
}

/* The semiconvex part of the lower bound over [A.a, B.a]. */
static inline double rbound_semi(const rctx *h, const rsample *A, const rsample *B) {
  return swarf_semiconvex_bound(A->g, A->dg, B->g, B->dg, B->a - A->a, rcurv(h, A, B));
}

/* Lower bound of g over [A.a, B.a] (see the top of the file). */
static double rbound(const rctx *h, const rsample *A, const rsample *B) {
  return max2(rbound_semi(h, A, B), rbound_lip(h, A, B));
}

/* Where step 3 splits a span without a sign change of g': at the distance
 * from its lower end within which the curvature bound alone keeps g above
 * best - EPS (g(end) - K d^2 / 2), so that the piece next to the end is
 * certified at once (a span next to a minimum otherwise takes a bisection
 * per halving of its width); in the middle when that is half the span or more. */
static double rsplit(const rctx *h, const rsample *A, const rsample *B) {
  double w = B->a - A->a, K = rcurv(h, A, B), lo = min2(A->g, B->g), d;
  d = K > 0.0 ? 0.9 * sqrt(2.0 * (lo - h->best.g + EPS) / K) : INFINITY;
  if (!(d < 0.5 * w)) return A->a + 0.5 * w;
  return A->g <= B->g ? A->a + d : B->a - d;
}

static void rpush(rctx *h, rsample lo, rsample hi) {
  rspan sp = {lo, hi, 0.0, 0};
  sp.lb = rbound_lip(h, &lo, &hi);
  if (sp.lb >= h->best.g - EPS) return; /* cheap test first */
  sp.lb = max2(sp.lb, rbound_semi(h, &lo, &hi));
  if (sp.lb >= h->best.g - EPS || h->nheap == HEAP || hi.a - lo.a < 1e-12) return;
  swarf_tspan_push(h->heap, &h->nheap, sp);
}

static rspan rpop(rctx *h) {
  return swarf_tspan_pop(h->heap, &h->nheap);
}

/* lo.dg < 0 < hi.dg: Illinois regula falsi to g' = 0 (the characteristic).
 * Every piece of [lo, hi] a sample cuts off the bracket is queued for step
 * 3 with both its ends known, and the last bracket on either side of the
 * final sample, so no sample's information is lost to the certification. */
static void rrefine(rctx *h, rsample lo, rsample hi) {
  double flo = lo.dg, fhi = hi.dg;
  int side = 0;
  for (int it = 0; it < 40 && hi.a - lo.a > 1e-13; it++) {
    double a = (lo.a * fhi - hi.a * flo) / (fhi - flo);
    rsample m;
    if (!(a > lo.a && a < hi.a)) a = 0.5 * (lo.a + hi.a);
    m = reval(h, a);
    if (fabs(m.dg) <= 1e-12 * (1.0 + fabs(m.g))) {
      rpush(h, lo, m);
      rpush(h, m, hi);
      return;
    }
    if (m.dg < 0.0) {
      rpush(h, lo, m);
      lo = m, flo = m.dg;
      if (side < 0) fhi *= 0.5;
      side = -1;
    } else {
      rpush(h, m, hi);
      hi = m, fhi = m.dg;
      if (side > 0) flo *= 0.5;
      side = 1;
    }
    if (rbound(h, &lo, &hi) >= h->best.g - EPS) return; /* the bracket is certified */
  }
  rpush(h, lo, hi);
}

/* Step 2 on one interval between samples: refined to g' = 0 where g' goes
 * from - to +, its parts queued for step 3. */
static void rinterval(rctx *h, rsample lo, rsample hi) {
  if (h->best.g <= h->floor) return;
  if (lo.dg < 0.0 && hi.dg > 0.0 && rbound(h, &lo, &hi) < h->best.g) {
    rrefine(h, lo, hi);
    return;
  }
  rpush(h, lo, hi);
}

/* Step 3: the queued intervals split, lowest bound first, until none can
 * hold a value below best - EPS (or the cap). */
static void rheap(rctx *h) {
  while (h->nheap > 0 && h->evals < MAX_EVALS && h->best.g > h->floor) {
    rspan sp = rpop(h);
    rsample m;
    if (sp.lb >= h->best.g - EPS) break;
    if (sp.lo.dg < 0.0 && sp.hi.dg > 0.0 && sp.hi.a - sp.lo.a > 1e-13) {
      rrefine(h, sp.lo, sp.hi);
      continue;
    }
    m = reval(h, rsplit(h, &sp.lo, &sp.hi));
    rpush(h, sp.lo, m);
    rpush(h, m, sp.hi);
  }
}

/* Steps 2 and 3 over the sampled poses. */
static void rcertify(rctx *h, const rsample *smp, int n) {
  for (int i = 0; i < n; i++)
    rinterval(h, smp[i], smp[i + 1]);
  rheap(h);
}

/* The sample at step i of n, from the pose table if there is one. */
static rsample rstep(rctx *h, const swarf_pose *table, int i, int n) {
  return table ? rsample_at(h, (double)i / n, &table[i]) : reval(h, (double)i / n);
}

/* Coarse intervals (every S-th step, S ~ sqrt(n)) sorted by lower bound (the steps
 * marked in have are in smp already). */
static int rcoarse(rctx *h, const swarf_pose *table, int n, int S, rsample *smp, char *have,
                   int *order, double *lbc) {
  int nc = (n + S - 1) / S;
  for (int j = 0; j <= nc; j++) {
    int i = j * S < n ? j * S : n;
    if (!have[i]) smp[i] = rstep(h, table, i, n), have[i] = 1;
  }
  for (int j = 0; j < nc; j++) {
    int i0 = j * S, i1 = (j + 1) * S < n ? (j + 1) * S : n, k;
    lbc[j] = rbound_lip(h, &smp[i0], &smp[i1]); /* enough to drop it: no need for more */
    if (lbc[j] < h->best.g - EPS) lbc[j] = max2(lbc[j], rbound_semi(h, &smp[i0], &smp[i1]));
    for (k = j; k > 0 && lbc[order[k - 1]] > lbc[j]; k--)
      order[k] = order[k - 1];
    order[k] = j;
  }
  return nc;
}

/* Step 1: the samples at the time steps, evaluated only in the coarse
 * intervals whose lower bound is below the best value so far (most promising
 * first; the others cannot hold a lower value); with ends, smp[0] and smp[n]
 * hold the ends already (step 0). Compacts the samples, in
 * time order, to the front of smp and returns their number minus one; *lb
 * receives a lower bound of g over the whole move. */
static int rsteps(rctx *h, const swarf_pose *table, int n, rsample *smp, int ends, double *lb) {
  char have[MAXN + 1];
  int order[MAXN], S = (int)sqrt((double)n), nc, m = 0;
  double lbc[MAXN];
  if (S < 1) S = 1;
  order[0] = 0, lbc[0] = INFINITY;
  memset(have, 0, (size_t)n + 1);
  have[0] = have[n] = (char)ends;
  nc = rcoarse(h, table, n, S, smp, have, order, lbc);
  *lb = lbc[order[0]];
  if (*lb > swarf_sweep_cdata(h->s)->u.rigid.far) return -1;
  for (int k = 0; k < nc; k++) {
    int j = order[k], i1 = (j + 1) * S < n ? (j + 1) * S : n;
    if (lbc[j] >= h->best.g - EPS || h->best.g <= h->floor) break;
    for (int i = j * S + 1; i < i1; i++)
      smp[i] = rstep(h, table, i, n), have[i] = 1;
  }
  for (int i = 0; i <= n; i++)
    if (have[i]) smp[m++] = smp[i];
  return m - 1;
}

/* The two ends alone, into smp[0] and smp[n]: 1 when their lower bound over the whole
 * move (rbound's, over [0, 1]) is at or above the value to beat, so that no sample can beat
 * it and the search would end with that value (most points of a rotary move's bounding box
 * lie well clear of it; the coarse steps would only confirm that). */
static int rends_above(rctx *h, const swarf_pose *table, int n, rsample *smp) {
  smp[0] = rstep(h, table, 0, n), smp[n] = rstep(h, table, n, n);
  return h->best.g < INFINITY && rbound(h, &smp[0], &smp[n]) >= h->best.g;
}

/* The search, pruned by upper (best value to beat) and stopped at floor; ends: the ends'
 * bound first (rends_above). */
static double rsearch(const swarf_sweep *s, swarf_body_sdf_fn body, const void *ctx,
                      const double p[3], double floor, double upper, int ends, double *alpha) {
  rsample smp[MAXN + 1];
  const swarf_pose *table;
  rctx h;
  int n;
  double lb;
  h.s = s, h.body = body, h.body_ctx = ctx, h.p = p, h.floor = floor, h.evals = 0, h.nheap = 0;
  h.best.a = 0.0, h.best.g = upper, h.best.dg = 0.0, h.best.dist = 0.0;
  n = swarf_sweep_cdata(s)->u.rigid.n;
  /* NULL when out of memory: poses computed */
  swarf_motion_pose_table_id(s->motion, n, swarf_sweep_cdata(s)->u.rigid.id, &table);
  if (ends && rends_above(&h, table, n, smp)) {
    if (alpha != NULL) *alpha = h.best.a;
    return h.best.g;
  }
  n = rsteps(&h, table, n, smp, ends, &lb);
  if (alpha != NULL) *alpha = h.best.a;
  if (n < 0) return fmin(lb, upper);
  h.evals = 0;
  rcertify(&h, smp, n);
  if (alpha != NULL) *alpha = h.best.a;
  return h.best.g;
}

double swarf_sweep_rigid_body_below(const swarf_sweep *s, swarf_body_sdf_fn body, const void *ctx,
                                    const double p[3], double upper, double *alpha) {
  return rsearch(s, body, ctx, p, -INFINITY, upper, 1, alpha);
}

int swarf_sweep_rigid_range_plane(const swarf_sweep *s, const double p[3], double lo, double hi,
                                  double r, double *d, double *pd, double g[3]) {
  const int k = swarf_sweep_rigid_ball_plane(s, p, lo, hi, r, d, pd, g);
  if (k >= 0) return k;
  /* a ball's path has tried its ends' bounds already (a flat's or bull's capsule: not its own) */
  *d = rsearch(s, cutter_body, s->cutter, p, lo, hi + EPS, swarf_sweep_cdata(s)->u.rigid.ball != 1,
               NULL);
  return 0;
}

double swarf_sweep_rigid_sdf_range(const swarf_sweep *s, const double p[3], double lo, double hi) {
  double v, pd, g[3];
  swarf_sweep_rigid_range_plane(s, p, lo, hi, 0.0, &v, &pd, g); /* r = 0: no plane */
  return v;
}

double swarf_sweep_rigid_body_sdf(const swarf_sweep *s, swarf_body_sdf_fn body, const void *ctx,
                                  const double p[3], double *alpha) {
  if (s == NULL || swarf_sweep_cdata(s)->method != SWARF_SWEEP_RIGID || body == NULL || p == NULL)
    return NAN;
  return swarf_sweep_rigid_body_below(s, body, ctx, p, INFINITY, alpha);
}

double swarf_sweep_rigid_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  double v;
  if (s == NULL || p == NULL) return NAN; /* s->cutter below */
  if (swarf_sweep_cdata(s)->method == SWARF_SWEEP_RIGID &&
      swarf_sweep_rigid_ball(s, p, -INFINITY, INFINITY, &v, alpha) == 0)
    return v;
  return swarf_sweep_rigid_body_sdf(s, cutter_body, s->cutter, p, alpha);
}
