/* SPDX-License-Identifier: MPL-2.0 */
/* engine.h -- the envelope core (fast path, double precision).
 *
 * Role: cutters of revolution given by their support function, the
 * characteristic curves of a moving cutter at a time step (the closed form of
 * shared/docs/ENVELOPE.md, Fact 2) and, per move, the signed distance to the
 * swept volume that the stock rasterizes.
 *
 * Frames: the cutter frame has the tip (bottom centre) at the origin and the
 * axis along +z. A motion (toolpath.h) carries it into the workpiece frame.
 * Units: mm and radians. All functions are pure or work on caller-owned
 * values: thread-safe for distinct outputs.
 */
#ifndef SWARF_ENGINE_H
#define SWARF_ENGINE_H

#include <stddef.h>

#include "swarf_status.h"
#include "toolpath.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Cutters ------------------------------------------------------------ */

/* A QSS of revolution about z (paper eq. 12 with c = d = 0):
 * h(n) = a (n_x^2 + n_y^2) + b n_z^2 + e n_z + f, so phi(z) = (b - a) z^2 + e z + a + f.
 * Its surface point is x_h(n) = phi(z) n + phi'(z) (e_z - z n). */
typedef struct {
  double a, b, e, f;
} swarf_qss;

/* Every cutter (and every non-cutting body of revolution: shank, holder
 * segment) is a solid of revolution about the +z axis of its frame, given by
 * its PROFILE in the (r, z) half-plane r >= 0. The profile is a union of
 * PIECES; each piece is
 *   - a HULL: the convex hull of a few circles (r_i, z_i, rho_i) and their
 *     mirror images (-r_i, z_i, rho_i), bounded by lines and convex arcs. A
 *     point is a circle of radius 0. Cylinders, cones, frustums, balls,
 *     bull noses, V tips, drill points, tapered and APT cutters are one hull;
 *   - a QSS of revolution (swarf_qss above): the region enclosed by the
 *     surface x_h(n) of h = a(x^2+y^2) + b z^2 + e z + f and the axis, moved
 *     up by `lift`; convex or not (Example 2's h = x^2+y^2-z^2 is a spool
 *     with dished ends and sharp rims).
 * A non-convex cutter is a union of convex hulls (lollipop = ball + neck,
 * dovetail = frustum + neck, T-slot = disk + neck; a holder = a stack of
 * frustums). Its exact distance is the minimum over the pieces outside; inside
 * it is the deepest piece's depth (never deeper than the true depth; equal
 * near the surface). The distance to a solid of revolution is the 2-D
 * distance to its profile region at (sqrt(x^2 + y^2), z).
 *
 * Building a body that is not a cutter (the `assembly` use):
 *   swarf_cutter c;
 *   swarf_cutter_begin(&c);
 *   swarf_cutter_add_frustum(&c, z0, r0, z1, r1, err);   any number, <= MAX_PIECES
 *   (or swarf_cutter_add_hull with circles)
 *   swarf_cutter_finish(&c, err);
 * after which every engine call (sdf, sweeps, characteristic curves) takes it
 * like a cutter. Its z range need not start at 0 (a shank from z = L to S).
 *
 * flat, ball and bull (swarf_cutter_init) keep their closed forms (fast = 1);
 * their piece is filled too, so profile code sees every cutter the same way. */

typedef enum {
  SWARF_CUTTER_FLAT,     /* flat end mill: corner radius 0 */
  SWARF_CUTTER_BALL,     /* ball end mill: corner radius D/2 */
  SWARF_CUTTER_BULL,     /* bull nose: 0 < corner radius < D/2 */
  SWARF_CUTTER_VEE,      /* V-bit / engraver: sharp cone tip, included angle */
  SWARF_CUTTER_DRILL,    /* twist drill: point angle (default 118 deg) */
  SWARF_CUTTER_SPOT,     /* spot drill: point angle (default 90 deg) */
  SWARF_CUTTER_CHAMFER,  /* chamfer mill: cone from a tip diameter up to D */
  SWARF_CUTTER_TAPER,    /* tapered end mill: tip diameter, half-angle, tip radius */
  SWARF_CUTTER_APT,      /* the APT 7-parameter cutter */
  SWARF_CUTTER_LOLLIPOP, /* undercut ball: sphere on a thinner neck (non-convex) */
  SWARF_CUTTER_DOVETAIL, /* frustum narrowing upward on a neck (non-convex) */
  SWARF_CUTTER_TSLOT,    /* disk on a thinner neck (non-convex) */
  SWARF_CUTTER_QSS,      /* the paper's QSS of revolution, lowest point at the tip */
  SWARF_CUTTER_BODY      /* built with swarf_cutter_begin, add_..., finish */
} swarf_cutter_shape;

