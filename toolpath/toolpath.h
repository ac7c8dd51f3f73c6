/* SPDX-License-Identifier: MPL-2.0 */
/* toolpath.h -- rigid motions of the cutter and the machines that make them.
 *
 * Role: a rigid motion
 *   x' = t(alpha) + U(alpha) x,   alpha in [0, 1],
 * carries a point x of the cutter frame (tip at the origin, axis +z) into
 * the workpiece frame. On the 3-axis machine (xyz) U is the identity and
 * t(alpha) is the tool tip on the programmed path; arcs stay arcs: a
 * helical motion is evaluated exactly at any alpha. Machines with rotary
 * axes, in the table or the spindle head (swarf_machine, machine.c), give
 * RIGID motions with U != I: relative to the workpiece a head that tilts is
 * again a rigid motion of the cutter.
 *
 * Layers: this header knows nothing of G-code. A canonical move of the
 * front end becomes a motion in move_motion.h (library swarf_move_motion),
 * the one place where toolpath meets gcode; the engine sees only motions.
 *
 * Units: mm, radians, seconds. Values only, no state: thread-safe (the pose
 * table is per thread).
 */
#ifndef SWARF_TOOLPATH_H
#define SWARF_TOOLPATH_H

#include <stddef.h>
#include <stdint.h>

#include "swarf_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  SWARF_MOTION_LINE,  /* t(a) = p0 + a (p1 - p0) */
  SWARF_MOTION_HELIX, /* t(a) = center + Rot(axis, a angle)(p0 - center) + a rise axis */
  SWARF_MOTION_RIGID  /* rotary machine: U(a) = R(a)^T, see below */
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
  /* RIGID only. R(a) = Rot(e1, th1(a)) Rot(e2, th2(a)), th = th0 + a (th1 - th0)
   * (the angles are interpolated linearly, as LinuxCNC does), and U(a) = R(a)^T:
   * the cutter's orientation relative to the workpiece. The first `nhead`
   * factors belong to the spindle head (H, the product of them, is the inverse
   * of the cutter's orientation in the machine frame), the others to the
   * table (T, the product of them: a workpiece point w sits at machine point
   * pivot + T (w - pivot)); R = H T. Table machines have nhead = 0 (H = I, the
   * spindle keeps axis +z), head-head machines nhead = 2 (T = I, the
   * workpiece stays), head-table machines nhead = 1. P(a) is the programmed
   * tip path: the line p0 p1 or, when helix = 1, the helix of
   * center/axis/angle/rise. With tcp = 1 it is in the workpiece frame and
   * t(a) = P(a); with tcp = 0 it is in the machine frame (joint positions:
   * the tip where it would be at zero angles) and
   *   t(a) = pivot + T^T (P(a) - pivot + head - H^T head),
   * head being the point where the head's axes meet, relative to the tip at
   * zero angles (for nhead = 0: t = pivot + U (P - pivot)). */
  int tcp;
  int helix;             /* 1: the tip path P is the helix of the fields above (any kind) */
  double e1[3], e2[3];   /* unit rotation axes of the two rotary axes (e2 = 0: one axis) */
  double th0[2], th1[2]; /* their angles at a = 0 and a = 1, radians */
  double pivot[3];       /* a point of every table axis, mm */
  double turn;           /* |th1 - th0| summed over the axes, radians */
  int nhead;             /* how many of e1, e2 (from e1) are head axes: 0, 1 or 2 */
  double head[3];        /* head pivot relative to the tip, cutter frame, mm */
} swarf_motion;

/* Rapid traverse rate used for the duration of G0 moves, mm/min. */
#define SWARF_RAPID_RATE 5000.0

/* ---- Machines ------------------------------------------------------------ */

typedef enum {
  SWARF_MACHINE_XYZ,       /* 3 axes (default) */
  SWARF_MACHINE_XYZA,      /* rotary table about machine X (4th axis), joint kinematics */
  SWARF_MACHINE_XYZAC_TRT, /* table tilting about X (A) carrying a rotary table about Z (C) */
  SWARF_MACHINE_XYZBC_TRT, /* table tilting about Y (B) carrying a rotary table about Z (C) */
  SWARF_MACHINE_XYZAB_TDR, /* table tilting about Y (B) carrying a rotary table about X (A) */
  SWARF_MACHINE_XYZBC_HH,  /* spindle head: rotary about Z (C) carrying a tilt about Y (B) */
  SWARF_MACHINE_XYZBC_HT   /* spindle head tilting about Y (B), rotary table about Z (C) */
} swarf_machine_kind;

