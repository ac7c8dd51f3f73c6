/* toolpath.h -- canonical moves become rigid motions of the cutter.
 *
 * Role: a move from the G-code front end becomes a rigid motion
 *   x' = t(alpha) + U(alpha) x,   alpha in [0, 1],
 * that carries a point x of the cutter frame (tip at the origin, axis +z)
 * into the workpiece frame. This first version is the 3-axis machine (xyz):
 * U is the identity and t(alpha) is the tool tip on the programmed path.
 * Arcs stay arcs: a helical motion is evaluated exactly at any alpha.
 *
 * Units: mm, radians, seconds. Values only, no state: thread-safe.
 */
#ifndef SWARF_TOOLPATH_H
#define SWARF_TOOLPATH_H

#include "gcode.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  SWARF_MOTION_LINE, /* t(a) = p0 + a (p1 - p0) */
  SWARF_MOTION_HELIX /* t(a) = center + Rot(axis, a angle)(p0 - center) + a rise axis */
} swarf_motion_kind;

typedef struct {
  swarf_motion_kind kind;
  double p0[3], p1[3]; /* tip at alpha = 0 and 1, workpiece frame, mm (for a helix
                        * p1 is the exact end of the helix) */
  double center[3];    /* helix: a point of its axis, in the plane of p0, mm */
  double axis[3];      /* helix: unit axis direction */
  double angle;        /* helix: total turning angle, radians, > 0 */
  double rise;         /* helix: advance along `axis` over the motion, mm */
  double radius;       /* helix: distance of p0 from the axis, mm */
  double duration;     /* seconds at the programmed feed (rapids: see rapid_rate) */
  double length;       /* path length of the tip, mm */
  int tool;            /* tool number in the spindle */
  int rapid;           /* 1 for G0 */
  long line;           /* source line */
  int column;          /* source column */
} swarf_motion;

/* Rapid traverse rate used for the duration of G0 moves, mm/min. */
#define SWARF_RAPID_RATE 5000.0

/* Fill `out` from a motion move (RAPID, LINE or ARC) of a 3-axis machine.
 * Returns 0, or -1 if the move has no motion (dwell, tool change) or a
 * rotary axis moves (not handled by the xyz machine). */
int swarf_motion_from_move(const swarf_move *move, swarf_motion *out);

/* Pose at alpha: t (3) and U (3x3 row-major). */
void swarf_motion_eval(const swarf_motion *m, double alpha, double t[3], double U[9]);

/* Velocities at alpha with respect to alpha: tdot (workpiece frame) and the
 * moving-frame quantities of the paper, v = U^T tdot and omega
 * (U^T Udot = [omega]_x). */
void swarf_motion_velocity(const swarf_motion *m, double alpha, double tdot[3], double v[3],
                           double omega[3]);

/* Axis-aligned bounds of the tip path t([0,1]), mm. */
void swarf_motion_bounds(const swarf_motion *m, double lo[3], double hi[3]);

/* True when the motion does not move the tip at all. */
int swarf_motion_is_null(const swarf_motion *m);

#ifdef __cplusplus
}
#endif
#endif
