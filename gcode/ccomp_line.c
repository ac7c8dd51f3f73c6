/* SPDX-License-Identifier: MPL-2.0 */
/* ccomp_line.c -- the compensated path of G0 and G1 under cutter compensation:
 * the entry move, corners before a line (convex: an arc; concave: the
 * held move ends where the offset paths cross)
 * (see ccomp.c for LinuxCNC's rules, ccomp.h for the plane coordinates).
 */
#include <math.h>
#include <string.h>

#include "ccomp.h"

/* ---- straight moves ------------------------------------------------------ */

/* The first move: to the end offset perpendicular to the move. */
static int straight_entry(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                          swarf_gc_call_kind kind, const double end[SWARF_NAXES], swarf_error *f) {
  swarf_gc_cc_plane pl = swarf_gc_cc_plane_of(st);
  double r = st->comp_radius, at[SWARF_NAXES];
  double cx = st->comp_pos[pl.a1], cy = st->comp_pos[pl.a2], px = end[pl.a1], py = end[pl.a2];
  double alpha, x, y;
  if (hypot(px - cx, py - cy) <= r)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ENTRY_LINE, b->motion_column);
  alpha = atan2(py - cy, px - cx) + (st->comp_side == LEFT ? HALF_PI : -HALF_PI);
  x = px + r * cos(alpha);
  y = py + r * sin(alpha);
  swarf_gc_tool_pos(st, at);
  swarf_gc_cc_set_endpoint(st, cx, cy);
  swarf_gc_cc_hold_line(st, ex, &pl, kind, at, x, y, end, cos(alpha), sin(alpha), b->motion_column);
  st->comp_first = 0;
  swarf_gc_cc_set_current(st, &pl, x, y, end[pl.a3]);
  return SWARF_OK;
}

/* Where a held arc (compensated) meets the next line's offset. */
static int arc_line_corner(const swarf_gc_call *prev, const swarf_gc_cc_plane *pl, int side,
                           double r, double base_dir, double opx, double opy, double *mx,
                           double *my, int column, swarf_error *f) {
  const swarf_move *mv = &prev->move;
  double pc1 = mv->center[pl->a1], pc2 = mv->center[pl->a2];
  double oldrad = hypot(pc1 - mv->end[pl->a1], pc2 - mv->end[pl->a2]);
  int inside = swarf_gc_cc_inside(side, prev->turns), ccw = prev->turns > 0;
  double th = base_dir + (ccw ? HALF_PI : -HALF_PI), phi = atan2(pc2 - opy, pc1 - opx);
  double d = (inside ? oldrad + r : oldrad - r) * cos(th - phi);
  double l = (inside ? d - r : d + r) / oldrad, ang;
  if (l > 1.0 || l < -1.0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ARC_LINE_CORNER, column);
  ang = ((inside == ccw) ? -acos(l) : acos(l)) + th + PI;
  *mx = pc1 + oldrad * cos(ang);
  *my = pc2 + oldrad * sin(ang);
  return SWARF_OK;
}

/* Corner geometry of a straight move after another move. */
typedef struct {
  double beta, gamma; /* corner angle (0: tangent, < 0 or > pi: concave); side offset */
  double theta;       /* direction from the programmed corner to the tool */
  double alpha;       /* direction of the new move */
} corner;

static corner line_corner(int side, double cx, double cy, double opx, double opy, double px,
                          double py) {
  corner k;
  k.theta = atan2(cy - opy, cx - opx);
  k.alpha = atan2(py - opy, px - opx);
  if (side == LEFT) {
    if (k.theta < k.alpha) k.theta += TWO_PI;
    k.beta = k.theta - k.alpha - HALF_PI;
    k.gamma = HALF_PI;
  } else {
    if (k.alpha < k.theta) k.alpha += TWO_PI;
    k.beta = k.alpha - k.theta - HALF_PI;
    k.gamma = -HALF_PI;
  }
  return k;
}

