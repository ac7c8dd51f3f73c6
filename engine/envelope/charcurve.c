/* SPDX-License-Identifier: MPL-2.0 */
/* charcurve.c -- characteristic curves of a moving body of revolution at one
 * time step: closed polylines, one per component, sampled so that the chord
 * error of the surface points stays under a tolerance.
 *
 * The per-slice math and the branch points live in charslice.c. A component
 * is a maximal parameter interval where Delta > 0; its two branches s = +1,
 * s = -1 meet at the branch points (roots of Delta) and, at a flat face, are
 * joined by the face's chord. The curve owns its arrays (init/clear pair);
 * compute replaces the contents.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "engine_private.h"

#define MAX_ROOTS 64
#define MAX_DEPTH 48       /* bisections of one parameter interval */
#define MAX_POINTS 4000000 /* refuse to grow beyond this */
#define MARGIN 0.6         /* accepted middle-point distance, in units of tol */
#define AIM 0.45           /* middle-point distance aimed at when splitting */
#define MAX_SPLIT 64       /* most steps one split makes */
#define SPAN_STEPS 16      /* first steps of a branch over the whole of sigma */
#define MIN_STEPS 2        /* first steps of any piece */
#define HALF_PI 1.57079632679489661923

typedef struct {
  swarf_char_curve *cc;
  const swarf_char_profile *pr;
  const double *v, *omega, *t, *U;
  double tol;
  size_t first; /* index of the first point of the open component */
} builder;

void swarf_char_curve_init(swarf_char_curve *cc) {
  memset(cc, 0, sizeof *cc);
}

void swarf_char_curve_clear(swarf_char_curve *cc) {
  free(cc->pts);
  free(cc->start);
  memset(cc, 0, sizeof *cc);
}

static int reset(swarf_char_curve *cc) {
  cc->len = 0;
  cc->ncomp = 0;
  if (cc->start_cap == 0) {
    cc->start = malloc(8 * sizeof *cc->start);
    if (cc->start == NULL) return -1;
    cc->start_cap = 8;
  }
  cc->start[0] = 0;
  return 0;
}

static int push(builder *b, const double n[3], const double x[3]) {
  swarf_char_curve *cc = b->cc;
  swarf_char_point *p;
  if (cc->len == cc->cap) {
    size_t cap = cc->cap ? 2 * cc->cap : 256;
    void *mem = cap <= MAX_POINTS ? realloc(cc->pts, cap * sizeof *cc->pts) : NULL;
    if (mem == NULL) return -1;
    cc->pts = mem;
    cc->cap = cap;
  }
  p = &cc->pts[cc->len++];
  for (int k = 0; k < 3; k++) {
    p->n[k] = n[k];
    p->x[k] = x[k];
  }
  for (int k = 0; k < 3; k++)
    p->w[k] = b->t[k] + b->U[3 * k] * x[0] + b->U[3 * k + 1] * x[1] + b->U[3 * k + 2] * x[2];
  return 0;
}

/* Push unless it repeats the last point of the open component. */
static int push_new(builder *b, const double n[3], const double x[3]) {
  swarf_char_curve *cc = b->cc;
  if (cc->len > b->first) {
    const swarf_char_point *q = &cc->pts[cc->len - 1];
    if (memcmp(q->n, n, 3 * sizeof *n) == 0 && memcmp(q->x, x, 3 * sizeof *x) == 0) return 0;
  }
  return push(b, n, x);
}

/* Close the open component (repeat its first point) and count it. */
static int close_component(builder *b) {
  swarf_char_curve *cc = b->cc;
  if (cc->len == b->first) return 0;
  if (push_new(b, cc->pts[b->first].n, cc->pts[b->first].x) != 0) return -1;
  if (cc->ncomp + 2 > cc->start_cap) {
    size_t cap = 2 * cc->start_cap;
    void *mem = realloc(cc->start, cap * sizeof *cc->start);
    if (mem == NULL) return -1;
    cc->start = mem;
    cc->start_cap = cap;
  }
  cc->start[++cc->ncomp] = cc->len;
  b->first = cc->len;
  return 0;
}

