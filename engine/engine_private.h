/* SPDX-License-Identifier: MPL-2.0 */
/* engine_private.h -- the engine's insides, shared by its source files only.
 *
 *   cutter.c        cutters: support function, surface points, exact sdf.
 *   cutter_body.c   bodies piece by piece: hulls, frustums, QSS pieces.
 *   cutter_family.c the named families (vee, drill, ..., qss) from numbers.
 *   profile.c       a piece's outline and its exact 2-D signed distance.
 *   charslice.c     the per-slice closed form of ENVELOPE.md Fact 2 and the
 *                   branch points (roots of Delta), for cutters and QSS.
 *   charcurve.c     characteristic curves: components, adaptive sampling.
 *   charpoly.c      real roots of a small polynomial (a QSS's Delta quartic).
 *   charcutter.c    a cutter's branch points, certified in double-double.
 *   charqss.c       the fast path for eq. 12 with an off-axis linear part.
 *   charqssgen_sweep.c  general QSS: slice roots, events, strand maps.
 *   charqssgen.c    general QSS: components walked and sampled.
 *   sweep.c         a move's swept volume: method choice, bounds, dispatch.
 *   sweep_line.c    straight moves: closed forms (slot, plunge, ramp).
 *   sweep_helix.c   arcs and helices: the closed form for planar arcs about
 *                   a vertical axis, the set-up of the others.
 *   sweep_sampled.c any other helix: sampling plus certified refinement.
 *   sweep_rigid.c   motions with rotation: time steps, characteristic
 *                   refinement, certification; sweep_rigid_setup.c its
 *                   per-move constants and bounds; sweep_rigid_ball.c a
 *                   ball end mill's path from the characteristic circles.
 *   sweep_profile.c profile cutters: the union of convex pieces, each swept
 *                   by the closed forms or the searches above.
 *   sweep_general.c a non-convex QSS piece under any motion.
 *
 * Nothing here allocates; every function works on caller-owned values.
 */
#ifndef SWARF_ENGINE_PRIVATE_H
#define SWARF_ENGINE_PRIVATE_H

#include <math.h>

#include "engine.h"

/* Distance from (x, y) to the quadrant {x <= 0, y <= 0}, signed (< 0 inside):
 * the exact 2D box combination of two signed slab distances. */
static inline double swarf_box2(double x, double y) {
  double xp = x > 0.0 ? x : 0.0, yp = y > 0.0 ? y : 0.0;
  double in = x > y ? x : y;
  return sqrt(xp * xp + yp * yp) + (in < 0.0 ? in : 0.0);
}

/* ---- Certified time searches (sweep_sampled.c, sweep_rigid.c) ----------- */

/* A sample of g(alpha) = cutter distance at time alpha, and an interval of
 * times waiting for refinement with its lower bound. */
typedef struct {
  double a, g, dg, dist; /* time, g, g', |p - t| (the rigid search only) */
} swarf_tsample;

typedef struct {
  swarf_tsample lo, hi;
  double lb; /* lower bound of g over [lo.a, hi.a] */
  int depth; /* splits so far (the helix search only) */
} swarf_tspan;

/* A binary min-heap of spans by lb: heap[0 .. *n) (the caller checks room). */
static inline void swarf_tspan_push(swarf_tspan *heap, int *n, swarf_tspan sp) {
  int i;
  for (i = (*n)++; i > 0 && heap[(i - 1) / 2].lb > sp.lb; i = (i - 1) / 2)
    heap[i] = heap[(i - 1) / 2];
  heap[i] = sp;
}

/* Remove and return the span of least lb (the heap is not empty). */
static inline swarf_tspan swarf_tspan_pop(swarf_tspan *heap, int *n) {
  swarf_tspan top = heap[0], last = heap[--*n];
  int i = 0;
  for (;;) {
    int c = 2 * i + 1;
    if (c >= *n) break;
    if (c + 1 < *n && heap[c + 1].lb < heap[c].lb) c++;
    if (heap[c].lb >= last.lb) break;
    heap[i] = heap[c];
    i = c;
  }
  if (*n > 0) heap[i] = last;
  return top;
}

