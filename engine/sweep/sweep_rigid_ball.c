/* SPDX-License-Identifier: MPL-2.0 */
/* sweep_rigid_ball.c -- the volume swept by a ball end mill under a rigid
 * motion with rotation, built from the characteristic circles at the time
 * steps: per point a local refinement certified by convexity
 * instead of the general search over the move (sweep_rigid.c). Flat and
 * bull end mills take it too, as bounds (body_kind, at the end).
 *
 * The cutter is a capsule: the points within R of its axis segment from the
 * ball's centre (0, 0, R) up to (0, 0, L - R) (swarf_cutter_sdf_rz). Under
 * x' = t(a) + U(a) x the centre runs on c(a) = t + U (0, 0, R) with
 * c' = U u, u = v + omega x (0, 0, R), and k(a) = U e_z is the tool axis.
 * With d = p - c and h = k . d (p's height above the ball's equator plane)
 * the squared distance to the axis segment is
 *   G = |d|^2          where h <= 0 (the ball: inside and out),
 *   G = |e|^2, e = d - h k, where 0 < h < L - 2R (the shank),
 * and the sweep's value is min over a of sqrt(G) - R. G is C^1 with
 * G' = -2 e . X', X' = c' + h+ k' the velocity of the axis point nearest p:
 * zero where p lies in the plane of the ball's characteristic circle
 * {|x - c| = R, (x - c) . c' = 0} of that time (or on the shank's
 * characteristic lines). G'' is bounded below piece by piece:
 *   ball:  G'' = 2 (|c'|^2 - d . c'')  >= 2 (cvmin^2 - D ca),
 *   shank: G'' = 2 (|X'_xy|^2 + 2 (k' . e) u_z - (k' . e)^2 - e . (c'' + h k''))
 *              >= 2 (P^2 - 2 W E ck - W^2 E^2 - E (ca + H (W^2 + W'))),
 * X'_xy = u_xy + h (omega_y, -omega_x) the part of X' across the axis (cutter
 * frame), P its least norm over h at the steps less its change over half a
 * step, D >= |d|, E >= |e| and H >= h over the move (from the time steps,
 * Lipschitz in cv, cv + W D and W D + ck), cv, cvmin, ca, ck the per-move
 * bounds of sweep_rigid_setup.c (|c'| above and below, |c''|, |u_z|), W, W'
 * those of |omega| and its derivative. G' is continuous (the pieces meet at
 * h = 0 with equal slopes), so G'' >= mu on each piece makes G convex with
 * modulus mu. When mu > 0 the sign of G' at the time steps (the pose table:
 * which side of each step's circle plane p lies on) brackets the one
 * minimiser, or it is an end; Illinois regula falsi on G' inside the
 * bracket finds it (at the table's step nearest its point while the bracket
 * holds one, then poses off the table: 30 % fewer of those, ~850
 * instructions each against ~80 for a step), and the quadratic minorants of
 * curvature mu through the bracket's ends certify the value (to TIGHT,
 * below the general search's 1e-6 mm). The two ends come first: the lesser
 * at or below lo, or a lower bound at or above hi, ends the work before any
 * bound on G'' from below (their Lipschitz bound, then the concave minorants
 * through them with G'' >= -K, K from the bounds above without P^2: 24 M of
 * the impeller's 43 M calls at 0.2 mm, 15.5 M of them by the minorants); then the
 * bounds taken over the whole move (most points: a short move's G is convex
 * by those alone, and the nearest instant is often an end); then the steps
 * (every sqrt(n)-th first on long moves), the bounds taken only over the
 * window of steps whose Lipschitz bound (the nearest point of the axis
 * segment moves at most cv + W (L - 2R)) is below the best step's value:
 * over the window's coarse steps first (their spacing in the bounds), over
 * all its steps only if those do not certify it.
 * Where convexity is not certified that Lipschitz bound, or the concave
 * minorants step by step, may still put the value at or above hi; otherwise (also: p above the top
 * of the axis segment at some time, a window of more than MAXW steps, no pose table, no
 * convergence) the answer is -1 and the caller runs the general search, so
 * exactness never rests on this path's assumptions. Where the whole move's
 * convexity gave the value, a plane below the sweep within a radius of p
 * comes with it on request (ball_plane; swarf_sweep_range_plane). The window (lo, hi) is
 * swarf_sweep_rigid_sdf_range's: a value at or below lo (a genuine one, from
 * a pose) ends the work, and so does a lower bound at or above hi. Nothing
 * allocates; pure function of the sweep and p.
 */