/* Conventions (LinuxCNC's kinematics modules, their default directions; a
 * workpiece point w, a cutter-frame point x, Rx Ry Rz right-hand rotations):
 *   xyza, xyzac-trt, xyzbc-trt (xyzac-trt-kins, xyzbc-trt-kins): the table
 *     turns the workpiece by +A/+B about X/Y and +C about Z: w sits at
 *     pivot + Rx(A) Rz(C) (w - pivot) (Ry(B) for xyzbc-trt);
 *   xyzab-tdr (xyzab_tdr_kins): B tilts a cradle about Y carrying a rotary
 *     table about X (A); w sits at pivot + Ry(-B) Rx(-A) (w - pivot): the
 *     cutter turns by +A, +B relative to the workpiece, U = Rx(A) Ry(B);
 *   xyzbc-hh (5axiskins, the bridge mill): the head turns about Z (C) and
 *     carries a tilt about Y (B); the cutter's orientation is Rz(C) Ry(-B)
 *     (the tool axis (-sin B cos C, -sin B sin C, cos B)), the head's axes
 *     meet `head` above the tip; the workpiece stays;
 *   xyzbc-ht (maxkins, 'max'): the head tilts about Y (B, cutter
 *     orientation Ry(-B)), the table turns the workpiece by -C about the
 *     Z axis through pivot: w sits at pivot + Rz(-C) (w - pivot); U = Rz(C) Ry(-B).
 * In TCP mode X Y Z are the tip in the workpiece frame; in joint mode they
 * are the joint positions (the tip where it would be at zero angles). */
typedef struct {
  swarf_machine_kind kind;
  int tcp;         /* 5-axis: 1 tool-centre-point mode (default), 0 joint mode */
  double pivot[3]; /* the table axes pass here, machine = workpiece frame at zero angles, mm */
  double head;     /* head machines: the head's pivot is this far above the tip at zero
                    * angles (along the tool axis), mm; used in joint mode. The
                    * simulation reads --machine head=L from the spindle's gauge
                    * line and adds the length of the tool in the spindle. */
} swarf_machine;

/* Fill `m` from "NAME[,key=value...]": NAME xyz, xyza, xyzac-trt, xyzbc-trt,
 * xyzab-tdr, xyzbc-hh, xyzbc-ht; keys pivot=Y,Z (xyza), pivot=X,Y,Z (trt,
 * tdr) or pivot=X,Y (ht: the C axis), head=L (hh, ht; required with
 * mode=joint), mode=tcp|joint (all 5-axis machines). SWARF_ERR_ARG when the
 * description is wrong: *err (may be NULL) gets the reason, naming --machine
 * (err->word "--machine"). */
SWARF_API swarf_status swarf_machine_parse(swarf_machine *m, const char *spec, swarf_error *err);

/* Pose at alpha: t (3) and U (3x3 row-major). */
SWARF_API void swarf_motion_eval(const swarf_motion *m, double alpha, double t[3], double U[9]);

/* Velocities at alpha with respect to alpha: tdot (workpiece frame) and the
 * moving-frame quantities of the paper, v = U^T tdot and omega
 * (U^T Udot = [omega]_x). */
SWARF_API void swarf_motion_velocity(const swarf_motion *m, double alpha, double tdot[3],
                                     double v[3], double omega[3]);

/* Pose and velocities at one alpha, as swarf_motion_eval and
 * swarf_motion_velocity give them (tdot omitted). */
typedef struct {
  double t[3], U[9];     /* pose: x' = t + U x */
  double v[3], omega[3]; /* moving-frame velocity and angular velocity, per unit alpha */
} swarf_pose;

/* A pose's rates in the workpiece frame: t' = U v and the derivative of the
 * tool axis k = U e_z, k' = U (omega x e_z) (what a ball end mill's sweep
 * needs per time step: sweep_rigid_ball.c). */
typedef struct {
  double tdot[3], kdot[3];
} swarf_pose_rates;

/* The rates of pose p. */
SWARF_API void swarf_pose_rates_of(const swarf_pose *p, swarf_pose_rates *out);

/* swarf_motion_eval and swarf_motion_velocity in one evaluation (the table
 * rotation's sines and cosines once). */
SWARF_API void swarf_motion_pose(const swarf_motion *m, double alpha, swarf_pose *out);

/* The poses at alpha = i / n, i = 0..n (n >= 1), into *out, from a
 * per-thread cache of the last motions asked for (keyed by the motion's
 * contents, so a motion changed in place is recomputed). The array belongs
 * to the cache and stays valid until the next call of this function on the
 * same thread. SWARF_ERR_MEMORY (*out = NULL) when out of memory,
 * SWARF_ERR_ARG for n < 1. Thread-safe (each thread has its own cache). */
SWARF_API swarf_status swarf_motion_pose_table(const swarf_motion *m, int n,
                                               const swarf_pose **out);

/* swarf_motion_pose_table, the table found by id (not 0) instead of a
 * comparison of m's contents: the caller's number for m's current contents,
 * which it must never give to other contents (a new number whenever m is
 * changed or its place reused). id 0: as swarf_motion_pose_table. */
SWARF_API swarf_status swarf_motion_pose_table_id(const swarf_motion *m, int n, uint64_t id,
                                                  const swarf_pose **out);

/* swarf_motion_pose_table_id and the poses' rates (swarf_pose_rates_of),
 * kept beside the table once asked for (the table alone keeps its size for
 * the callers that need only the poses). */
SWARF_API swarf_status swarf_motion_pose_table_rates(const swarf_motion *m, int n, uint64_t id,
                                                     const swarf_pose **poses,
                                                     const swarf_pose_rates **rates);

/* Axis-aligned bounds of the tip path t([0,1]), mm. */
SWARF_API void swarf_motion_bounds(const swarf_motion *m, double lo[3], double hi[3]);

/* True when the motion does not move the tip at all. */
SWARF_API int swarf_motion_is_null(const swarf_motion *m);

#ifdef __cplusplus
}
#endif
#endif
