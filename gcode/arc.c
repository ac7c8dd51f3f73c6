/* SPDX-License-Identifier: MPL-2.0 */
/* arc.c -- G2/G3 geometry: centre, sweep and helix of an arc, LinuxCNC's way.
 *
 * Follows rs274ngc's convert_arc and interp_arc.cc (arc_data_ijk,
 * arc_data_r). An arc lives in the active plane, named by its first and
 * second axes as LinuxCNC does: G17 (X, Y; offsets I, J), G18 (Z, X; K, I),
 * G19 (Y, Z; J, K); the third axis carries the helix. Each triple is
 * right-handed, so counter-clockwise in the plane is a positive turn about
 * the third axis: G3 has normal +third axis, G2 has -third axis.
 *
 * Centre format: the radii to start and end may differ (a slight spiral)
 * within LinuxCNC's tolerance; the move then follows the circle of the start
 * radius and ends at the programmed end (off by at most that tolerance).
 * Radius format: R < 0 asks for the arc longer than a half circle.
 * P (default 1) counts turns: the sweep grows by 2 pi (P - 1).
 * Lengths are mm here; messages print program units, as LinuxCNC does.
 */
#include <math.h>

#include "gcode_private.h"

#define TWO_PI 6.283185307179586476925286766559
#define HALF_PI 1.5707963267948966192313216916398
#define RADIUS_TOLERANCE_MM (0.00005 * SWARF_GC_MM_PER_INCH) /* below: a zero radius */
#define SPIRAL_TOLERANCE_MM (2 * 0.01 * 1.4142135623730950488)
#define SPIRAL_TOLERANCE_INCH (2 * 0.001 * 1.4142135623730950488)
#define SPIRAL_RELATIVE_TOLERANCE 0.001
#define FULL_CIRCLE_FUZZ_MM 1e-8 /* start and end this close: a full circle */
#define ZERO_SWEEP 5e-7          /* LinuxCNC's CIRCLE_FUZZ / 2 */

typedef struct {
  int a1, a2, a3;          /* first, second, third axis indices */
  char axis1, axis2;       /* their letters */
  char off1, off2, banned; /* centre offset letters; the offset letter not allowed */
  const char *name;
} plane_axes;

static const plane_axes planes[] = {
    {SWARF_AXIS_X, SWARF_AXIS_Y, SWARF_AXIS_Z, 'X', 'Y', 'I', 'J', 'K', "XY"},
    {SWARF_AXIS_Z, SWARF_AXIS_X, SWARF_AXIS_Y, 'Z', 'X', 'K', 'I', 'J', "XZ"},
    {SWARF_AXIS_Y, SWARF_AXIS_Z, SWARF_AXIS_X, 'Y', 'Z', 'J', 'K', 'I', "YZ"},
};

/* The arc's data in plane coordinates (mm), and what messages need. */
typedef struct {
  const plane_axes *pl;
  double s1, s2, e1, e2; /* start and end */
  double c1, c2;         /* centre */
  double scale;          /* mm per program unit */
  int ccw;               /* G3 */
  int column;            /* motion column, for messages */
} arc_data;

static const plane_axes *plane_of(const swarf_gc_state *st) {
  return st->modal.plane == 180 ? &planes[1] : st->modal.plane == 190 ? &planes[2] : &planes[0];
}

static int check_offsets(const swarf_gc_block *b, const swarf_gc_state *st, const arc_data *a,
                         swarf_error *f) {
  const swarf_gc_word *banned = swarf_gc_block_word(b, a->pl->banned);
  if (banned->present)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_PLANE_WORD, banned->column, a->pl->banned,
                         a->pl->name, banned->text);
  if (st->modal.arc_distance == 901) {
    char missing = !swarf_gc_block_has(b, a->pl->off1)   ? a->pl->off1
                   : !swarf_gc_block_has(b, a->pl->off2) ? a->pl->off2
                                                         : 0;
    if (missing) return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_CENTER_MISSING, a->column, missing);
  }
  return SWARF_OK;
}

/* The word checks of LinuxCNC's convert_arc, in its order. */
static int check_words(const swarf_gc_block *b, const swarf_gc_state *st, const arc_data *a,
                       swarf_error *f) {
  int r = swarf_gc_block_has(b, 'R');
  int ijk = swarf_gc_block_has(b, 'I') || swarf_gc_block_has(b, 'J') || swarf_gc_block_has(b, 'K');
  if (!r && !ijk) return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_WORDS_MISSING, a->column);
  if (r && ijk)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_MIXED_FORMAT, swarf_gc_block_word(b, 'R')->column);
  if (st->feed <= 0 && st->modal.feed_mode != 930) /* G93: rs274's 0.1 floor (motion.c) */
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_ZERO_FEED, a->column);
  if (ijk) return check_offsets(b, st, a, f);
  if (!swarf_gc_block_has(b, a->pl->axis1) && !swarf_gc_block_has(b, a->pl->axis2))
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_END_MISSING, a->column, a->pl->axis1, a->pl->axis2,
                         a->pl->name);
  return SWARF_OK;
}

static int radius_mismatch(const arc_data *a, double r1, double r2, double abs_err, double rel_err,
                           swarf_error *f) {
  double k = 1.0 / a->scale;
  char p = a->pl->axis1, q = a->pl->axis2;
  return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_RADIUS_MISMATCH, a->column, p, a->s1 * k, q, a->s2 * k,
                       p, a->c1 * k, q, a->c2 * k, p, a->e1 * k, q, a->e2 * k, r1 * k, r2 * k,
                       abs_err * k, rel_err * 100);
}