/* Point of branch s at sigma. At a branch point (at_root) Delta is set to 0
 * so that both branches give the same point. Where the slice is degenerate
 * (a pole where the rim direction comes only from the limit) the parameter is
 * nudged toward `inward`. */
static int eval_point(const builder *b, double sigma, double s, int at_root, double inward,
                      double n[3], double x[3]) {
  swarf_char_slice sl;
  double nudge = 1e-10 * b->pr->sigma_end;
  for (int tries = 0; tries < 4; tries++, nudge *= 100.0) {
    swarf_char_slice_eval(b->pr, b->v, b->omega, sigma, &sl);
    if (at_root) sl.delta = 0.0;
    if (swarf_char_slice_point(b->pr, &sl, s, n, x) == 0) return 0;
    sigma += inward * nudge;
  }
  return -1;
}

static double seg_dist(const double p[3], const double a[3], const double c[3]) {
  double d[3], w[3], dd = 0.0, t = 0.0, r = 0.0;
  for (int k = 0; k < 3; k++) {
    d[k] = c[k] - a[k];
    w[k] = p[k] - a[k];
    dd += d[k] * d[k];
    t += d[k] * w[k];
  }
  t = dd > 0.0 ? t / dd : 0.0;
  t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
  for (int k = 0; k < 3; k++)
    r += (w[k] - t * d[k]) * (w[k] - t * d[k]);
  return sqrt(r);
}

/* One smooth piece [s0, s1] of a branch, run with tau in [0, 1]. Next to a
 * branch point sqrt(Delta) grows like sqrt(sigma - root): there sigma moves
 * quadratically in tau (sigma - root ~ tau^2), which makes the branch smooth
 * in tau (and the two branches one smooth curve through the branch point),
 * so that the chord error of equal tau steps is nearly uniform. */
typedef struct {
  double s0, s1;
  int root0, root1; /* the end is a branch point */
} piece;

static double piece_sigma(const piece *p, double tau) {
  double d = p->s1 - p->s0;
  if (p->root0 && p->root1) return p->s0 + d * tau * tau * (3.0 - 2.0 * tau);
  if (p->root0) return p->s0 + d * tau * tau;
  if (p->root1) return p->s1 - d * (1.0 - tau) * (1.0 - tau);
  return p->s0 + d * tau;
}

/* Append the points of branch s after (tau0, x0) up to (tau1, n1, x1). The
 * step is accepted when its middle point is within MARGIN * tol of the chord:
 * on a smooth arc the chord error is largest near the middle, and the margin
 * covers an uneven speed along the arc (the middle point then still sees at
 * least 3/4 of the largest error). Otherwise the middle distance d fixes the
 * count: the error falls with the square of the step, so k = sqrt(d / (AIM
 * tol)) equal steps should pass; each is checked the same way. */
static int refine(builder *b, const piece *p, double s, double tau0, const double x0[3],
                  double tau1, const double n1[3], const double x1[3], int depth) {
  double tm = 0.5 * (tau0 + tau1), nm[3], xm[3], d, prev = tau0, xp[3];
  int k;
  if (depth >= MAX_DEPTH || eval_point(b, piece_sigma(p, tm), s, 0, 0.0, nm, xm) != 0 ||
      (d = seg_dist(xm, x0, x1)) <= MARGIN * b->tol)
    return push_new(b, n1, x1);
  k = (int)ceil(sqrt(d / (AIM * b->tol)));
  k = k < 2 ? 2 : k > MAX_SPLIT ? MAX_SPLIT : k;
  memcpy(xp, x0, sizeof xp);
  for (int j = 1; j <= k; j++) {
    double tau = j == k ? tau1 : tau0 + (tau1 - tau0) * j / k, n[3], x[3];
    if (j == k)
      memcpy(n, n1, sizeof n), memcpy(x, x1, sizeof x);
    else if (2 * j == k)
      memcpy(n, nm, sizeof n), memcpy(x, xm, sizeof x), tau = tm;
    else if (eval_point(b, piece_sigma(p, tau), s, 0, 0.0, n, x) != 0)
      continue;
    if (refine(b, p, s, prev, xp, tau, n, x, depth + 1) != 0) return -1;
    memcpy(xp, x, sizeof xp);
    prev = tau;
  }
  return 0;
}