#define SWARF_PIECE_MAX_ELEMS 12
#define SWARF_PIECE_MAX_CIRCLES 6
#define SWARF_CUTTER_MAX_PIECES 8

typedef enum { SWARF_PIECE_HULL, SWARF_PIECE_QSS } swarf_piece_kind;

/* One element of a hull's outline, counterclockwise (bottom to top, r >= 0):
 * a line from (r0, z0) to (r1, z1) (rad = 0; a point when both ends agree),
 * or an arc of the circle (cr, cz, rad) from (r0, z0) to (r1, z1),
 * counterclockwise about its centre (a convex arc). */
typedef struct {
  double r0, z0, r1, z1;
  double cr, cz, rad;
  double inv; /* line: 1 / squared length (0 for a point) */
} swarf_profile_elem;

typedef struct {
  swarf_piece_kind kind;
  int convex; /* 1: the solid is convex (every hull; a QSS when p + p'' >= 0) */
  /* HULL: the circles as given (r, z, rho), and the outline built from them.
   * The outline has a lower chain (elements below the widest part, as z
   * goes up), the side (a vertical line at r = rmax from zw0 to zw1, perhaps
   * of length 0) and an upper chain. */
  int ncircle;
  double circle[SWARF_PIECE_MAX_CIRCLES][3];
  int nel, side; /* elements, and the index of the side element */
  swarf_profile_elem el[SWARF_PIECE_MAX_ELEMS];
  double zlo, zhi, rmax, zw0, zw1;
  /* QSS: h = a(x^2+y^2) + b z^2 + e z + f, profile r(s) = sqrt(1-s^2)(q0 - q2 s^2),
   * z(s) = -q2 s^3 + (q0 + 2 q2) s + q1 + lift for s = n_z in [-1, 1]. */
  swarf_qss qss;
  double q2, q1, q0, lift;
} swarf_profile_piece;

/* A cutter of revolution. The flat/ball/bull fields keep their meaning: the
 * body is the Minkowski sum of a solid cylinder of radius a = D/2 - R over z
 * in [R, length - R] and a ball of radius R (the top rim rounded like the
 * bottom one), support h(n) = phi(n_z),
 *   phi(z) = a sqrt(1 - z^2) + R + (z >= 0 ? (length - R) z : R z).
 * For the other shapes `diameter` is the largest diameter and `length` the
 * top of the body; corner_radius is the family's R if it has one. */
typedef struct {
  swarf_cutter_shape shape;
  double diameter;      /* D, mm (largest) */
  double corner_radius; /* R, mm */
  double length;        /* top of the body above the tip (z max), mm */
  double zmin;          /* bottom of the body, mm (0 for cutters) */
  int fast;             /* 1: flat/ball/bull closed forms apply */
  int convex;           /* 1: the body is convex (one convex piece) */
  double param[8];      /* the family's numbers as given (angles in radians) */
  int npieces;
  swarf_profile_piece piece[SWARF_CUTTER_MAX_PIECES];
} swarf_cutter;

/* A cutter's sizes lie between these (mm): a diameter below a micrometre or
 * any length above a metre is a typo or a unit slip, not a cutter, and
 * simulating it would give a volume with no meaning. */
#define SWARF_CUTTER_MIN_MM 1e-3
#define SWARF_CUTTER_MAX_MM 1000.0

