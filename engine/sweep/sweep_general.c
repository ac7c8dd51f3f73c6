/* SPDX-License-Identifier: MPL-2.0 */
/* sweep_general.c -- the swept volume of a cutter with a non-convex QSS
 * piece (Example 2's spool: dished ends, a concave waist, sharp rims) under
 * any motion. Its sdf is neither convex nor semiconvex (the evolute of the
 * waist reaches the rims), so the semiconvex bounds of sweep_rigid.c do not
 * hold. The bound used instead needs nothing but geometry:
 *
 *   over a time interval [a, b] the cutter-frame point q(alpha) = U^T (p - t)
 *   stays within d3 = M (b - a)^2 / 8 of the chord [q(a), q(b)] (M bounds
 *   |q''|: (W' + W^2) |q| + W V + V', 0 on a line); the chord's image in the
 *   meridian half-plane (r, z) is a hyperbola arc within dh of the 2-D chord
 *   [c(a), c(b)] (dh: the largest gap between the convex r(s) and its secant,
 *   closed form); the 2-D sdf is 1-Lipschitz, so
 *     g >= min over the 2-D chord of S2 - dh - d3.
 *   That minimum, when the chord lies outside the region, is the distance
 *   between a segment and the profile curve: the endpoints' distances, the
 *   curve's axis points and cusps, and the two curve points whose normal is
 *   normal to the chord (the hedgehog's point of normal u is unique); a
 *   crossing (found on the curve's monotone pieces) or an endpoint inside
 *   sends it to the inside bound: S2(x) >= -|x - y| for any boundary point y,
 *   so g >= -max over the chord of min(|x - y_a|, |x - y_b|) (y_a, y_b the
 *   endpoints' nearest boundary points), a bisector crossing in closed form.
 * Both parts shrink quadratically with the interval: the search (time steps,
 * lowest bound first, splitting at the middle or at g' = 0 by regula falsi)
 * certifies the minimum to EPS like sweep_rigid.c. Convex pieces of the same
 * cutter go through sweep_rigid.c. Pure function of the sweep and p.
 */
#include <math.h>
#include <string.h>

#include "engine_private.h"

#define EPS 1e-6       /* certified accuracy, mm */
#define HEAP 128       /* intervals waiting */
#define MAX_EVALS 3000 /* evaluations per call beyond the steps */
#define MAXN 512

static inline double len2(double a, double b) {
  return sqrt(a * a + b * b);
}

typedef struct {
  double a, g, dg;
  double q[3], c[2], y[2]; /* cutter-frame point, its (r, z), nearest profile point */
} gsample;

typedef struct {
  gsample lo, hi;
  double lb;
} gspan;

typedef struct {
  const swarf_sweep *s;
  const swarf_profile_piece *pc;
  const double *p;
  gsample best;
  gspan heap[HEAP];
  int n, evals;
} gctx;

static gsample gsample_at(gctx *h, double a, const swarf_pose *P) {
  const double *U = P->U, *v = P->v, *w = P->omega;
  double d[3], gr[3], g2[2], dq[3], r;
  gsample s;
  for (int k = 0; k < 3; k++)
    d[k] = h->p[k] - P->t[k];
  for (int k = 0; k < 3; k++)
    s.q[k] = U[k] * d[0] + U[3 + k] * d[1] + U[6 + k] * d[2];
  r = sqrt(s.q[0] * s.q[0] + s.q[1] * s.q[1]);
  s.a = a;
  s.c[0] = r, s.c[1] = s.q[2];
  s.g = swarf_profile_qss_sdf_near(h->pc, r, s.q[2], g2, s.y);
  gr[0] = r > 0.0 ? g2[0] * s.q[0] / r : g2[0], gr[1] = r > 0.0 ? g2[0] * s.q[1] / r : 0.0;
  gr[2] = g2[1];
  dq[0] = -(w[1] * s.q[2] - w[2] * s.q[1]) - v[0];
  dq[1] = -(w[2] * s.q[0] - w[0] * s.q[2]) - v[1];
  dq[2] = -(w[0] * s.q[1] - w[1] * s.q[0]) - v[2];
  s.dg = gr[0] * dq[0] + gr[1] * dq[1] + gr[2] * dq[2];
  h->evals++;
  if (s.g < h->best.g) h->best = s;
  return s;
}