#include <math.h>

#include "engine_private.h"

#define TIGHT 1e-7 /* certified accuracy, mm */
#define MAXW 64    /* time steps in the window at most (more: the general search) */
#define COARSE 16  /* moves of more steps: every sqrt(n)-th step first */
#define MAXC 32    /* coarse steps at most (n <= 512: sqrt(n) - 1 <= n / sqrt(n) <= 24) */
#define ITER 24    /* regula falsi steps at most */

typedef struct {
  double a, G, dG, h, f; /* time, squared distance to the axis segment, G', h, |d|^2 */
  const swarf_pose *P;   /* a table's pose (shank_mu reads its v and omega), or NULL */
} bsample;

typedef struct {
  const double *p;
  double R, off, seg;      /* capsule radius; its axis segment's start above the tip and length */
  double mu;               /* G'' >= mu > 0 over the move */
  const swarf_pose *table; /* the poses at the N + 1 time steps i / N */
  const swarf_pose_rates *rates; /* and their rates */
  int N;
  bsample *bs;      /* non-NULL: bwindow's refinements keep their best sample in it */
  swarf_pose *keep; /* and its pose there when it is off the table */
} bctx;

typedef enum { B_VALUE, B_BELOW, B_ABOVE, B_FAIL } bkind;

static inline double min2(double a, double b) {
  return a < b ? a : b;
}

static inline double max2(double a, double b) {
  return a > b ? a : b;
}

/* The sample at time a from the pose there and its rates: c = t + R k, c' = t' + R k'
 * (U (omega x (0, 0, R))), h' = k' . d - k . c' = k' . d - v_z (k . t' = v_z,
 * k . k' = 0). */
static bsample bsample_at(const bctx *b, double a, const swarf_pose *P,
                          const swarf_pose_rates *Pr) {
  const double *U = P->U, *td = Pr->tdot, *kd = Pr->kdot, *p = b->p, R = b->off;
  const double k[3] = {U[2], U[5], U[8]};
  const double d[3] = {p[0] - P->t[0] - R * k[0], p[1] - P->t[1] - R * k[1],
                       p[2] - P->t[2] - R * k[2]};
  const double cp[3] = {td[0] + R * kd[0], td[1] + R * kd[1], td[2] + R * kd[2]};
  const double f = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  bsample r;
  r.a = a, r.P = P;
  r.h = k[0] * d[0] + k[1] * d[1] + k[2] * d[2];
  r.f = r.G = f;
  r.dG = -2.0 * (d[0] * cp[0] + d[1] * cp[1] + d[2] * cp[2]);
  if (r.h > 0.0) { /* the shank's segment (its top end: h >= seg) */
    double z = r.h < b->seg ? r.h : b->seg;
    double hp = kd[0] * d[0] + kd[1] * d[1] + kd[2] * d[2] - P->v[2];
    r.G = f - z * (2.0 * r.h - z);
    r.dG -= 2.0 * z * hp; /* z = h: G' = f' - 2 h h'; z = seg: the same (k . k' = 0) */
    if (r.G < 0.0) r.G = 0.0;
  }
  return r;
}

/* The sample at time step i (of the N + 1 in the pose table). */
static bsample bstep(const bctx *b, int i) {
  return bsample_at(b, (double)i / b->N, &b->table[i], &b->rates[i]);
}

/* Minimum over [l, r] of the parabola f0 + g0 (x - x0) + mu/2 (x - x0)^2. */
static double qmin(double f0, double g0, double x0, double mu, double l, double r) {
  double x = x0 - g0 / mu;
  x = x < l ? l : x > r ? r : x;
  return f0 + (x - x0) * (g0 + 0.5 * mu * (x - x0));
}