/* Validate and fill a flat, ball or bull cutter. corner_radius is ignored
 * for flat and ball. length <= 0 selects the default, 4 * diameter. Flutes
 * shorter than the diameter are allowed (a face mill); a bull needs length
 * >= 2 R, a ball length >= R (below 2 R = D the ball is cut flat at the
 * top: a profile cutter, fast = 0). SWARF_ERR_TOOL when the dimensions are
 * impossible or outside [SWARF_CUTTER_MIN_MM, SWARF_CUTTER_MAX_MM]: *err (may be NULL) gets the
 * reason and, as its word, the letter of the tool spec's number that is wrong (D, R or L);
 * SWARF_ERR_ARG for a NULL cutter. */
SWARF_API swarf_status swarf_cutter_init(swarf_cutter *c, swarf_cutter_shape shape, double diameter,
                                         double corner_radius, double length, swarf_error *err);

/* A cutter of any named family from its numbers (mm, angles in DEGREES as
 * the tool world writes them); a field left NAN takes its default:
 *   VEE      d, angle (included), length (default max(4 d, cone height))
 *   DRILL    d, angle (point, default 118), length (default max(4 d, point))
 *   SPOT     d, angle (point, default 90), length
 *   CHAMFER  d, angle (included), tip (tip diameter, default 0), length
 *   TAPER    d (tip diameter), angle (taper half-angle), r (tip corner radius,
 *            default 0; d/2: tapered ball), length (default 4 d)
 *   APT      d, r, e, f, angle (alpha), beta, h: corner circle (e, f, r), bottom
 *            line at alpha from the horizontal through the tip, side at beta
 *            from the axis, up to h; requires f cos(alpha) - e sin(alpha) = r
 *            and d = 2 (e + r / cos(beta)) (to 1e-3 mm + 1e-3 d)
 *   LOLLIPOP d (sphere), neck (K: diameter < d), length (default 4 d)
 *   DOVETAIL d (bottom diameter), angle (flank to base, < 90), h (flank
 *            height), neck (default the flank's top diameter), length
 *            (default h + 2 d)
 *   TSLOT    d, h (disk thickness), neck (< d), length (default h + 2 d)
 *   QSS      a, b, e, f (h = a(x^2+y^2) + b z^2 + e z + f, mm), moved up so
 *            that its lowest point is at z = 0
 *   FLAT, BALL, BULL: d, r, length as swarf_cutter_init.
 * A length given must be > 0, and every size within SWARF_CUTTER_MAX_MM.
 * On bad numbers returns SWARF_ERR_TOOL and err->message names the
 * parameter (its letter in the tool spec: D, A, R, L, T, E, F, B, H, K) and
 * why; err->word holds the letter. */
typedef struct {
  swarf_cutter_shape shape;
  double d, r, length, angle, tip, e, f, beta, h, neck;
  double qa, qb, qe, qf; /* QSS coefficients */
} swarf_cutter_spec;

/* All fields NAN, shape FLAT. */
SWARF_API void swarf_cutter_spec_init(swarf_cutter_spec *s);
SWARF_API swarf_status swarf_cutter_make(swarf_cutter *c, const swarf_cutter_spec *spec,
                                         swarf_error *err);

/* Bodies piece by piece (see the top of this section). begin empties c
 * (shape BODY); add_hull adds the convex hull of n circles {r, z, rho}
 * (r >= 0, rho >= 0; at least one circle with r + rho > 0) and their mirror
 * images; add_frustum the frustum (cylinder when r0 = r1, cone when one
 * radius is 0) between heights z0 < z1; add_qss a QSS piece lifted by
 * `lift`. finish computes the bounds (diameter, zmin, length, convex).
 * Errors: SWARF_ERR_TOOL (bad numbers, too many pieces or circles). */
SWARF_API void swarf_cutter_begin(swarf_cutter *c);
SWARF_API swarf_status swarf_cutter_add_hull(swarf_cutter *c, const double (*circles)[3], int n,
                                             swarf_error *err);
SWARF_API swarf_status swarf_cutter_add_frustum(swarf_cutter *c, double z0, double r0, double z1,
                                                double r1, swarf_error *err);
SWARF_API swarf_status swarf_cutter_add_qss(swarf_cutter *c, const swarf_qss *q, double lift,
                                            swarf_error *err);
SWARF_API swarf_status swarf_cutter_finish(swarf_cutter *c, swarf_error *err);

