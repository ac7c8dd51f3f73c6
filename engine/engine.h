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

#include "toolpath.h"
#include "swarf_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Cutters ------------------------------------------------------------ */

typedef enum {
  SWARF_CUTTER_FLAT, /* flat end mill: corner radius 0 */
  SWARF_CUTTER_BALL, /* ball end mill: corner radius D/2 */
  SWARF_CUTTER_BULL  /* bull nose: 0 < corner radius < D/2 */
} swarf_cutter_shape;

/* A cutter of revolution: the body swept by the cutting edges, from the tip
 * (z = 0) to z = length. It is the Minkowski sum of a solid cylinder of
 * radius a = D/2 - R spanning z in [R, length - R] and a ball of radius R, so
 * its support function is
 *   h(n) = phi(n_z),  phi(z) = a sqrt(1 - z^2) + R + (z >= 0 ? (length - R) z : R z).
 * (The top rim is rounded like the bottom one; it never cuts in practice.) */
typedef struct {
  swarf_cutter_shape shape;
  double diameter;      /* D, mm */
  double corner_radius; /* R, mm */
  double length;        /* cutting body above the tip, mm, >= D */
} swarf_cutter;

/* Validate and fill a cutter. corner_radius is ignored for flat and ball.
 * length <= 0 selects the default, 4 * diameter. Returns 0, or -1 with a
 * reason in `why` (if not NULL) when the dimensions are impossible. */
SWARF_API int swarf_cutter_init(swarf_cutter *c, swarf_cutter_shape shape, double diameter,
                                double corner_radius, double length, const char **why);

/* Support function on the unit sphere, h(n), and its profile phi(z), phi'(z)
 * (phi' is one-sided at the kinks z = 0 and unbounded at z = +-1 when a > 0;
 * the value returned there is the limit from inside (-1, 1)). */
SWARF_API double swarf_cutter_support(const swarf_cutter *c, const double n[3]);
SWARF_API void swarf_cutter_profile(const swarf_cutter *c, double z, double *phi, double *dphi);

/* Surface point x_h(n) = h(n) n + grad_S h(n) for a unit normal n (paper eq. 1-2).
 * Where the support function has a kink (a flat face or a ruling), returns the
 * point of that face given by continuity from n_z -> 0+ / n_z -> +-1. */
SWARF_API void swarf_cutter_point(const swarf_cutter *c, const double n[3], double x[3]);

/* Signed distance from p (cutter frame) to the cutter: < 0 inside. Exact. */
SWARF_API double swarf_cutter_sdf(const swarf_cutter *c, const double p[3]);

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
 * contents of cc. Returns the number of components (0 when the cutter does
 * not move, or only turns about its own axis), or -1 when out of memory. */
SWARF_API int swarf_char_curve_compute(swarf_char_curve *cc, const swarf_cutter *c,
                                       const double t[3], const double U[9], const double v[3],
                                       const double omega[3], double tol);

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

/* A QSS of revolution about z (paper eq. 12 with c = d = 0):
 * h(n) = a (n_x^2 + n_y^2) + b n_z^2 + e n_z + f, so phi(z) = (b - a) z^2 + e z + a + f.
 * Its surface point is x_h(n) = phi(z) n + phi'(z) (e_z - z n). */
typedef struct {
  double a, b, e, f;
} swarf_qss;

/* swarf_char_curve_compute for a QSS of revolution instead of a cutter. */
SWARF_API int swarf_char_curve_compute_qss(swarf_char_curve *cc, const swarf_qss *q,
                                           const double t[3], const double U[9], const double v[3],
                                           const double omega[3], double tol);

/* A general trivariate QSS: h(n) = n^T Q n + b . n + c on the unit sphere
 * (Q row-major; only its symmetric part counts). Its surface point is
 * x_h(n) = h n + grad h - (grad h . n) n with grad h = 2 Q n + b. */
typedef struct {
  double Q[9], b[3], c;
} swarf_qss_general;

/* swarf_char_curve_compute for a general QSS (engine/charqssgen.c): the
 * spherical quartic f = g = 0 traced by a sweep along a generic axis. Same
 * layout (closed polylines, chord error of x under tol). Returns the number of
 * components; 0 when f vanishes identically (still, or the whole sphere is
 * characteristic), when the curve is empty or only isolated points; -1 when
 * out of memory or when the sweep finds an inconsistent topology. */
SWARF_API int swarf_char_curve_compute_qss_general(swarf_char_curve *cc, const swarf_qss_general *q,
                                                   const double t[3], const double U[9],
                                                   const double v[3], const double omega[3],
                                                   double tol);

/* The same for the full revolution form of eq. 12, coef = a, b, c, d, e, f:
 * h = a (n_x^2 + n_y^2) + b n_z^2 + c n_x + d n_y + e n_z + f (its axis passes
 * through (c, d, 0)). Same contract; the exact counterpart is envelope_exact.h. */
SWARF_API int swarf_char_curve_compute_qss12(swarf_char_curve *cc, const double coef[6],
                                             const double t[3], const double U[9],
                                             const double v[3], const double omega[3], double tol);

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
 * the slice touches the curve (Delta = 0), 0 when it misses it or when
 * A = B = 0 (the whole latitude circle, or none, is characteristic). */
SWARF_API int swarf_char_gauss_slice(double dphi, const double v[3], const double omega[3],
                                     double z, double n[2][3]);

/* ---- Swept volume of one move ------------------------------------------- */

/* The volume swept by cutter c along motion m (a value; it points at both,
 * which must outlive it). */
typedef struct {
  const swarf_cutter *cutter;
  const swarf_motion *motion;
  int method;       /* internal: which evaluator applies */
  double aux[16];   /* internal: precomputed per-move constants */
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

/* The characteristic curve of the sweep at time alpha in [0, 1]: the cutter
 * at the pose of the motion, moving with its velocity d/dalpha (for the xyz
 * machine U = I, omega = 0 and v = dt/dalpha). The union over alpha of these
 * curves (world points w) is the envelope whose inside swarf_sweep_sdf
 * measures. Same contract as swarf_char_curve_compute. */
SWARF_API int swarf_sweep_char_curve(const swarf_sweep *s, double alpha, double tol,
                                     swarf_char_curve *cc);

#ifdef __cplusplus
}
#endif
#endif