/* Lower bound over [0, w] of a function g with g'' >= -K (semiconvex) from
 * its values and slopes at both ends (ga, dga at 0; gb, dgb at w): g is at
 * least max(T_A, T_B), T_A and T_B the concave parabolas of curvature -K
 * through the end data, whose minimum is at an end or where T_A = T_B
 * (T_A - T_B is linear). Shared by the certified time searches of
 * sweep_sampled.c and sweep_rigid.c. */
static inline double swarf_semiconvex_bound(double ga, double dga, double gb, double dgb, double w,
                                            double K) {
  double k2 = 0.5 * K, ta_b = ga + dga * w - k2 * w * w, tb_a = gb - dgb * w - k2 * w * w;
  double m_a = ga > tb_a ? ga : tb_a, m_b = gb > ta_b ? gb : ta_b, lb = m_a < m_b ? m_a : m_b;
  double c0 = ga - tb_a, c1 = dga - dgb - K * w; /* T_A - T_B = c0 + c1 x */
  if (c1 != 0.0) {
    double x = -c0 / c1;
    double tx = ga + dga * x - k2 * x * x;
    if (x > 0.0 && x < w && tx < lb) lb = tx;
  }
  return lb;
}

/* Core radius a = D/2 - R of the cutter (the cylinder the ball of radius R is
 * swept over). */
static inline double swarf_cutter_core(const swarf_cutter *c) {
  double a = 0.5 * c->diameter - c->corner_radius;
  return a > 0.0 ? a : 0.0;
}

/* Cutter sdf from the horizontal distance r >= 0 to its axis and the height z
 * above its tip. Exact. */
static inline double swarf_cutter_sdf_rz(const swarf_cutter *c, double r, double z) {
  double R = c->corner_radius, hh = 0.5 * c->length - R;
  return swarf_box2(r - swarf_cutter_core(c), fabs(z - 0.5 * c->length) - hh) - R;
}

/* ---- Profiles (profile.c, cutter_body.c) -------------------------------- */

/* Trace a hull piece's outline from its circles (0, or -1: too many
 * elements), then its extent (zlo, zhi, rmax and the side's zw0, zw1). */
int swarf_profile_hull_build(swarf_profile_piece *pc);
void swarf_profile_hull_extent(swarf_profile_piece *pc);

/* 2-D signed distance of a piece at (r, z), r >= 0, and its gradient (dr,
 * dz) if g is not NULL. The hull's with its upper chain raised by dz >= 0
 * (the hull swept up by dz); the QSS piece's from its quartic. */
double swarf_profile_hull_sdf(const swarf_profile_piece *pc, double r, double z, double dz,
                              double g[2]);
double swarf_profile_qss_sdf(const swarf_profile_piece *pc, double r, double z, double g[2]);
/* The same, with the nearest point of the profile curve in near; and the
 * curve's point at parameter s = n_z in [-1, 1]. */
double swarf_profile_qss_sdf_near(const swarf_profile_piece *pc, double r, double z, double g[2],
                                  double near[2]);
void swarf_profile_qss_point(const swarf_profile_piece *pc, double s, double y[2]);
double swarf_profile_piece_sdf(const swarf_profile_piece *pc, double r, double z, double g[2]);
/* The same at a 3-D point q of the cutter frame, with the 3-D gradient. */
double swarf_profile_piece_sdf_grad(const swarf_profile_piece *pc, const double q[3], double g[3]);

/* swarf_cutter_add_hull cut flat at height top (above the widest part). */
swarf_status swarf_cutter_add_hull_clipped(swarf_cutter *c, const double (*circles)[3], int n,
                                           double top, swarf_error *err);

/* Cutter sdf at p (cutter frame) and its gradient g (unit where the sdf is
 * differentiable; a subgradient on the medial axis). */
double swarf_cutter_sdf_grad(const swarf_cutter *c, const double p[3], double g[3]);

/* ---- Characteristic curves: the slice closed form ------------------------ */

/* A profile of revolution, h(n) = phi(n_z), with the parameter sigma that
 * runs over its Gauss image from the south pole to the north pole:
 * theta = polar angle from -z, z = -cos(theta), and for a cutter with a side
 * ruling an extra unit interval at theta = pi/2 over which the height c of
 * the ruling point runs from R to length - R (phi' sweeps its jump there). */