static gsample geval(gctx *h, double a) {
  swarf_pose P;
  swarf_motion_pose(h->s->motion, a, &P);
  return gsample_at(h, a, &P);
}

/* ---- the bound ---------------------------------------------------------------- */

static double seg_point_dist(const double a[2], const double b[2], const double x[2]) {
  double dr = b[0] - a[0], dz = b[1] - a[1], l2 = dr * dr + dz * dz, t = 0.0;
  if (l2 > 0.0) t = ((x[0] - a[0]) * dr + (x[1] - a[1]) * dz) / l2;
  t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
  return len2(x[0] - a[0] - t * dr, x[1] - a[1] - t * dz);
}

/* Largest gap between r(s) = |qa_xy + s d_xy| (convex) and its secant on [0, 1]. */
static double hyperbola_gap(const double qa[3], const double qb[3], double ra, double rb) {
  double dx = qb[0] - qa[0], dy = qb[1] - qa[1], k2 = dx * dx + dy * dy, k, s0, e2, D, s, r;
  if (!(k2 > 0.0)) return 0.0;
  k = sqrt(k2);
  s0 = -(qa[0] * dx + qa[1] * dy) / k2;
  e2 = fmax(0.0, ra * ra - k2 * s0 * s0);
  D = rb - ra;
  if (fabs(D) >= k) return 0.0;
  s = s0 + D * sqrt(e2) / (k * sqrt(k2 - D * D));
  s = s < 0.0 ? 0.0 : s > 1.0 ? 1.0 : s;
  r = sqrt(e2 + k2 * (s - s0) * (s - s0));
  return fmax(0.0, ra + s * D - r);
}