/* Lower bound of G over [A.a, B.a]: the minimum of the larger of the two
 * minorants T_A, T_B of curvature mu through the ends (T_A - T_B is linear:
 * T_A is the larger up to xs, T_B after). */
static double bracket_lb(const bctx *b, const bsample *A, const bsample *B) {
  double mu = b->mu, w = B->a - A->a, xs = B->a;
  double c0 = A->G - (B->G - B->dG * w + 0.5 * mu * w * w), c1 = A->dG - B->dG + mu * w;
  if (c1 < 0.0) xs = A->a - c0 / c1;
  xs = xs < A->a ? A->a : xs > B->a ? B->a : xs;
  return min2(qmin(A->G, A->dG, A->a, mu, A->a, xs), qmin(B->G, B->dG, B->a, mu, xs, B->a));
}

/* The sample at the time step nearest x strictly inside (a0, a1), from
 * the pose table; 0 if there is none (the bracket lies within one step). */
static int table_step(const bctx *b, double a0, double a1, double x, bsample *M) {
  double t1 = a1 * b->N; /* times in [0, 1]: (int) truncates as floor */
  int i0 = (int)(a0 * b->N) + 1, i1 = (int)t1 - ((double)(int)t1 == t1), i = (int)(x * b->N + 0.5);
  if (i1 > b->N - 1) i1 = b->N - 1;
  i = i < i0 ? i0 : i > i1 ? i1 : i;
  if (i0 > i1 || !((double)i / b->N > a0 && (double)i / b->N < a1)) return 0;
  *M = bstep(b, i);
  return 1;
}

/* The minimum over the move, its minimiser inside [A.a, B.a] (A.dG < 0 <
 * B.dG): Illinois regula falsi on G' until the minorants certify the best
 * sample to TIGHT (B_VALUE), or it is at most lo (B_BELOW), or the bound is
 * at least hi (B_ABOVE: *v the bound). With bs, the best sample there, its
 * pose in *keep when it is off the table. */
static bkind brefine(const bctx *b, const swarf_motion *m, bsample A, bsample B, double lo,
                     double hi, double *v, double *at, bsample *bs, swarf_pose *keep) {
  bsample best = A.G <= B.G ? A : B;
  double gA = A.dG, gB = B.dG;
  int side = 0;
  for (int it = 0;; it++) {
    double lb = sqrt(max2(bracket_lb(b, &A, &B), 0.0)) - b->R, vb = sqrt(best.G) - b->R, x;
    swarf_pose P;
    swarf_pose_rates Pr;
    bsample M;
    *at = best.a;
    if (vb <= lo || vb - lb <= TIGHT) {
      *v = vb;
      if (bs != NULL) *bs = best;
      return vb <= lo ? B_BELOW : B_VALUE;
    }
    if (lb >= hi) {
      *v = lb;
      return B_ABOVE;
    }
    if (it == ITER || !(B.a - A.a > 1e-15)) return B_FAIL;
    x = (A.a * gB - B.a * gA) / (gB - gA);
    if (!(x > A.a && x < B.a)) x = 0.5 * (A.a + B.a);
    if (!table_step(b, A.a, B.a, x, &M)) {
      swarf_motion_pose(m, x, &P);
      swarf_pose_rates_of(&P, &Pr);
      M = bsample_at(b, x, &P, &Pr);
      M.P = NULL; /* P ends with this iteration */
    }
    if (M.G < best.G) {
      best = M;
      if (bs != NULL && M.P == NULL) *keep = P, best.P = keep;
    }
    if (M.dG < 0.0) {
      A = M, gA = M.dG;
      if (side < 0) gB *= 0.5;
      side = -1;
    } else {
      B = M, gB = M.dG;
      if (side > 0) gA *= 0.5;
      side = 1;
    }
  }
}

/* The minimum over the move from the steps smp[0..n] (G convex); with bs, the sample
 * the value is of (B_VALUE; its pose in *keep if off the table). */