/* A general hull profile (npart > 0): smooth parts, where the point is the
 * circle (a, c) of radius R (a vertex when R = 0) at the normal's polar
 * angle theta in [th0, th1] (sigma = s0 + theta - th0), and plateaus: a line
 * of the outline with one normal (th0 = th1), along which the point runs
 * from (r0, z0) to (r1, z1) while sigma runs over [s0, s1] (length 1). */
#define SWARF_CHAR_MAX_PARTS 28
typedef struct {
  int plateau;
  double s0, s1, th0, th1;
  double a, c, R;
  double r0, z0, r1, z1;
} swarf_char_part;

typedef struct {
  int is_qss; /* 1: phi(z) = q2 z^2 + q1 z + q0; 0: a cutter */
  int npart;  /* > 0: a general hull, the parts below (a, R, L unused) */
  swarf_char_part part[SWARF_CHAR_MAX_PARTS];
  double a, R, L;    /* cutter: core radius, corner radius, length */
  double q2, q1, q0; /* QSS of revolution */
  double plateau;    /* sigma length of the ruling: 1, or 0 when none */
  double sigma_end;  /* pi + plateau */
  double scale;      /* size of the surface, mm, for relative tolerances */
} swarf_char_profile;

/* One slice: everything at parameter sigma. P = phi'(z) sqrt(1 - z^2) stays
 * finite at the poles; (At, Bt, C) are Fact 2's (A, B, C) with A, B scaled by
 * sqrt(1 - z^2), so Delta = At^2 + Bt^2 - C^2 is Fact 2's Delta. */
typedef struct {
  double z, sz; /* n_z and sqrt(1 - n_z^2) */
  double c;     /* cutter: height of the core point (R, ruling, L - R) */
  double a, R;  /* cutter: the core radius and the corner radius at this slice */
  double At, Bt, C, delta;
} swarf_char_slice;

void swarf_char_profile_cutter(swarf_char_profile *pr, const swarf_cutter *c);
void swarf_char_profile_qss(swarf_char_profile *pr, const swarf_qss *q);
/* The profile of one piece of a profile cutter: a hull's parts, or a QSS
 * piece's QSS (its lift is the caller's: a shift along the axis). */
void swarf_char_profile_piece(swarf_char_profile *pr, const swarf_profile_piece *pc);
void swarf_char_slice_eval(const swarf_char_profile *pr, const double v[3], const double omega[3],
                           double sigma, swarf_char_slice *sl);

/* Point of branch s (+1 or -1) at sigma: unit normal n and surface point x.
 * Returns 0, or -1 where the slice has no real point (Delta < 0 beyond
 * rounding) or is degenerate (At = Bt = 0). */
int swarf_char_slice_point(const swarf_char_profile *pr, const swarf_char_slice *sl, double s,
                           double n[3], double x[3]);

/* Roots of Delta(sigma) on [0, sigma_end], sorted: the changes between
 * Delta < 0 and Delta >= 0. A QSS's are bisected to adjacent doubles and
 * given by the end where Delta >= 0; a cutter's are the zeros of its
 * per-piece quadratic form (charcutter.c), to a few ulps. Returns the count
 * (writes at most max). */
int swarf_char_delta_roots(const swarf_char_profile *pr, const double v[3], const double omega[3],
                           double *roots, int max);

/* Whether sigma (inside a run between roots) is on the curve: for a QSS
 * Delta > 0 in double; for a cutter Delta >= 0, certified unless |Delta| is
 * within ~1e-30 of its scale. */
int swarf_char_delta_positive(const swarf_char_profile *pr, const double v[3],
                              const double omega[3], double sigma);

/* The cutter cases of the two above (charcutter.c: double-double quadratic
 * forms per smooth piece of the profile). */
int swarf_char_cutter_delta_roots(const swarf_char_profile *pr, const double v[3],
                                  const double omega[3], double *roots, int max);
int swarf_char_cutter_delta_positive(const swarf_char_profile *pr, const double v[3],
                                     const double omega[3], double sigma);
int swarf_char_parts_delta_roots(const swarf_char_profile *pr, const double v[3],
                                 const double omega[3], double *roots, int max);
int swarf_char_parts_delta_positive(const swarf_char_profile *pr, const double v[3],
                                    const double omega[3], double sigma);