/* -max over the segment ab of min(|x - ya|, |x - yb|): ends and the bisector. */
static double inside_bound(const double a[2], const double b[2], const double ya[2],
                           const double yb[2]) {
  double m = fmax(fmin(len2(a[0] - ya[0], a[1] - ya[1]), len2(a[0] - yb[0], a[1] - yb[1])),
                  fmin(len2(b[0] - ya[0], b[1] - ya[1]), len2(b[0] - yb[0], b[1] - yb[1])));
  double nr = yb[0] - ya[0], nz = yb[1] - ya[1],
         c = 0.5 * (nr * (ya[0] + yb[0]) + nz * (ya[1] + yb[1]));
  double fa = nr * a[0] + nz * a[1] - c, fb = nr * b[0] + nz * b[1] - c;
  if ((fa < 0.0) != (fb < 0.0) && fa != fb) {
    double t = fa / (fa - fb), x[2] = {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
    m = fmax(m, len2(x[0] - ya[0], x[1] - ya[1]));
  }
  return -m;
}

/* Signed distance of the profile curve's point at s from the segment's line. */
static double curve_side(const swarf_profile_piece *pc, double s, const double a[2],
                         const double n[2], double y[2]) {
  swarf_profile_qss_point(pc, s, y);
  return (y[0] - a[0]) * n[0] + (y[1] - a[1]) * n[1];
}

static void sort_small(double *x, int n) {
  for (int i = 1; i < n; i++)
    for (int j = i; j > 0 && x[j] < x[j - 1]; j--) {
      double t = x[j];
      x[j] = x[j - 1], x[j - 1] = t;
    }
}

/* The distance between the segment ab (both ends outside) and the profile
 * curve, or -1 when the curve crosses it. */
static double outside_dist(const swarf_profile_piece *pc, const double a[2], const double b[2],
                           double da, double db) {
  double t[2] = {b[0] - a[0], b[1] - a[1]}, len = len2(t[0], t[1]), n[2], s[8], best;
  double cusp, y[2], fprev = 0.0, sprev = -1.0;
  int ns = 0;
  best = fmin(da, db);
  if (!(len > 0.0)) return best;
  t[0] /= len, t[1] /= len, n[0] = t[1], n[1] = -t[0];
  s[ns++] = -1.0, s[ns++] = 1.0;
  if (pc->q2 != 0.0 && (cusp = (pc->q0 + 2.0 * pc->q2) / (3.0 * pc->q2)) > 0.0 && cusp < 1.0)
    s[ns++] = sqrt(cusp), s[ns++] = -sqrt(cusp);
  if (n[0] >= 0.0) s[ns++] = n[1]; /* the curve's normal u = (sqrt(1 - s^2), s) = +-n */
  if (n[0] <= 0.0) s[ns++] = -n[1];
  sort_small(s, ns);
  for (int i = 0; i < ns; i++) {
    double f = curve_side(pc, s[i], a, n, y), u = (y[0] - a[0]) * t[0] + (y[1] - a[1]) * t[1];
    best = fmin(best, u >= 0.0 && u <= len ? fabs(f) : seg_point_dist(a, b, y));
    if (i > 0 && (f < 0.0) != (fprev < 0.0)) { /* a crossing of the line: within the segment? */
      double lo = sprev, hi = s[i], flo = fprev;
      for (int it = 0; it < 44 && hi - lo > 1e-12; it++) { /* conservative below */
        double mid = 0.5 * (lo + hi), fm = curve_side(pc, mid, a, n, y);
        if ((fm < 0.0) == (flo < 0.0))
          lo = mid, flo = fm;
        else
          hi = mid;
      }
      { /* the crossing lies on the tiny arc [lo, hi]: its u range, widened */
        double y0[2], y1[2], u0, u1, pad;
        curve_side(pc, lo, a, n, y0);
        curve_side(pc, hi, a, n, y1);
        u0 = (y0[0] - a[0]) * t[0] + (y0[1] - a[1]) * t[1];
        u1 = (y1[0] - a[0]) * t[0] + (y1[1] - a[1]) * t[1];
        pad = 2.0 * len2(y1[0] - y0[0], y1[1] - y0[1]);
        if (fmax(u0, u1) + pad >= -1e-9 && fmin(u0, u1) - pad <= len + 1e-9) return -1.0;
      }
    }
    fprev = f, sprev = s[i];
  }
  return best;
}

/* Lower bound of g over [A.a, B.a]. */
static double gbound(const gctx *h, const gsample *A, const gsample *B) {
  const swarf_sweep_rigid *x = &swarf_sweep_cdata(h->s)->u.rigid;
  /* |q| = |p - t| grows by at most V w / 2 inside; |q'| <= V + W |q| */
  double w = B->a - A->a,
         Q = fmax(len2(len2(A->q[0], A->q[1]), A->q[2]), len2(len2(B->q[0], B->q[1]), B->q[2])) +
             0.5 * x->v * w;
  double L = x->v + x->w * Q, lip = 0.5 * (A->g + B->g - L * w);
  double M = (x->wd + x->w * x->w) * Q + x->w * x->v + x->vd;
  double d3 = M * w * w / 8.0, dh = hyperbola_gap(A->q, B->q, A->c[0], B->c[0]), m;
  if (A->g > 0.0 && B->g > 0.0 && (m = outside_dist(h->pc, A->c, B->c, A->g, B->g)) >= 0.0)
    return fmax(lip, m - dh - d3);
  return fmax(lip, inside_bound(A->c, B->c, A->y, B->y) - dh - d3);
}

static void gpush(gctx *h, gsample lo, gsample hi) {
  gspan sp = {lo, hi, 0.0};
  int i;
  if (hi.a - lo.a < 1e-13 || h->n == HEAP) return;
  sp.lb = gbound(h, &lo, &hi);
  if (sp.lb >= h->best.g - EPS) return;
  for (i = h->n++; i > 0 && h->heap[(i - 1) / 2].lb > sp.lb; i = (i - 1) / 2)
    h->heap[i] = h->heap[(i - 1) / 2];
  h->heap[i] = sp;
}

static gspan gpop(gctx *h) {
  gspan top = h->heap[0], last = h->heap[--h->n];
  int i = 0;
  for (;;) {
    int c = 2 * i + 1;
    if (c >= h->n) break;
    if (c + 1 < h->n && h->heap[c + 1].lb < h->heap[c].lb) c++;
    if (h->heap[c].lb >= last.lb) break;
    h->heap[i] = h->heap[c];
    i = c;
  }
  if (h->n > 0) h->heap[i] = last;
  return top;
}

/* The next time to look at in [lo, hi]: regula falsi on g' when it brackets
 * a minimum, else the middle. */
static double split_at(const gspan *sp) {
  double a = 0.5 * (sp->lo.a + sp->hi.a);
  if (sp->lo.dg < 0.0 && sp->hi.dg > 0.0) {
    double r = (sp->lo.a * sp->hi.dg - sp->hi.a * sp->lo.dg) / (sp->hi.dg - sp->lo.dg);
    double w = sp->hi.a - sp->lo.a;
    if (r > sp->lo.a + 0.05 * w && r < sp->hi.a - 0.05 * w) a = r;
  }
  return a;
}

static gsample step_at(gctx *h, const swarf_pose *table, int i, int n) {
  return table != NULL ? gsample_at(h, (double)i / n, &table[i]) : geval(h, (double)i / n);
}

/* The minimum of g over the move for one piece, to EPS, or a value >= upper
 * - EPS when nothing is below upper. Beyond FAR from the volume: a lower bound
 * from the coarse steps (every S-th, S ~ sqrt(n)); the fine steps are looked
 * at only inside coarse intervals whose bound is below the best so far. */
static double piece_min(const swarf_sweep *s, const swarf_profile_piece *pc, const double p[3],
                        double upper, double *alpha) {
  gctx h;
  const swarf_pose *table = NULL;
  gsample cs[MAXN + 1];
  double lbc[MAXN], lbmin = INFINITY;
  int order[MAXN], n = swarf_sweep_cdata(s)->u.rigid.n, S = (int)sqrt((double)n), nc;
  memset(&h.best, 0, sizeof h.best);
  h.s = s, h.pc = pc, h.p = p, h.n = 0, h.evals = 0;
  h.best.g = upper;
  if (S < 1) S = 1;
  nc = (n + S - 1) / S;
  swarf_motion_pose_table_id(s->motion, n, swarf_sweep_cdata(s)->u.rigid.id, &table);
  for (int j = 0; j <= nc; j++)
    cs[j] = step_at(&h, table, j * S < n ? j * S : n, n);
  for (int j = 0; j < nc; j++) {
    int k;
    lbc[j] = gbound(&h, &cs[j], &cs[j + 1]);
    lbmin = fmin(lbmin, lbc[j]);
    for (k = j; k > 0 && lbc[order[k - 1]] > lbc[j]; k--)
      order[k] = order[k - 1];
    order[k] = j;
  }
  if (alpha != NULL) *alpha = h.best.a;
  if (lbmin > swarf_sweep_cdata(s)->u.rigid.far) return fmin(lbmin, h.best.g);
  for (int k = 0; k < nc; k++) {
    int j = order[k], i0 = j * S, i1 = (j + 1) * S < n ? (j + 1) * S : n;
    gsample prev = cs[j];
    if (lbc[j] >= h.best.g - EPS) break;
    for (int i = i0 + 1; i <= i1; i++) {
      gsample cur = i == i1 ? cs[j + 1] : step_at(&h, table, i, n);
      gpush(&h, prev, cur);
      prev = cur;
    }
  }
  h.evals = 0;
  while (h.n > 0 && h.evals < MAX_EVALS) {
    gspan sp = gpop(&h);
    gsample m;
    if (sp.lb >= h.best.g - EPS) break;
    m = geval(&h, split_at(&sp));
    gpush(&h, sp.lo, m);
    gpush(&h, m, sp.hi);
  }
  if (alpha != NULL) *alpha = h.best.a;
  return h.best.g;
}

static double piece_body(const void *ctx, const double q[3], double grad[3]) {
  return swarf_profile_piece_sdf_grad((const swarf_profile_piece *)ctx, q, grad);
}

double swarf_sweep_general_sdf(const swarf_sweep *s, const double p[3], double *alpha) {
  const swarf_cutter *c = s->cutter;
  double best = INFINITY, ab = 0.0;
  for (int i = 0; i < c->npieces; i++) {
    const swarf_profile_piece *pc = &c->piece[i];
    double a = 0.0, g = pc->convex ? swarf_sweep_rigid_body_below(s, piece_body, pc, p, best, &a)
                                   : piece_min(s, pc, p, best, &a);
    if (g < best) best = g, ab = a;
  }
  if (alpha != NULL) *alpha = ab;
  return best;
}