/* "vee D6 A90 L20"-like one-line description of the cutter (for reports). */
SWARF_API void swarf_cutter_describe(const swarf_cutter *c, char *buf, size_t len);

/* Support function on the unit sphere, h(n), and its profile phi(z), phi'(z)
 * (phi' is one-sided at the kinks z = 0 and unbounded at z = +-1 when a > 0;
 * the value returned there is the limit from inside (-1, 1)). For a
 * non-convex cutter: those of its convex hull. */
SWARF_API double swarf_cutter_support(const swarf_cutter *c, const double n[3]);
SWARF_API void swarf_cutter_profile(const swarf_cutter *c, double z, double *phi, double *dphi);

/* Surface point x_h(n) = h(n) n + grad_S h(n) for a unit normal n (paper eq. 1-2).
 * Where the support function has a kink (a flat face or a ruling), returns the
 * point of that face given by continuity from n_z -> 0+ / n_z -> +-1. For a
 * non-convex cutter: the point of its convex hull's outline. */
SWARF_API void swarf_cutter_point(const swarf_cutter *c, const double n[3], double x[3]);

/* Signed distance from p (cutter frame) to the cutter: < 0 inside. Exact
 * outside; inside exact for one piece, the deepest piece's depth otherwise. */
SWARF_API double swarf_cutter_sdf(const swarf_cutter *c, const double p[3]);

/* The 2-D signed distance of the profile region at (r, z), r >= 0, and its
 * gradient (dr, dz) (unit; a subgradient on the medial axis). The same value
 * as swarf_cutter_sdf at any point with that r and z. */
SWARF_API double swarf_cutter_sdf2(const swarf_cutter *c, double r, double z, double g[2]);

/* ---- Characteristic curves ---------------------------------------------- */

/* One point of a characteristic curve. */
typedef struct {
  double n[3]; /* unit normal, moving (cutter) frame */
  double x[3]; /* surface point x_h(n), cutter frame, mm */
  double w[3]; /* world point t + U x, mm */
} swarf_char_point;

/* Characteristic curves at one time step: ordered polylines, one per
 * component. Component k holds points [start[k], start[k+1]). Init/clear pair. */
typedef struct {
  swarf_char_point *pts;
  size_t len, cap;
  size_t *start; /* ncomp + 1 entries */
  size_t ncomp, start_cap;
} swarf_char_curve;

SWARF_API void swarf_char_curve_init(swarf_char_curve *cc);
SWARF_API void swarf_char_curve_clear(swarf_char_curve *cc);

/* The characteristic curve of cutter c at the pose (t, U) with moving-frame
 * velocity v and angular velocity omega (ENVELOPE.md, Fact 2), sampled so
 * that the chord error on the surface stays under `tol` mm. Replaces the
 * contents of cc; cc->ncomp is the number of components (0 when the cutter
 * does not move, or only turns about its own axis). SWARF_ERR_MEMORY when
 * out of memory, SWARF_ERR_ARG for a NULL argument. */
SWARF_API swarf_status swarf_char_curve_compute(swarf_char_curve *cc, const swarf_cutter *c,
                                                const double t[3], const double U[9],
                                                const double v[3], const double omega[3],
                                                double tol);

/* Layout of the result of the compute functions: each component is a CLOSED
 * polyline that repeats its first point at its end. A component runs along
 * branch s = +1 of Fact 2 from its lower end (a branch point, or a pole) to
 * its upper end, then back along s = -1. Where the curve crosses a kink of
 * phi it follows the kink's face: along the side ruling (n_z = 0) the normal
 * stays on the equator while the point climbs the ruling; at a flat face
 * (n_z = +-1, core radius a > 0) the two branch ends are joined by the chord
 * of the face. A pure translation along the cutter axis makes the whole side
 * characteristic: the result is then the two rim circles of the side (one
 * when the side has no height). Degenerate instances whose characteristic set
 * contains a surface patch (a ball turning about its own centre) give some
 * curves inside that patch. */

/* A QSS of revolution about z: swarf_qss (declared with the cutters). */

