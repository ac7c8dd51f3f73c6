/* SPDX-License-Identifier: MPL-2.0 */
/* ccomp.h -- what the files of cutter radius compensation share (ccomp.c:
 * on, off and refusals; ccomp_queue.c: the held move; ccomp_line.c and
 * ccomp_arc.c: the compensated path of lines and arcs). Not used elsewhere.
 *
 * Positions are program mm, in plane coordinates: the plane's first and
 * second axes (G17: X, Y; G18: Z, X), seen from its normal's positive end.
 */
#ifndef SWARF_GCODE_CCOMP_H
#define SWARF_GCODE_CCOMP_H

#include "gcode_private.h"

#define SWARF_GC_CC_PI 3.14159265358979323846
#define SWARF_GC_CC_SMALL 0.05   /* TOLERANCE_CONCAVE_CORNER: tangent within, radians */
#define SWARF_GC_CC_EQUAL 0.0001 /* TOLERANCE_EQUAL */

typedef struct {
  int a1, a2, a3; /* first, second and normal axis */
  double s;       /* mm per program unit */
} swarf_gc_cc_plane;

swarf_gc_cc_plane swarf_gc_cc_plane_of(const swarf_gc_state *st);
/* The tool is inside an arc turning this way (LinuxCNC's TOOL_INSIDE_ARC). */
int swarf_gc_cc_inside(int side, int turns);
/* Signed sweep from (x1, y1) to (x2, y2) about (cx, cy) with `turns` turns
 * (LinuxCNC's find_turn: a coincident end is a whole turn). */
double swarf_gc_cc_find_turn(double x1, double y1, double cx, double cy, int turns, double x2,
                             double y2);
/* The compensated tool point becomes (x, y) in the plane, z on its normal. */
void swarf_gc_cc_set_current(swarf_gc_state *st, const swarf_gc_cc_plane *pl, double x, double y,
                             double z);

/* The first held motion, or NULL (LinuxCNC's qc().front()). */
swarf_gc_call *swarf_gc_cc_front(swarf_gc_out *o);
/* All held calls go out as they are; the recorded end point (the start
 * of the held move, LinuxCNC's `endpoint`) is forgotten (dequeue_canons). */
void swarf_gc_cc_dequeue(swarf_gc_state *st, swarf_gc_exec *ex);
/* Records where the next held move starts (LinuxCNC's set_endpoint). */
void swarf_gc_cc_set_endpoint(swarf_gc_state *st, double x, double y);
/* Every held move ends at (x, y), checked for gouging, then all held calls
 * go out (LinuxCNC's move_endpoint_and_flush); nothing if none is held.
 * The checks look from the recorded end point, when there is one: LinuxCNC
 * does not record one for an entry arc, nor after a plain dequeue.
 * Errors name `column`. */
int swarf_gc_cc_move_ends(swarf_gc_state *st, swarf_gc_exec *ex, double x, double y, int column,
                          swarf_error *f);
/* A held line from `at` to (x, y) in the plane, the other axes from `end`;
 * (d1, d2) is the programmed direction the gouging check compares with. */
void swarf_gc_cc_hold_line(swarf_gc_state *st, swarf_gc_exec *ex, const swarf_gc_cc_plane *pl,
                           swarf_gc_call_kind kind, const double at[SWARF_NAXES], double x,
                           double y, const double end[SWARF_NAXES], double d1, double d2,
                           int column);
/* A held arc from `at` to (x, y, z) about (c1, c2); A B C go to `end`'s;
 * `sweep` is its signed sweep as programmed (0: never moved). */
void swarf_gc_cc_hold_arc(swarf_gc_state *st, swarf_gc_exec *ex, const swarf_gc_cc_plane *pl,
                          const double at[SWARF_NAXES], double x, double y, double z, double c1,
                          double c2, int turns, double sweep, const double end[SWARF_NAXES],
                          int column);
/* A convex corner: an arc about the programmed corner to (mx, my) (a
 * traverse for G0), which goes out at once; `at` becomes its end. */
int swarf_gc_cc_corner_convex(swarf_gc_state *st, swarf_gc_exec *ex, const swarf_gc_cc_plane *pl,
                              swarf_gc_call_kind kind, double mx, double my,
                              const double end[SWARF_NAXES], double at[SWARF_NAXES], int column);

/* Short names used throughout the ccomp*.c files (only they include this header). */
#define PI SWARF_GC_CC_PI
#define HALF_PI (PI / 2)
#define TWO_PI (2 * PI)
#define SMALL SWARF_GC_CC_SMALL
#define EQUAL SWARF_GC_CC_EQUAL
#define LEFT SWARF_GC_COMP_LEFT
#define RIGHT SWARF_GC_COMP_RIGHT

#endif
