/* SPDX-License-Identifier: MPL-2.0 */
/* ccomp_arc.c -- the compensated path of G2 and G3 under cutter compensation:
 * the entry arc, corners before an arc, the arc offset along its radius
 * (see ccomp.c for LinuxCNC's rules, ccomp.h for the plane coordinates).
 */
#include <math.h>
#include <string.h>

#include "ccomp.h"

/* ---- arcs ---------------------------------------------------------------- */

/* The first move is an arc: to the end offset along its radius, about a
 * new centre on that radius as far from the tool as from the new end. */
static int arc_entry(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                     const swarf_move *mv, int turns, swarf_error *f) {
  swarf_gc_cc_plane pl = swarf_gc_cc_plane_of(st);
  double r = st->comp_radius, at[SWARF_NAXES];
  double cx = st->comp_pos[pl.a1], cy = st->comp_pos[pl.a2];
  double c1 = mv->center[pl.a1], c2 = mv->center[pl.a2];
  double x = mv->end[pl.a1], y = mv->end[pl.a2], gamma, half, ab, a;
  int col = b->motion_column, inside = swarf_gc_cc_inside(st->comp_side, turns);
  if (hypot(x - cx, y - cy) <= r) return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ENTRY_ARC, col);
  if (inside && hypot(x - c1, y - c2) <= r)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ARC_RADIUS, col);
  gamma = inside ? atan2(c2 - y, c1 - x) : atan2(y - c2, x - c1);
  x += r * cos(gamma);
  y += r * sin(gamma);
  half = hypot(cy - y, cx - x) / 2;
  ab = atan2(c2 - y, c1 - x);
  a = atan2(cy - y, cx - x) - ab;
  if (fabs(cos(a)) < EQUAL) return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ARC_RADIUS, col);
  c1 = x + half / cos(a) * cos(ab);
  c2 = y + half / cos(a) * sin(ab);
  swarf_gc_tool_pos(st, at);
  swarf_gc_cc_hold_arc(st, ex, &pl, at, x, y, mv->end[pl.a3], c1, c2, turns,
                       swarf_gc_cc_find_turn(cx, cy, c1, c2, turns, x, y), mv->end, col);
  st->comp_first = 0;
  swarf_gc_cc_set_current(st, &pl, x, y, mv->end[pl.a3]);
  return SWARF_OK;
}

/* Where the held line's offset meets the new arc's offset circle. */
static int line_arc_corner(double beta, double theta, double c1, double c2, double arc_r, double r,
                           int inside, int turns, double *mx, double *my, int column,
                           swarf_error *f) {
  double cy = arc_r * sin(beta - HALF_PI);
  double dist = inside ? arc_r - r : arc_r + r;
  double l = (inside ? cy + r : cy - r) / dist, ang;
  if (l > 1.0 || l < -1.0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ARC_GOUGE, column);
  if (inside)
    ang = turns > 0 ? theta + asin(l) : theta - asin(l);
  else
    ang = turns > 0 ? theta + PI - asin(l) : theta + PI + asin(l);
  *mx = c1 + dist * cos(ang);
  *my = c2 + dist * sin(ang);
  return SWARF_OK;
}

/* Where the held arc (compensated) meets the new arc's offset circle. */
static int arc_arc_corner(const swarf_gc_call *prev, const swarf_gc_cc_plane *pl, int side,
                          double c1, double c2, double newrad, int turns, double *mx, double *my,
                          int column, swarf_error *f) {
  const swarf_move *mv = &prev->move;
  double pc1 = mv->center[pl->a1], pc2 = mv->center[pl->a2];
  double oldrad = hypot(pc1 - mv->end[pl->a1], pc2 - mv->end[pl->a2]);
  double cc = hypot(pc2 - c2, pc1 - c1), a, pull, dir, ccdir;
  if (oldrad == 0 || cc == 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ARCS_SAME_CENTER, column);
  a = (oldrad * oldrad + cc * cc - newrad * newrad) / (2 * oldrad * cc);
  if (a > 1.0 || a < -1.0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ARC_ARC_CORNER, column);
  pull = acos(a);
  ccdir = atan2(c2 - pc2, c1 - pc1);
  dir = (swarf_gc_cc_inside(side, prev->turns) == (turns > 0)) ? ccdir + pull : ccdir - pull;
  *mx = pc1 + oldrad * cos(dir);
  *my = pc2 + oldrad * sin(dir);
  return SWARF_OK;
}

/* Corner geometry of an arc after another move. */
typedef struct {
  double beta;  /* angle between the tangents, in [-pi/2, 3 pi/2) */
  double theta; /* direction of the last cut's tangent */
  double delta; /* direction from the programmed start to the tool's start */
  int inside;   /* the tool cuts inside the arc */
} arc_corner;