/* swarf_char_curve_compute for a QSS of revolution instead of a cutter. */
SWARF_API swarf_status swarf_char_curve_compute_qss(swarf_char_curve *cc, const swarf_qss *q,
                                                    const double t[3], const double U[9],
                                                    const double v[3], const double omega[3],
                                                    double tol);

/* A general trivariate QSS: h(n) = n^T Q n + b . n + c on the unit sphere
 * (Q row-major; only its symmetric part counts). Its surface point is
 * x_h(n) = h n + grad h - (grad h . n) n with grad h = 2 Q n + b. */
typedef struct {
  double Q[9], b[3], c;
} swarf_qss_general;

/* swarf_char_curve_compute for a general QSS (engine/envelope/charqssgen.c): the
 * spherical quartic f = g = 0 traced by a sweep along a generic axis. Same
 * layout (closed polylines, chord error of x under tol). cc->ncomp is the
 * number of components; 0 when f vanishes identically (still, or the whole
 * sphere is characteristic), when the curve is empty or only isolated
 * points. SWARF_ERR_MEMORY when out of memory, SWARF_ERR_INTERNAL when the
 * sweep finds an inconsistent topology. */
SWARF_API swarf_status swarf_char_curve_compute_qss_general(swarf_char_curve *cc,
                                                            const swarf_qss_general *q,
                                                            const double t[3], const double U[9],
                                                            const double v[3],
                                                            const double omega[3], double tol);

/* The same for the full revolution form of eq. 12, coef = a, b, c, d, e, f:
 * h = a (n_x^2 + n_y^2) + b n_z^2 + c n_x + d n_y + e n_z + f (its axis passes
 * through (c, d, 0)). Same contract; the exact counterpart is envelope_exact.h. */
SWARF_API swarf_status swarf_char_curve_compute_qss12(swarf_char_curve *cc, const double coef[6],
                                                      const double t[3], const double U[9],
                                                      const double v[3], const double omega[3],
                                                      double tol);

/* The real branch points of the characteristic curve: the z in [-1, 1] where
 * Fact 2's Delta changes sign, sorted, to full double precision (branch
 * points on a cutter's side ruling are reported as z = 0). Writes at most max
 * of them and returns how many there are. */
SWARF_API int swarf_char_branch_points(const swarf_cutter *c, const double v[3],
                                       const double omega[3], double *z, int max);
SWARF_API int swarf_char_branch_points_qss(const swarf_qss *q, const double v[3],
                                           const double omega[3], double *z, int max);

/* The Gauss points at one slice n_z = z of any profile of revolution with
 * phi'(z) = dphi (Fact 2): n[0] for s = +1, n[1] for s = -1. Returns 2, 1 when
 * the slice touches the curve (Delta = 0), 0 when it misses it, when
 * A = B = 0 (the whole latitude circle, or none, is characteristic), or when
 * dphi is not finite (a profile's slope at a pole: the slice z = +-1 holds
 * one point of the sphere, never a curve through it). */
SWARF_API int swarf_char_gauss_slice(double dphi, const double v[3], const double omega[3],
                                     double z, double n[2][3]);

/* ---- Swept volume of one move ------------------------------------------- */

/* The volume swept by cutter c along motion m (a value; it points at both,
 * which must outlive it). The evaluator that applies and its per-move
 * constants live in `internal_`, opaque storage typed in engine_private.h
 * (swarf_sweep_data, which a static assertion keeps within it). */
#define SWARF_SWEEP_STORAGE 18 /* doubles */
typedef struct {
  const swarf_cutter *cutter;
  const swarf_motion *motion;
  double internal_[SWARF_SWEEP_STORAGE]; /* internal: do not touch */
} swarf_sweep;

SWARF_API void swarf_sweep_init(swarf_sweep *s, const swarf_cutter *c, const swarf_motion *m);

/* The same for a stock of voxel edge `voxel` (mm): RIGID motions (rotary
 * machines) choose their time steps from it (swarf_sweep_init assumes 0.1 mm).
 * Their sdf is certified to 1e-6 mm within 72 voxels of the volume (within the
 * work caps; see sweep_rigid.c), a lower bound beyond. */