/* Branch s along piece p, forward (dir > 0: tau from 0 to 1) or backward.
 * The piece starts with SPAN_STEPS steps per sigma_end of its length (at
 * least MIN_STEPS), each refined. */
static int branch_piece(builder *b, const piece *p, double s, int dir) {
  int m = (int)ceil(SPAN_STEPS * (p->s1 - p->s0) / b->pr->sigma_end), first = 1;
  double x0[3], prev = dir > 0 ? 0.0 : 1.0;
  if (m < MIN_STEPS) m = MIN_STEPS;
  for (int i = 0; i <= m; i++) {
    double tau = dir > 0 ? (double)i / m : (double)(m - i) / m, n1[3], x1[3];
    int at_root = (tau == 0.0 && p->root0) || (tau == 1.0 && p->root1);
    double inward = tau == 0.0 ? 1.0 : tau == 1.0 ? -1.0 : 0.0;
    if (eval_point(b, piece_sigma(p, tau), s, at_root, inward, n1, x1) != 0) continue;
    if (first) {
      if (push_new(b, n1, x1) != 0) return -1;
      first = 0;
    } else if (refine(b, p, s, prev, x0, tau, n1, x1, 0) != 0) {
      return -1;
    }
    memcpy(x0, x1, sizeof x0);
    prev = tau;
  }
  return 0;
}

/* Split [lo, hi] at the kinks of phi (the ends of a cutter's side ruling),
 * where the branch has a corner; returns the number of pieces. */
static int split_pieces(const swarf_char_profile *pr, double lo, double hi, int root_lo,
                        int root_hi, piece *out) {
  double cut[SWARF_CHAR_MAX_PARTS] = {HALF_PI, HALF_PI + pr->plateau}, at = lo;
  int n = 0, root = root_lo, ncut = pr->is_qss ? 0 : 2;
  if (pr->npart > 0) {
    ncut = pr->npart - 1;
    for (int k = 0; k < ncut; k++)
      cut[k] = pr->part[k].s1;
  }
  for (int k = 0; k < ncut; k++) {
    if (!(cut[k] > at && cut[k] < hi)) continue;
    out[n++] = (piece){at, cut[k], root, 0};
    at = cut[k];
    root = 0;
  }
  out[n++] = (piece){at, hi, root, root_hi};
  return n;
}

static int component(builder *b, double lo, double hi, int root_lo, int root_hi) {
  piece p[SWARF_CHAR_MAX_PARTS + 1];
  int np = split_pieces(b->pr, lo, hi, root_lo, root_hi, p);
  for (int i = 0; i < np; i++)
    if (branch_piece(b, &p[i], 1.0, 1) != 0) return -1;
  for (int i = np - 1; i >= 0; i--)
    if (branch_piece(b, &p[i], -1.0, -1) != 0) return -1;
  return close_component(b);
}

static int compute_general(builder *b) {
  double ends[MAX_ROOTS + 2];
  int nr = swarf_char_delta_roots(b->pr, b->v, b->omega, ends + 1, MAX_ROOTS);
  if (nr > MAX_ROOTS) nr = MAX_ROOTS;
  ends[0] = 0.0;
  ends[nr + 1] = b->pr->sigma_end;
  for (int i = 0; i <= nr; i++) {
    if (!(ends[i + 1] > ends[i])) continue;
    if (!swarf_char_delta_positive(b->pr, b->v, b->omega, 0.5 * (ends[i] + ends[i + 1]))) continue;
    if (component(b, ends[i], ends[i + 1], i > 0, i < nr) != 0) return -1;
  }
  return 0;
}

/* One horizontal circle of normals n = (cos, sin, 0): points at radius rho,
 * height zc. */
static int rim_circle(builder *b, double rho, double zc) {
  double cosv, m;
  cosv = fabs(rho) > b->tol ? 1.0 - b->tol / fabs(rho) : -1.0;
  m = ceil(3.14159265358979323846 / acos(cosv));
  if (m < 8) m = 8;
  for (int i = 0; i < (int)m; i++) {
    double th = 6.28318530717958647692 * i / m;
    double n[3] = {cos(th), sin(th), 0.0}, x[3];
    x[0] = rho * n[0];
    x[1] = rho * n[1];
    x[2] = zc;
    if (push(b, n, x) != 0) return -1;
  }
  return close_component(b);
}