static bkind bmin(const bctx *b, const swarf_motion *m, const bsample *smp, int n, double lo,
                  double hi, double *v, double *at, bsample *bs, swarf_pose *keep) {
  int i = 0;
  while (i <= n && smp[i].dG < 0.0)
    i++;
  if (i == 0 || i > n) { /* G' >= 0 at the start, or < 0 at the end: an end */
    const bsample *e = i == 0 ? &smp[0] : &smp[n];
    *v = sqrt(e->G) - b->R, *at = e->a;
    if (bs != NULL) *bs = *e;
    return *v <= lo ? B_BELOW : B_VALUE;
  }
  return brefine(b, m, smp[i - 1], smp[i], lo, hi, v, at, bs, keep);
}

/* Least |u + h w|^2 over h in [h0, h1] (2-D: the squared distance from the
 * origin to a segment). */
static double seg_norm2(const double u[2], const double w[2], double h0, double h1) {
  double ww = w[0] * w[0] + w[1] * w[1], h = h0, x, y;
  if (ww > 0.0) h = -(u[0] * w[0] + u[1] * w[1]) / ww;
  h = h < h0 ? h0 : h > h1 ? h1 : h;
  x = u[0] + h * w[0], y = u[1] + h * w[1];
  return x * x + y * y;
}

/* The shank's piece of the bound on G'' where h is in [h0, h1] (0 <= h0):
 * 2 (P^2 - 2 W E ck - W^2 E^2 - E (ca + h1 (W^2 + W'))) with P <= |X'_xy|
 * (at the steps, less its change over half a step: |u'| <= ca + W cv,
 * |w'| <= W') and E >= |e| = sqrt(G) (Lipschitz in cv + W D). */
static double shank_mu(const swarf_sweep_rigid *x, double R, const bsample *smp, int n, double w,
                       double D, double h0, double h1) {
  double P2 = INFINITY, E2 = 0.0, W = x->w, P, E;
  for (int i = 0; i <= n; i++) {
    const double *v = smp[i].P->v, *o = smp[i].P->omega;
    const double u[2] = {v[0] + R * o[1], v[1] - R * o[0]}, wv[2] = {o[1], -o[0]};
    P2 = min2(P2, seg_norm2(u, wv, h0, h1));
    E2 = max2(E2, smp[i].f - smp[i].h * smp[i].h);
  }
  P = sqrt(P2) - 0.5 * w * (x->ca + W * x->cv + h1 * x->wd);
  if (!(P > 0.0)) return 0.0;
  E = sqrt(E2) + 0.5 * w * (x->cv + W * D);
  return 2.0 * (P * P - 2.0 * W * E * x->ck - W * W * E * E - E * (x->ca + h1 * (W * W + x->wd)));
}

/* mu from the steps, or 0 when G may not be convex: D >= |d| over the move
 * (Lipschitz in cv), h in [h0, h1] (Lipschitz in W D + ck: h' = k' . d - k .
 * c'), the ball's piece where h0 <= 0, the shank's where h1 > 0. */
static double curvature(const swarf_sweep_rigid *x, const bctx *b, const bsample *smp, int n,
                        double w) {
  double F = 0.0, hlo = INFINITY, hhi = -INFINITY, mu = INFINITY, D, lh;
  for (int i = 0; i <= n; i++) {
    F = max2(F, smp[i].f);
    hlo = min2(hlo, smp[i].h), hhi = max2(hhi, smp[i].h);
  }
  D = sqrt(F) + 0.5 * x->cv * w;
  lh = 0.5 * (x->w * D + x->ck) * w;
  hlo -= lh, hhi += lh;
  if (!(hhi < b->seg)) return 0.0; /* the top end may be nearest */
  if (hlo <= 0.0 && !((mu = 2.0 * (x->cvmin * x->cvmin - D * x->ca)) > 0.0)) return 0.0;
  if (hhi > 0.0) mu = min2(mu, shank_mu(x, b->off, smp, n, w, D, max2(hlo, 0.0), hhi));
  return mu > 0.0 ? mu : 0.0;
}