/* Real roots in (lo, hi) where the polynomial c[0] + c[1] x + ... + c[deg] x^deg
 * changes sign (deg <= 8), ascending, to adjacent doubles. Returns the count
 * (writes at most max). */
int swarf_char_poly_roots(const double *c, int deg, double lo, double hi, double *roots, int max);

/* ---- Characteristic curves of a general QSS (charqssgen*.c) ------------ */

#define SWARF_GEN_MAX_EVENTS 48

/* f(n) = n^T M n + L . n in a frame E (rows e1, e2, e3) whose e3 is the sweep
 * axis: n = sin(phi) (cos(theta) e1 + sin(theta) e2) + cos(phi) e3. An
 * event is a branch point (the number of roots in theta changes; [lo, hi]
 * are adjacent doubles around it) or a crossing of the cut theta = pi
 * ([lo, hi] a small bracket). Interval k runs from a[k] to b[k] with nroot[k]
 * roots; map_r[k][i] is the index in interval k + 1 of root i of interval k,
 * or -1 - p when it turns with root p at the event; map_l[k][j] the same from
 * interval k + 1 back to k. */
typedef struct {
  double E[9], m[9], l[3]; /* frame, and M, L in it */
  double lip;              /* bound on |d(f, f_theta)/dphi| */
  int nev, nint;
  double a[SWARF_GEN_MAX_EVENTS + 1], b[SWARF_GEN_MAX_EVENTS + 1];
  int branch[SWARF_GEN_MAX_EVENTS]; /* 1: the event is a branch point */
  int nroot[SWARF_GEN_MAX_EVENTS + 1];
  int map_r[SWARF_GEN_MAX_EVENTS][4], map_l[SWARF_GEN_MAX_EVENTS][4];
} swarf_gen_sweep;

/* Set up the sweep of f = n^T M n + L . n (M symmetric, row-major) along the
 * axis among a fixed generic set where |f| at the poles is largest. Returns
 * 0, or -1 when the topology is inconsistent (too many events, a strand at a
 * pole, an event whose two sides do not match). */
int swarf_gen_sweep_init(swarf_gen_sweep *s, const double M[9], const double L[3]);

/* The roots theta in [-pi, pi) of f on the slice phi, ascending (at most 4). */
int swarf_gen_slice_roots(const swarf_gen_sweep *s, double phi, double *theta);

/* The unit normal at (phi, theta). */
void swarf_gen_normal(const swarf_gen_sweep *s, double phi, double theta, double n[3]);

/* ---- Sweeps: per-method evaluators -------------------------------------- */

enum {
  SWARF_SWEEP_PLUNGE,    /* vertical line, or no motion at all (one instance) */
  SWARF_SWEEP_SLOT,      /* horizontal line */
  SWARF_SWEEP_RAMP_BALL, /* other line, ball cutter: parallelogram + ball */
  SWARF_SWEEP_RAMP,      /* other line, flat or bull: convex 1-D minimum */
  SWARF_SWEEP_ARC,       /* planar arc about a vertical axis, angle < 2 pi */
  SWARF_SWEEP_RING,      /* planar full circle about a vertical axis */
  SWARF_SWEEP_HELIX,     /* any other helix: sampling and refinement */
  SWARF_SWEEP_RIGID,     /* motion with rotation (rotary machines) */
  /* profile cutters (fast = 0; sweep_profile.c), convex pieces each: */
  SWARF_SWEEP_P_SLOT,   /* horizontal line: the profile at the horizontal distance */
  SWARF_SWEEP_P_PLUNGE, /* vertical line: hulls stretched, QSS pieces minimised */
  SWARF_SWEEP_P_RAMP,   /* other line: convex 1-D minimum per piece */
  SWARF_SWEEP_P_HELIX,  /* helix: sweep_sampled.c per piece */
  SWARF_SWEEP_P_RIGID,  /* rotation: sweep_rigid.c per piece */
  SWARF_SWEEP_P_GENERAL /* a non-convex QSS piece: sweep_general.c, any motion */
};

/* ---- The sweep's per-method data (swarf_sweep.internal_) ----------------- */

/* PLUNGE: the tip goes from z0 straight up or down the axis (x, y). */
typedef struct {
  double x, y;     /* the axis */
  double mid;      /* middle of the swept body, z */
  double half;     /* half height of the swept core */
  double z0;       /* tip at alpha = 0 */
  double inv_dz;   /* 1 / (z1 - z0); 0 when the tip does not move */
  double zlo, zhi; /* lowest and highest tip */
} swarf_sweep_plunge;