/* Translation along the axis: the whole side is characteristic. */
static int compute_axial(builder *b) {
  const swarf_char_profile *pr = b->pr;
  if (pr->is_qss) return rim_circle(b, pr->q0, pr->q1);
  if (pr->npart > 0) { /* the part at the equator theta = pi/2 */
    for (int k = 0; k < pr->npart; k++) {
      const swarf_char_part *q = &pr->part[k];
      if (q->plateau && fabs(q->th0 - HALF_PI) < 1e-12) {
        if (rim_circle(b, q->r0, q->z0) != 0) return -1;
        return rim_circle(b, q->r1, q->z1);
      }
      if (!q->plateau && q->th0 <= HALF_PI && q->th1 >= HALF_PI)
        return rim_circle(b, q->a + q->R, q->c);
    }
    return 0;
  }
  if (rim_circle(b, pr->a + pr->R, pr->R) != 0) return -1;
  if (pr->L - 2.0 * pr->R > 0.0) return rim_circle(b, pr->a + pr->R, pr->L - pr->R);
  return 0;
}

/* Append the curves of profile pr to cc (which the caller has reset). */
static int compute_into(swarf_char_curve *cc, const swarf_char_profile *pr, const double t[3],
                        const double U[9], const double v[3], const double omega[3], double tol) {
  builder b = {cc, pr, v, omega, t, U, tol > 0.0 ? tol : 1e-3 * pr->scale, cc->len};
  double l2 = pr->scale * pr->scale, lat, all;
  lat = v[0] * v[0] + v[1] * v[1] + (omega[0] * omega[0] + omega[1] * omega[1]) * l2;
  all = lat + v[2] * v[2] + omega[2] * omega[2] * l2;
  if (!(all > 0.0) || lat + v[2] * v[2] <= 1e-24 * all) return 0; /* still, or turning in place */
  if (lat <= 1e-24 * all) return compute_axial(&b);
  return compute_general(&b);
}

static int compute(swarf_char_curve *cc, const swarf_char_profile *pr, const double t[3],
                   const double U[9], const double v[3], const double omega[3], double tol) {
  if (cc == NULL || t == NULL || U == NULL || v == NULL || omega == NULL) return -1;
  if (reset(cc) != 0) return -1;
  if (compute_into(cc, pr, t, U, v, omega, tol) != 0) return -1;
  return (int)cc->ncomp;
}

/* The sharp rims of a non-convex QSS piece (its profile's cusps, where the
 * outline turns back: zero-angle edges). Their normal cone is the half-plane
 * of meridian directions d with d . tau >= 0 (tau pointing out of the
 * spike), which always holds a direction orthogonal to the rim's velocity:
 * every rim point is characteristic. Each is a closed circle with that
 * normal at each point (the QSS centred: x as compute_pieces passes it). */