/* K >= -G'' over [A.a, B.a] (w wide) from its ends (G semiconcave: the
 * bounds of the header without the speed across the axis, P^2 >= 0):
 * D >= |d| >= |e|, h <= hhi (as curvature), the ball's piece 2 D ca, the
 * shank's 2 (2 W D ck + W^2 D^2 + D (ca + H (W^2 + W'))), H = min(hhi,
 * L - 2R), and where p may lie above the axis segment's top
 * t = c + (L - 2R) k (G = |p - t|^2) 2 (D + L - 2R) |t''|,
 * |t''| <= ca + (L - 2R) (W^2 + W'). */
static inline double semiconcavity(const swarf_sweep_rigid *x, const bctx *b, const bsample *A,
                                   const bsample *B, double w) {
  double W = x->w, D = sqrt(max2(A->f, B->f)) + 0.5 * x->cv * w, kk = W * W + x->wd;
  double hhi = max2(A->h, B->h) + 0.5 * (W * D + x->ck) * w, H = min2(hhi, b->seg), K;
  if (hhi <= 0.0) return 2.0 * D * x->ca;
  K = 2.0 * (2.0 * W * D * x->ck + W * W * D * D + D * (x->ca + H * kk));
  if (hhi >= b->seg) K = max2(K, 2.0 * (D + b->seg) * (x->ca + b->seg * kk));
  return max2(K, 2.0 * D * x->ca);
}

/* Lower bound of G over [A.a, B.a] (w wide) with G'' >= -K: the least of the
 * larger of the concave minorants T_A (t) = GA + GA' t - K t^2 / 2 and
 * T_B (t) = GB - GB' (w - t) - K (w - t)^2 / 2 (each concave: at 0, w or
 * where they cross, T_A - T_B being linear in t). */
static inline double concave_lb(const bsample *A, const bsample *B, double K) {
  double w = B->a - A->a, GA = A->G, gA = A->dG, GB = B->G, gB = B->dG, Kw = 0.5 * K * w, t;
  double c1 = gA - gB - K * w, c0 = GA - GB + w * (gB + Kw);
  double lb = min2(max2(GA, GB - w * (gB + Kw)), max2(GA + w * (gA - Kw), GB));
  if (c1 != 0.0 && (t = -c0 / c1) > 0.0 && t < w)
    lb = min2(lb, max2(GA + t * (gA - 0.5 * K * t), GB - (w - t) * (gB + 0.5 * K * (w - t))));
  return lb;
}

/* The lower bound of sqrt(G) over [A.a, B.a] (w wide): the larger of the
 * Lipschitz bound from sqrt(G) at the ends (sA, sB; lip: half the step's
 * travel of the nearest axis point) and the concave minorants' (computed
 * only where the first is below `need`). */
static inline double interval_lb(const swarf_sweep_rigid *x, const bctx *b, const bsample *A,
                                 const bsample *B, double w, double sA, double sB, double lip,
                                 double need) {
  double l = 0.5 * (sA + sB) - lip;
  if (l >= need) return l;
  return max2(l, sqrt(max2(concave_lb(A, B, semiconcavity(x, b, A, B, w)), 0.0)));
}

/* Without convexity: the least value at the steps smp[0..n] (w apart) if it
 * is at most lo (B_BELOW), or a lower bound over the move if it is at least
 * hi (B_ABOVE: per step interval_lb, the nearest point of the axis segment
 * moving at most cv + W (L - 2R)); else B_FAIL. */
static bkind bbounds(const swarf_sweep_rigid *x, const bctx *b, const bsample *smp, int n, double w,
                     double lo, double hi, double *v, double *at) {
  double lip = 0.5 * (x->cv + x->w * b->seg) * w, lb = INFINITY, s0 = sqrt(smp[0].G), best = s0;
  int ib = 0;
  for (int i = 0; i < n; i++) {
    double s1 = sqrt(smp[i + 1].G);
    if (lb - b->R >= hi)
      lb = min2(lb, interval_lb(x, b, &smp[i], &smp[i + 1], w, s0, s1, lip, hi + b->R));
    if (s1 < best) best = s1, ib = i + 1;
    s0 = s1;
  }
  *v = best - b->R, *at = smp[ib].a;
  if (*v <= lo) return B_BELOW;
  *v = lb - b->R;
  return *v >= hi ? B_ABOVE : B_FAIL;
}