/* Centre format: the centre is given; the two radii must agree (LinuxCNC:
 * an error beyond 100 times the absolute tolerance, or beyond both the
 * absolute and the relative tolerance). */
static int centre_ijk(const swarf_gc_block *b, const swarf_gc_state *st, arc_data *a,
                      swarf_error *f) {
  double o1 = swarf_gc_block_word(b, a->pl->off1)->value * a->scale;
  double o2 = swarf_gc_block_word(b, a->pl->off2)->value * a->scale;
  double tol =
      st->modal.units == 200 ? SPIRAL_TOLERANCE_INCH * SWARF_GC_MM_PER_INCH : SPIRAL_TOLERANCE_MM;
  double r1, r2, abs_err, rel_err;
  int absolute = st->modal.arc_distance == 901;
  a->c1 = absolute ? o1 : a->s1 + o1;
  a->c2 = absolute ? o2 : a->s2 + o2;
  r1 = hypot(a->c1 - a->s1, a->c2 - a->s2);
  r2 = hypot(a->c1 - a->e1, a->c2 - a->e2);
  if (r1 < RADIUS_TOLERANCE_MM || r2 < RADIUS_TOLERANCE_MM)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_ZERO_RADIUS, a->column, r1 / a->scale, r2 / a->scale);
  abs_err = fabs(r1 - r2);
  rel_err = abs_err / fmax(r1, r2);
  if (abs_err > 100 * tol || (abs_err > tol && rel_err > SPIRAL_RELATIVE_TOLERANCE))
    return radius_mismatch(a, r1, r2, abs_err, rel_err, f);
  return SWARF_OK;
}

/* Radius format: the centre lies on the perpendicular bisector of the chord,
 * on the side that makes the arc short (R > 0) or long (R < 0). */
static int centre_r(const swarf_gc_block *b, arc_data *a, swarf_error *f) {
  double r = swarf_gc_block_word(b, 'R')->value * a->scale;
  double abs_r = fabs(r), m1, m2, half, theta, offset;
  if (a->e1 == a->s1 && a->e2 == a->s2)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_SAME_POINT, a->column);
  m1 = (a->s1 + a->e1) / 2;
  m2 = (a->s2 + a->e2) / 2;
  half = hypot(m1 - a->e1, m2 - a->e2);
  if (!(abs_r > 0) || half - abs_r > RADIUS_TOLERANCE_MM)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_RADIUS_TOO_SMALL, a->column, r / a->scale,
                         2 * half / a->scale);
  if (half / abs_r > 1 - 1e-12) half = abs_r;
  theta = atan2(a->e2 - a->s2, a->e1 - a->s1) + ((!a->ccw) == (r > 0) ? -HALF_PI : HALF_PI);
  offset = abs_r * cos(asin(half / abs_r));
  a->c1 = m1 + offset * cos(theta);
  a->c2 = m2 + offset * sin(theta);
  return SWARF_OK;
}

/* Sweep from start to end about the centre in the arc's sense, as LinuxCNC's
 * motion planner takes it (pmCircleInit): a full circle when start and end
 * coincide in the plane (within 1e-8), else the angle between them in
 * (0, 2 pi), however small; an exact zero (start and end on one ray, radii
 * differing) stays a tiny positive sweep. */
double swarf_gc_arc_sweep(double s1, double s2, double e1, double e2, double c1, double c2,
                          int ccw) {
  double ts, te, d;
  if (hypot(e1 - s1, e2 - s2) < FULL_CIRCLE_FUZZ_MM) return TWO_PI;
  ts = atan2(s2 - c2, s1 - c1);
  te = atan2(e2 - c2, e1 - c1);
  d = ccw ? te - ts : ts - te;
  if (d < 0) d += TWO_PI;
  if (d >= TWO_PI) d -= TWO_PI;
  return d > 0 ? d : ZERO_SWEEP;
}

static double sweep(const arc_data *a) {
  return swarf_gc_arc_sweep(a->s1, a->s2, a->e1, a->e2, a->c1, a->c2, a->ccw);
}

static int turns_of(const swarf_gc_block *b) {
  return swarf_gc_block_has(b, 'P') ? (int)floor(swarf_gc_block_word(b, 'P')->value + 0.5) : 1;
}

int swarf_gc_arc(const swarf_gc_block *b, const swarf_gc_state *st, swarf_move *mv, int *turns,
                 swarf_error *f) {
  arc_data a;
  double sign;
  int status;
  a.pl = plane_of(st);
  a.s1 = mv->start[a.pl->a1], a.s2 = mv->start[a.pl->a2];
  a.e1 = mv->end[a.pl->a1], a.e2 = mv->end[a.pl->a2];
  a.scale = st->modal.units == 200 ? SWARF_GC_MM_PER_INCH : 1.0;
  a.c1 = a.c2 = 0;
  a.ccw = b->motion == 30;
  a.column = b->motion_column;
  status = check_words(b, st, &a, f);
  if (status == SWARF_OK)
    status = swarf_gc_block_has(b, 'R') ? centre_r(b, &a, f) : centre_ijk(b, st, &a, f);
  if (status != SWARF_OK) return status;
  sign = a.ccw ? 1.0 : -1.0;
  mv->center[a.pl->a1] = a.c1;
  mv->center[a.pl->a2] = a.c2;
  mv->center[a.pl->a3] = mv->start[a.pl->a3];
  mv->normal[a.pl->a3] = sign;
  mv->angle = sweep(&a) + TWO_PI * (turns_of(b) - 1);
  *turns = a.ccw ? turns_of(b) : -turns_of(b);
  mv->rise = sign * (mv->end[a.pl->a3] - mv->start[a.pl->a3]);
  return SWARF_OK;
}