static int cusp_rims(builder *b, const swarf_profile_piece *pc) {
  double c2;
  if (pc->kind != SWARF_PIECE_QSS || pc->q2 == 0.0) return 0;
  c2 = (pc->q0 + 2.0 * pc->q2) / (3.0 * pc->q2);
  if (!(c2 > 0.0 && c2 < 1.0)) return 0;
  for (int side = -1; side <= 1; side += 2) {
    double sc = side * sqrt(c2), y[2], yn[2], tau[2], tl, m, cosv;
    double e = sc > 0.0 ? -1e-4 : 1e-4;
    swarf_profile_qss_point(pc, sc, y);
    swarf_profile_qss_point(pc, sc + e, yn);
    tau[0] = y[0] - yn[0], tau[1] = y[1] - yn[1], tl = hypot(tau[0], tau[1]);
    tau[0] /= tl, tau[1] /= tl;
    y[1] -= pc->lift; /* the centred QSS */
    cosv = y[0] > b->tol ? 1.0 - b->tol / y[0] : -1.0;
    m = ceil(3.14159265358979323846 / acos(cosv));
    if (m < 8) m = 8;
    for (int i = 0; i < (int)m; i++) {
      double ph = 6.28318530717958647692 * i / m, er[2] = {cos(ph), sin(ph)}, x[3], wx[3], nu[3];
      double nr, nz, nm, n[3];
      x[0] = y[0] * er[0], x[1] = y[0] * er[1], x[2] = y[1];
      wx[0] = b->omega[1] * x[2] - b->omega[2] * x[1];
      wx[1] = b->omega[2] * x[0] - b->omega[0] * x[2];
      wx[2] = b->omega[0] * x[1] - b->omega[1] * x[0];
      for (int k = 0; k < 3; k++)
        nu[k] = b->v[k] + wx[k];
      nr = -nu[2], nz = nu[0] * er[0] + nu[1] * er[1]; /* orthogonal to the meridian part of nu */
      nm = hypot(nr, nz);
      if (nm > 0.0)
        nr /= nm, nz /= nm;
      else
        nr = tau[0], nz = tau[1];
      if (nr * tau[0] + nz * tau[1] < 0.0) nr = -nr, nz = -nz;
      n[0] = nr * er[0], n[1] = nr * er[1], n[2] = nz;
      if (push(b, n, x) != 0) return -1;
    }
    if (close_component(b) != 0) return -1;
  }
  return 0;
}

/* A profile cutter: the curves of every piece, one after the other. A QSS
 * piece lifted by l along the axis is the QSS at the point (0, 0, l): it
 * moves with v + omega x (0, 0, l), and its points shift up by l. */
static int compute_pieces(swarf_char_curve *cc, const swarf_cutter *c, const double t[3],
                          const double U[9], const double v[3], const double omega[3], double tol) {
  if (reset(cc) != 0) return -1;
  for (int i = 0; i < c->npieces; i++) {
    const swarf_profile_piece *pc = &c->piece[i];
    swarf_char_profile pr;
    double l = pc->kind == SWARF_PIECE_QSS ? pc->lift : 0.0;
    double vp[3] = {v[0] + omega[1] * l, v[1] - omega[0] * l, v[2]};
    double tp[3] = {t[0] + U[2] * l, t[1] + U[5] * l, t[2] + U[8] * l};
    size_t first = cc->len;
    swarf_char_profile_piece(&pr, pc);
    if (compute_into(cc, &pr, tp, U, vp, omega, tol) != 0) return -1;
    if (!pc->convex) {
      builder b = {cc, &pr, vp, omega, tp, U, tol > 0.0 ? tol : 1e-3 * pr.scale, cc->len};
      if (cusp_rims(&b, pc) != 0) return -1;
    }
    for (size_t k = first; k < cc->len; k++)
      cc->pts[k].x[2] += l;
  }
  return (int)cc->ncomp;
}

/* compute()'s count as a status (its arguments were checked: -1 is memory). */
static swarf_status computed(int n) {
  return n >= 0 ? SWARF_OK : SWARF_ERR_MEMORY;
}

swarf_status swarf_char_curve_compute(swarf_char_curve *cc, const swarf_cutter *c,
                                      const double t[3], const double U[9], const double v[3],
                                      const double omega[3], double tol) {
  swarf_char_profile pr;
  if (cc == NULL || c == NULL || t == NULL || U == NULL || v == NULL || omega == NULL)
    return SWARF_ERR_ARG;
  if (!c->fast) return computed(compute_pieces(cc, c, t, U, v, omega, tol));
  swarf_char_profile_cutter(&pr, c);
  return computed(compute(cc, &pr, t, U, v, omega, tol));
}

swarf_status swarf_char_curve_compute_qss(swarf_char_curve *cc, const swarf_qss *q,
                                          const double t[3], const double U[9], const double v[3],
                                          const double omega[3], double tol) {
  swarf_char_profile pr;
  if (cc == NULL || q == NULL || t == NULL || U == NULL || v == NULL || omega == NULL)
    return SWARF_ERR_ARG;
  swarf_char_profile_qss(&pr, q);
  return computed(compute(cc, &pr, t, U, v, omega, tol));
}