/* The two ends alone, before any bound on G'' from below: the lesser at or
 * below lo (B_BELOW), or a lower bound over the move at or above hi
 * (B_ABOVE): their Lipschitz bound (as bbounds), or the concave minorants
 * through them; else B_FAIL. */
static bkind bends(const swarf_sweep_rigid *x, const bctx *b, const bsample *smp, double lo,
                   double hi, double *v, double *at) {
  double s0 = sqrt(smp[0].G), s1 = sqrt(smp[1].G);
  int i = s1 < s0;
  *v = (i ? s1 : s0) - b->R, *at = smp[i].a;
  if (*v <= lo) return B_BELOW;
  *v = interval_lb(x, b, &smp[0], &smp[1], 1.0, s0, s1, 0.5 * (x->cv + x->w * b->seg), hi + b->R) -
       b->R;
  return *v >= hi ? B_ABOVE : B_FAIL;
}

/* Every S-th of the n steps into c[0..nc] and their distances to the axis
 * segment into sq; returns the index of the least. */
static int bcoarse(const bctx *b, int n, int S, int nc, bsample *c, double *sq) {
  int jb = 0;
  for (int j = 0; j <= nc; j++) {
    int i = j * S < n ? j * S : n;
    c[j] = bstep(b, i);
    sq[j] = sqrt(c[j].G);
    if (j == 0 || sq[j] < sq[jb]) jb = j;
  }
  return jb;
}

/* The time steps that can hold the minimum: every S-th step (S ~ sqrt(n) on
 * long moves) first, then every step between the first and the last coarse
 * interval whose Lipschitz bound is below the best coarse value (and the
 * best step). Where more than MAXW steps remain or convexity over them is
 * not certified, the coarse steps' bounds decide if they can (bbounds). */
static bkind bwindow(bctx *b, const swarf_sweep *s, int n, double lo, double hi, double *v,
                     double *at) {
  const swarf_sweep_rigid *x = &swarf_sweep_cdata(s)->u.rigid;
  int S = n <= COARSE ? 1 : (int)sqrt((double)n), nc = (n + S - 1) / S, jb, j0 = -1, j1 = -1;
  bsample c[MAXC + 1], smp[MAXW + 1];
  double sq[MAXC + 1], lip = 0.5 * (x->cv + x->w * b->seg) * S / n;
  if (nc < 1 || nc > MAXC) return B_FAIL;
  jb = bcoarse(b, n, S, nc, c, sq);
  for (int j = 0; j < nc; j++)
    if (0.5 * (sq[j] + sq[j + 1]) - lip < sq[jb]) j0 = j0 < 0 ? j : j0, j1 = j + 1;
  if (j0 < 0) { /* nothing between the steps below the best: it is the minimum */
    *v = sq[jb] - b->R, *at = c[jb].a;
    return *v <= lo ? B_BELOW : B_VALUE;
  }
  j0 = j0 < jb ? j0 : jb, j1 = j1 > jb ? j1 : jb;
  if (S > 1) { /* convex over the coarse window: the refinement takes the steps it needs */
    b->mu = curvature(x, b, &c[j0], j1 - j0, (double)S / n);
    if (b->mu > 0.0) return bmin(b, s->motion, &c[j0], j1 - j0, lo, hi, v, at, b->bs, b->keep);
  }
  j0 *= S, j1 = j1 * S < n ? j1 * S : n; /* now steps */
  if (j1 - j0 <= MAXW) {
    for (int i = j0; i <= j1; i++)
      smp[i - j0] = bstep(b, i);
    b->mu = curvature(x, b, smp, j1 - j0, 1.0 / n);
    if (b->mu > 0.0) return bmin(b, s->motion, smp, j1 - j0, lo, hi, v, at, b->bs, b->keep);
  }
  return bbounds(x, b, c, nc, (double)S / n, lo, hi, v, at);
}