SWARF_API void swarf_sweep_init_voxel(swarf_sweep *s, const swarf_cutter *c, const swarf_motion *m,
                                      double voxel);

/* A convex body's signed distance at q (body frame) and its unit gradient. */
typedef double (*swarf_body_sdf_fn)(const void *ctx, const double q[3], double grad[3]);

/* The sdf of a RIGID sweep (swarf_sweep_init_voxel) with another convex body
 * `body` in place of the cutter, which then only gives the sizes the time
 * steps and bounds are chosen from (its radius and length must enclose the
 * body). For tests of other bodies (QSS). NaN for a non-RIGID sweep. */
SWARF_API double swarf_sweep_rigid_body_sdf(const swarf_sweep *s, swarf_body_sdf_fn body,
                                            const void *ctx, const double p[3], double *alpha);

/* Axis-aligned bounds of the swept volume, workpiece frame, mm. */
SWARF_API void swarf_sweep_bounds(const swarf_sweep *s, double lo[3], double hi[3]);

/* Signed distance from p (workpiece frame) to the swept volume: < 0 inside.
 * Exact outside the volume; inside, exact for the closed-form cases and never
 * larger in magnitude than the true depth otherwise. 1-Lipschitz. If alpha is
 * not NULL it receives the time of the nearest cutter instance. */
SWARF_API double swarf_sweep_sdf(const swarf_sweep *s, const double p[3], double *alpha);

/* swarf_sweep_sdf at p where only values in (lo, hi) matter (lo < hi; the
 * stock: hi the value that would not change the voxel, lo the depth that
 * clears it): the sdf, to the certified error, if it lies in [lo, hi);
 * if it is below lo, a value <= lo that is still >= the sdf (the first
 * instant found that deep); if it is at least hi, a value >= hi. RIGID
 * sweeps of the cutter prune their search by both (sweep_rigid.c); other
 * sweeps return swarf_sweep_sdf. */
SWARF_API double swarf_sweep_sdf_range(const swarf_sweep *s, const double p[3], double lo,
                                       double hi);

/* swarf_sweep_sdf_range's value at p for the window (lo, hi) in *d and, when it
 * returns 1 (the value then lies in the window), a plane below the sdf within r of p:
 * sdf(q) >= *pd + g.(q - p) for every q with |q - p| <= r (*pd <= *d; |g| may pass 1). A
 * swept volume under rotation is not convex, so no plane bounds it everywhere; near p
 * one does where the time of p's nearest instance is certified unique: a ball end mill's
 * rigid moves whose distance to p is convex in time over the whole move
 * (sweep_rigid_ball.c). Otherwise returns 0 and leaves pd and g alone. For the removal's
 * per-voxel bounds on rotary moves. */
SWARF_API int swarf_sweep_range_plane(const swarf_sweep *s, const double p[3], double lo, double hi,
                                      double r, double *d, double *pd, double g[3]);

/* The sdf at p (*d) and, when it returns 1, a supporting plane there: a unit
 * vector g with sdf(q) >= *d + g.(q - p) for every q. Given where the volume
 * is convex (a straight move of a flat, ball or bull end mill: the fast
 * cutters), so that its sdf is convex inside and out: outside the cutter's
 * core g is the gradient, the direction from the nearest point of the core
 * (on the nearest instance) to p; inside it, the gradient of the core's
 * nearer side (radial or height) where that is a subgradient of the sdf.
 * Otherwise returns 0 and leaves g alone. For the removal's per-voxel
 * bounds. */
SWARF_API int swarf_sweep_support(const swarf_sweep *s, const double p[3], double *d, double g[3]);

/* The characteristic curve of the sweep at time alpha in [0, 1]: the cutter
 * at the pose of the motion, moving with its velocity d/dalpha (for the xyz
 * machine U = I, omega = 0 and v = dt/dalpha). The union over alpha of these
 * curves (world points w) is the envelope whose inside swarf_sweep_sdf
 * measures. Same contract as swarf_char_curve_compute. */
SWARF_API swarf_status swarf_sweep_char_curve(const swarf_sweep *s, double alpha, double tol,
                                              swarf_char_curve *cc);

#ifdef __cplusplus
}
#endif
#endif