/* SLOT: a horizontal line p0 + alpha d. */
typedef struct {
  double p0[3];
  double d[2];     /* horizontal displacement */
  double inv_len2; /* 1 / |d|^2 */
} swarf_sweep_slot;

/* RAMP, RAMP_BALL: a climbing line, tip p0 + u (e, k) for u in [0, len]. */
typedef struct {
  double p0[3];
  double e[2];      /* unit horizontal direction */
  double len;       /* horizontal length */
  double k;         /* climb per horizontal mm */
  double core_mid;  /* middle of the core above the tip */
  double core_half; /* half height of the core */
  double core;      /* core radius a */
  double w;         /* 1 / (1 + k^2) */
} swarf_sweep_ramp;

/* ARC, RING: a planar arc about a vertical axis through (cx, cy) at height z0,
 * from the direction e1 towards e2, ending at (x1, y1). */
typedef struct {
  double cx, cy, z0;
  double e1[2], e2[2];
  double radius, angle, cos_angle, sin_angle;
  double x1, y1;
} swarf_sweep_arc;

/* HELIX: t(alpha) = c + radius (cos(angle alpha) e1 + sin(angle alpha) e2)
 * + alpha rise axis; n samples `step` mm apart along the path of length len.
 * A helix of more than two turns about a vertical axis is searched turn by
 * turn, one of more than one turn about a horizontal axis in a one-turn
 * window (sweep_sampled.c): tn samples a turn (0: the whole helix searched). */
typedef struct {
  double c[3], e1[3], e2[3];
  double radius, angle, rise;
  double step, len;
  int n, tn;
} swarf_sweep_helix;

/* RIGID: bounds lo, hi of the volume; n time steps; v, w bounds of |v|,
 * |omega| and vd, wd of their alpha-derivatives; beyond `far` mm a lower
 * bound is returned. A ball end mill (ball = 1; sweep_rigid_ball.c): cv and
 * cvmin bound the speed |c'| of its centre c = t + U (0, 0, R) from above and
 * below, ca its acceleration |c''|, ck the part of c' along the tool axis; a
 * flat or bull end mill (ball = 2) the same for c at its corner radius R: the
 * start of the axis of the capsule of radius D/2 that holds it.
 * id: this sweep's number for its motion's pose table (unique to each init:
 * swarf_motion_pose_table_id). */
typedef struct {
  double lo[3], hi[3];
  double v, w, vd, wd;
  double far;
  double cv, cvmin, ca, ck;
  uint64_t id;
  int n;
  int ball;
} swarf_sweep_rigid;

/* P_SLOT, P_PLUNGE, P_RAMP (profile cutters): the line p0 + alpha d. */
typedef struct {
  double p0[3], d[3];
  double inv_h2; /* 1 / |d_xy|^2, 0 for a plunge */
} swarf_sweep_pline;

typedef struct {
  int method; /* SWARF_SWEEP_* */
  union {
    swarf_sweep_pline pline;
    swarf_sweep_plunge plunge;
    swarf_sweep_slot slot;
    swarf_sweep_ramp ramp;
    swarf_sweep_arc arc;
    swarf_sweep_helix helix;
    swarf_sweep_rigid rigid;
  } u;
} swarf_sweep_data;

_Static_assert(sizeof(swarf_sweep_data) <= sizeof(((swarf_sweep *)0)->internal_),
               "swarf_sweep_data must fit in swarf_sweep.internal_ (SWARF_SWEEP_STORAGE)");
_Static_assert(_Alignof(swarf_sweep_data) <= _Alignof(double),
               "swarf_sweep.internal_ is aligned for doubles");

/* The typed data of a sweep (only engine code and tests use it). */
static inline swarf_sweep_data *swarf_sweep_data_of(swarf_sweep *s) {
  return (swarf_sweep_data *)(void *)s->internal_;
}
static inline const swarf_sweep_data *swarf_sweep_cdata(const swarf_sweep *s) {
  return (const swarf_sweep_data *)(const void *)s->internal_;
}