/* A plane below the sweep's sdf within r of p, from the whole move's convexity (G'' >= mu
 * over [0, 1] at p) and the sample bs the value came from, at time a_b: for q = p + delta,
 * |delta| <= r, and every time a (t = a - a_b):
 *   G_q(a) >= G_p(a) + 2 delta . e_p(a)   (the nearest point of a convex set: the segment)
 *          >= G_b + G'_b t + mu t^2 / 2 + 2 delta . e_b - 2 r L |t|
 *          >= G_b - Q + 2 delta . e_b,
 * L >= |e_p'| the speed of p's nearest point of the segment, c + z k (z = clamp(h, 0, L -
 * 2R)): cv, and where h may be positive W D + ck (|z'| <= |h'|) and W Z (Z >= z); Q the
 * larger of the least values of the quadratic in t on either side of a_b within [0, 1]:
 * (2 r L -+ G'_b)^2 / (2 mu) where that is positive (at an end the value is often an end's,
 * G' pointing out of the move: no loss on that side). So the sweep's sdf at q is at least
 * sqrt(A + x) - R, A = G_b - Q, x = 2 delta . e_b in [-2 r E, 2 r E] (E = |e_b|), and the
 * chord of the concave sqrt over that interval is the plane: (s- + s+) / 2 - R + delta .
 * e_b (s+ - s-) / (2 r E). Rounding (1e-15 relative) stays far below the removal's margin.
 * 1 when given. */
static int ball_plane(const swarf_sweep_rigid *x, const bctx *b, const bsample *ends,
                      const bsample *bs, double r, double *pd, double g[3]) {
  const double *U = bs->P->U, *t = bs->P->t, k3[3] = {U[2], U[5], U[8]};
  const double z = bs->h <= 0.0 ? 0.0 : bs->h < b->seg ? bs->h : b->seg, zc = b->off + z;
  const double e[3] = {b->p[0] - t[0] - zc * k3[0], b->p[1] - t[1] - zc * k3[1],
                       b->p[2] - t[2] - zc * k3[2]}; /* p less its nearest axis point */
  const double W = x->w, D = sqrt(max2(ends[0].f, ends[1].f)) + 0.5 * x->cv;
  const double hhi = max2(ends[0].h, ends[1].h) + 0.5 * (W * D + x->ck); /* as curvature */
  const double L = x->cv + (hhi > 0.0 ? W * D + x->ck + W * min2(hhi, b->seg) : 0.0);
  const double E = sqrt(bs->G), up = bs->a < 1.0 ? max2(2.0 * r * L - bs->dG, 0.0) : 0.0;
  const double down = bs->a > 0.0 ? max2(2.0 * r * L + bs->dG, 0.0) : 0.0, k = max2(up, down);
  const double A = bs->G - k * k / (2.0 * b->mu), lo2 = A - 2.0 * r * E;
  if (!(r > 0.0) || !(E > 0.0) || !(lo2 > 0.0)) return 0;
  const double sl = sqrt(lo2), sh = sqrt(A + 2.0 * r * E), sg = (sh - sl) / (2.0 * r * E);
  *pd = 0.5 * (sl + sh) - b->R;
  for (int i = 0; i < 3; i++)
    g[i] = sg * e[i];
  return 1;
}

/* A flat or bull end mill's own value at time a, for the capsule's result there
 * (ball_eval): at the pose P if given (the refinement's), else a table step's if a is
 * one. */
static double body_at(const swarf_sweep *s, const bctx *b, double a, const swarf_pose *P) {
  const int i = (int)(a * b->N + 0.5);
  swarf_pose off;
  double d[3], q[3], g[3];
  if (P == NULL && (double)i / b->N == a) P = &b->table[i];
  if (P == NULL) {
    swarf_motion_pose(s->motion, a, &off);
    P = &off;
  }
  for (int k = 0; k < 3; k++)
    d[k] = b->p[k] - P->t[k];
  for (int k = 0; k < 3; k++)
    q[k] = P->U[k] * d[0] + P->U[3 + k] * d[1] + P->U[6 + k] * d[2];
  return swarf_cutter_sdf_grad(s->cutter, q, g); /* the general search's instance value */
}