static arc_corner arc_corner_of(int side, int ccw, double cx, double cy, double opx, double opy,
                                double c1, double c2) {
  arc_corner k;
  double alpha;
  k.theta = atan2(cy - opy, cx - opx) + (side == LEFT ? -HALF_PI : HALF_PI);
  k.delta = atan2(c2 - opy, c1 - opx);
  alpha = ccw ? k.delta - HALF_PI : k.delta + HALF_PI;
  k.beta = side == LEFT ? k.theta - alpha : alpha - k.theta;
  if (k.beta > 1.5 * PI)
    k.beta -= TWO_PI;
  else if (k.beta < -HALF_PI)
    k.beta += TWO_PI;
  k.inside = (side == LEFT && ccw) || (side == RIGHT && !ccw);
  if (!k.inside) k.delta += PI;
  return k;
}

static int arc_concave(swarf_gc_state *st, swarf_gc_exec *ex, const swarf_gc_cc_plane *pl,
                       const arc_corner *k, double c1, double c2, double arc_r, int turns,
                       double at[SWARF_NAXES], int column, swarf_error *f) {
  swarf_gc_call *prev = swarf_gc_cc_front(ex->out);
  double r = st->comp_radius, mx = 0, my = 0;
  int status;
  if (prev == NULL || prev->kind != SWARF_GC_CALL_ARC)
    status =
        line_arc_corner(k->beta, k->theta, c1, c2, arc_r, r, k->inside, turns, &mx, &my, column, f);
  else
    status = arc_arc_corner(prev, pl, st->comp_side, c1, c2, k->inside ? arc_r - r : arc_r + r,
                            turns, &mx, &my, column, f);
  if (status == SWARF_OK) status = swarf_gc_cc_move_ends(st, ex, mx, my, column, f);
  if (status == SWARF_OK && prev != NULL) at[pl->a1] = mx, at[pl->a2] = my;
  return status;
}

static int arc_next(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                    const swarf_move *mv, int turns, swarf_error *f) {
  swarf_gc_cc_plane pl = swarf_gc_cc_plane_of(st);
  double r = st->comp_radius, at[SWARF_NAXES];
  double opx = st->pos[pl.a1], opy = st->pos[pl.a2];
  double c1 = mv->center[pl.a1], c2 = mv->center[pl.a2];
  double ex1 = mv->end[pl.a1], ex2 = mv->end[pl.a2], arc_r = hypot(c1 - ex1, c2 - ex2), gamma;
  int col = b->motion_column, status = SWARF_OK;
  arc_corner k = arc_corner_of(st->comp_side, b->motion == 30, st->comp_pos[pl.a1],
                               st->comp_pos[pl.a2], opx, opy, c1, c2);
  if (k.inside && arc_r <= r) return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ARC_RADIUS, col);
  gamma = k.inside ? atan2(c2 - ex2, c1 - ex1) : atan2(ex2 - c2, ex1 - c1);
  swarf_gc_tool_pos(st, at);
  if (k.beta < -SMALL || k.beta > PI + SMALL || (fabs(k.beta - PI) < SMALL && !k.inside))
    status = arc_concave(st, ex, &pl, &k, c1, c2, arc_r, turns, at, col, f);
  else if (k.beta > SMALL) {
    swarf_gc_cc_dequeue(st, ex);
    swarf_gc_cc_corner_convex(st, ex, &pl, SWARF_GC_CALL_FEED, opx + r * cos(k.delta),
                              opy + r * sin(k.delta), mv->end, at, col);
  } else {
    swarf_gc_cc_dequeue(st, ex);
    swarf_gc_cc_set_endpoint(st, st->comp_pos[pl.a1], st->comp_pos[pl.a2]);
  }
  if (status != SWARF_OK) return status;
  ex1 += r * cos(gamma);
  ex2 += r * sin(gamma);
  swarf_gc_cc_hold_arc(
      st, ex, &pl, at, ex1, ex2, mv->end[pl.a3], c1, c2, turns,
      swarf_gc_cc_find_turn(opx, opy, c1, c2, turns, mv->end[pl.a1], mv->end[pl.a2]), mv->end, col);
  swarf_gc_cc_set_current(st, &pl, ex1, ex2, mv->end[pl.a3]);
  return SWARF_OK;
}

int swarf_gc_comp_arc(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                      const swarf_move *mv, int turns, swarf_error *f) {
  if (st->comp_first) return arc_entry(b, st, ex, mv, turns, f);
  return arc_next(b, st, ex, mv, turns, f);
}