/* Concave corner before a line: the held move ends where the paths cross. */
static int line_concave(swarf_gc_state *st, swarf_gc_exec *ex, const swarf_gc_cc_plane *pl,
                        const corner *k, double px, double py, double at[SWARF_NAXES], int column,
                        swarf_error *f) {
  double cx = st->comp_pos[pl->a1], cy = st->comp_pos[pl->a2], r = st->comp_radius, mx = 0, my = 0;
  double opx = st->pos[pl->a1], opy = st->pos[pl->a2];
  swarf_gc_call *prev = swarf_gc_cc_front(ex->out);
  int status;
  if (prev == NULL || prev->kind != SWARF_GC_CALL_ARC) {
    double half = (k->beta + PI) / 2;
    if (half == 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ZERO_CORNER, column);
    mx = cx + r / tan(half) * cos(k->theta + k->gamma);
    my = cy + r / tan(half) * sin(k->theta + k->gamma);
  } else {
    status = arc_line_corner(prev, pl, st->comp_side, r, atan2(py - opy, px - opx), opx, opy, &mx,
                             &my, column, f);
    if (status != SWARF_OK) return status;
  }
  status = swarf_gc_cc_move_ends(st, ex, mx, my, column, f);
  if (status == SWARF_OK && prev != NULL) at[pl->a1] = mx, at[pl->a2] = my;
  return status;
}

/* A later straight move: corner, then a held line to the offset end. */
static int straight_next(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                         swarf_gc_call_kind kind, const double end[SWARF_NAXES], swarf_error *f) {
  swarf_gc_cc_plane pl = swarf_gc_cc_plane_of(st);
  double r = st->comp_radius, at[SWARF_NAXES], x, y;
  double cx = st->comp_pos[pl.a1], cy = st->comp_pos[pl.a2];
  double opx = st->pos[pl.a1], opy = st->pos[pl.a2], px = end[pl.a1], py = end[pl.a2];
  int col = b->motion_column, status = SWARF_OK, concave;
  swarf_gc_call *prev;
  corner k;
  swarf_gc_tool_pos(st, at);
  if (px == opx && py == opy) { /* no motion in the plane */
    swarf_gc_cc_hold_line(st, ex, &pl, kind, at, cx, cy, end, 0, 0, col);
    swarf_gc_cc_set_current(st, &pl, cx, cy, end[pl.a3]);
    return SWARF_OK;
  }
  prev = swarf_gc_cc_front(ex->out);
  k = line_corner(st->comp_side, cx, cy, opx, opy, px, py);
  x = px + r * cos(k.alpha + k.gamma);
  y = py + r * sin(k.alpha + k.gamma);
  concave = k.beta < -SMALL || k.beta > PI + SMALL ||
            (k.beta > PI - SMALL && prev != NULL && prev->kind == SWARF_GC_CALL_ARC &&
             !swarf_gc_cc_inside(st->comp_side, prev->turns));
  if (!concave && k.beta > SMALL) {
    status = swarf_gc_cc_move_ends(st, ex, cx, cy, col, f);
    if (status == SWARF_OK)
      swarf_gc_cc_corner_convex(st, ex, &pl, kind, opx + r * cos(k.alpha + k.gamma),
                                opy + r * sin(k.alpha + k.gamma), end, at, col);
  } else if (concave)
    status = line_concave(st, ex, &pl, &k, px, py, at, col, f);
  else {
    swarf_gc_cc_dequeue(st, ex);
    swarf_gc_cc_set_endpoint(st, cx, cy);
  }
  if (status != SWARF_OK) return status;
  swarf_gc_cc_hold_line(st, ex, &pl, kind, at, x, y, end, px - opx, py - opy, col);
  swarf_gc_cc_set_current(st, &pl, x, y, end[pl.a3]);
  return SWARF_OK;
}

int swarf_gc_comp_straight(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                           const double end[SWARF_NAXES], swarf_error *f) {
  swarf_gc_call_kind kind = b->motion == 0 ? SWARF_GC_CALL_TRAVERSE : SWARF_GC_CALL_FEED;
  if (st->comp_first) return straight_entry(b, st, ex, kind, end, f);
  return straight_next(b, st, ex, kind, end, f);
}