/* A flat or bull end mill lies inside the capsule of radius D/2 about its axis from the
 * corner radius up (ball = 2), and shares that capsule's side: the capsule's value is a
 * lower bound of the cutter's everywhere (kept: B_ABOVE, and its plane), and the cutter's
 * own at the capsule's time a its value where the two agree (to TIGHT: both certified to
 * 2 TIGHT) or its bound at or below lo. Otherwise (the bottom or a corner nearest) B_FAIL. */
static bkind body_kind(const swarf_sweep *s, const bctx *b, bkind kind, double lo, double *v,
                       double a, const bsample *bs) {
  if (kind == B_ABOVE || kind == B_FAIL) return kind;
  const double u = body_at(s, b, a, bs->a == a ? bs->P : NULL);
  if (kind == B_BELOW) return u <= lo ? (*v = u, B_BELOW) : B_FAIL;
  return u - *v <= TIGHT ? (*v = u, B_VALUE) : B_FAIL;
}

/* The ball's path at p for the window (lo, hi); with r > 0, a plane valid within r of p
 * where the whole move's convexity gave the value (ball_plane). -1: not certified (the
 * caller searches); 0: the value; 1: the value and the plane. A flat or bull end mill
 * takes its capsule's path, then body_kind. */
static int ball_eval(const swarf_sweep *s, const double p[3], double lo, double hi, double r,
                     double *value, double *alpha, double *pd, double g[3]) {
  const swarf_sweep_rigid *x = &swarf_sweep_cdata(s)->u.rigid;
  const swarf_pose *table;
  const swarf_pose_rates *rates;
  bsample smp[2], bs;
  swarf_pose keep;
  double v, at;
  int n = x->n, plane = 0;
  bctx b;
  bkind kind;
  if (!x->ball || swarf_motion_pose_table_rates(s->motion, n, x->id, &table, &rates) != SWARF_OK)
    return -1;
  b.p = p, b.R = 0.5 * s->cutter->diameter, b.off = s->cutter->corner_radius;
  b.seg = s->cutter->length - 2.0 * b.off;
  b.table = table, b.rates = rates, b.N = n;
  b.bs = x->ball == 2 ? &bs : NULL, b.keep = &keep;
  bs.a = -1.0, bs.P = NULL;
  /* the ends first: their bounds over the whole move often certify it */
  smp[0] = bsample_at(&b, 0.0, &table[0], &rates[0]);
  smp[1] = bsample_at(&b, 1.0, &table[n], &rates[n]);
  kind = bends(x, &b, smp, lo, hi, &v, &at);
  /* a flat's or bull's: below the capsule's equator at both ends, its bottom or a corner is
   * nearest, where the capsule's value is not the cutter's (the general search's) */
  if (kind == B_FAIL && x->ball == 2 && smp[0].h < 0.0 && smp[1].h < 0.0) return -1;
  if (kind == B_FAIL && (b.mu = curvature(x, &b, smp, 1, 1.0)) > 0.0) {
    kind = bmin(&b, s->motion, smp, 1, lo, hi, &v, &at, r > 0.0 || b.bs ? &bs : NULL, &keep);
    if (kind == B_VALUE && r > 0.0) plane = ball_plane(x, &b, smp, &bs, r, pd, g);
  }
  if (kind == B_FAIL && n > 1) kind = bwindow(&b, s, n, lo, hi, &v, &at);
  if (x->ball == 2) kind = body_kind(s, &b, kind, lo, &v, at, &bs);
  if (kind == B_FAIL) return -1;
  *value = v;
  if (alpha != NULL) *alpha = at;
  return plane;
}

int swarf_sweep_rigid_ball(const swarf_sweep *s, const double p[3], double lo, double hi,
                           double *value, double *alpha) {
  return ball_eval(s, p, lo, hi, 0.0, value, alpha, NULL, NULL) < 0 ? -1 : 0;
}

int swarf_sweep_rigid_ball_plane(const swarf_sweep *s, const double p[3], double lo, double hi,
                                 double r, double *value, double *pd, double g[3]) {
  return ball_eval(s, p, lo, hi, r, value, NULL, pd, g);
}