void swarf_sweep_line_init(swarf_sweep *s, const double p0[3], const double p1[3]);
double swarf_sweep_slot_sdf(const swarf_sweep *s, const double p[3], double *alpha);
double swarf_sweep_plunge_sdf(const swarf_sweep *s, const double p[3], double *alpha);
double swarf_sweep_ramp_ball_sdf(const swarf_sweep *s, const double p[3], double *alpha);
double swarf_sweep_ramp_sdf(const swarf_sweep *s, const double p[3], double *alpha);
/* A straight move's sdf at p in *d and, where it has one in closed form, the
 * sweep's supporting plane there (swarf_sweep_support for the line methods):
 * returns 1 with its unit normal in g, from the core of the nearest
 * instance; outside the core (by at least 1e-6 mm) its normal there, inside
 * the gradient of its nearer side; else 0. */
int swarf_sweep_line_support(const swarf_sweep *s, const double p[3], double *d, double g[3]);

void swarf_sweep_helix_init(swarf_sweep *s);
/* The helix search of sweep_sampled.c for a convex body (gradient callback),
 * pruned by upper: returns the minimum if below upper - 1e-9, else a value
 * >= upper - 1e-9 (nothing below it). */
double swarf_sweep_helix_body_sdf(const swarf_sweep *s, swarf_body_sdf_fn body, const void *ctx,
                                  const double p[3], double upper, double *alpha);
double swarf_sweep_arc_sdf(const swarf_sweep *s, const double p[3], double *alpha);
double swarf_sweep_ring_sdf(const swarf_sweep *s, const double p[3], double *alpha);
double swarf_sweep_helix_sdf(const swarf_sweep *s, const double p[3], double *alpha);

void swarf_sweep_rigid_init(swarf_sweep *s, double voxel);
/* swarf_sweep_rigid_body_sdf pruned by upper: the minimum if it is below
 * upper - 1e-6, else a value >= upper - 1e-6. Any motion kind. */
double swarf_sweep_rigid_body_below(const swarf_sweep *s, swarf_body_sdf_fn body, const void *ctx,
                                    const double p[3], double upper, double *alpha);

/* Profile cutters (sweep_profile.c): init for any motion, bounds, sdf. */
void swarf_sweep_profile_init(swarf_sweep *s, double voxel);
double swarf_sweep_profile_sdf(const swarf_sweep *s, const double p[3], double *alpha);
/* Cutters with a non-convex QSS piece, any motion (sweep_general.c). */
double swarf_sweep_general_sdf(const swarf_sweep *s, const double p[3], double *alpha);
/* The cutter's 2-D sdf at horizontal distance r and height z: the closed
 * form of flat/ball/bull, or the minimum over the profile's pieces. */
static inline double swarf_cutter_rz(const swarf_cutter *c, double r, double z) {
  return c->fast ? swarf_cutter_sdf_rz(c, r, z) : swarf_cutter_sdf2(c, r, z, NULL);
}
void swarf_sweep_rigid_bounds(const swarf_sweep *s, double lo[3], double hi[3]);
double swarf_sweep_rigid_sdf(const swarf_sweep *s, const double p[3], double *alpha);
double swarf_sweep_rigid_sdf_range(const swarf_sweep *s, const double p[3], double lo, double hi);
/* The ball end mill's path (sweep_rigid_ball.c): the value at p as
 * swarf_sweep_rigid_sdf_range gives it for the window (lo, hi), the instant
 * of the value in *alpha (may be NULL). Returns 0, or -1 when its
 * preconditions cannot be certified at p (then the caller searches). */
int swarf_sweep_rigid_ball(const swarf_sweep *s, const double p[3], double lo, double hi,
                           double *value, double *alpha);
/* swarf_sweep_rigid_ball with, where it returns 1, a plane below the sdf within r of p
 * (swarf_sweep_range_plane); 0: the value alone; -1 as swarf_sweep_rigid_ball. */
int swarf_sweep_rigid_ball_plane(const swarf_sweep *s, const double p[3], double lo, double hi,
                                 double r, double *value, double *pd, double g[3]);
/* swarf_sweep_range_plane for RIGID sweeps (sweep_rigid.c). */
int swarf_sweep_rigid_range_plane(const swarf_sweep *s, const double p[3], double lo, double hi,
                                  double r, double *d, double *pd, double g[3]);

#endif
