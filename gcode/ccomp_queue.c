/* SPDX-License-Identifier: MPL-2.0 */
/* ccomp_queue.c -- cutter compensation's held move: LinuxCNC holds a move back
 * until the next one says where it ends, then moves its end and lets it go
 * (see ccomp.c for LinuxCNC's rules, ccomp.h for the plane coordinates).
 */
#include <math.h>
#include <string.h>

#include "ccomp.h"

/* The tool is inside an arc turning this way (LinuxCNC's TOOL_INSIDE_ARC). */
int swarf_gc_cc_inside(int side, int turns) {
  return (side == LEFT && turns > 0) || (side == RIGHT && turns < 0);
}

/* Signed sweep from (x1, y1) to (x2, y2) about (cx, cy), `turns` turns
 * (LinuxCNC's find_turn: a coincident end is a whole turn). */
double swarf_gc_cc_find_turn(double x1, double y1, double cx, double cy, int turns, double x2,
                             double y2) {
  double a = atan2(y1 - cy, x1 - cx), b = atan2(y2 - cy, x2 - cx);
  if (turns == 0) return 0;
  if (turns > 0) {
    if (b <= a) b += TWO_PI;
    return b - a + (turns - 1) * TWO_PI;
  }
  if (a <= b) a += TWO_PI;
  return b - a + (turns + 1) * TWO_PI;
}

/* ---- the plane ----------------------------------------------------------- */

swarf_gc_cc_plane swarf_gc_cc_plane_of(const swarf_gc_state *st) {
  int ax[3];
  swarf_gc_cc_plane pl;
  swarf_gc_plane_axes(st, ax);
  pl.a1 = ax[0], pl.a2 = ax[1], pl.a3 = ax[2];
  pl.s = swarf_gc_scale(st);
  return pl;
}

void swarf_gc_cc_set_current(swarf_gc_state *st, const swarf_gc_cc_plane *pl, double x, double y,
                             double z) {
  st->comp_pos[pl->a1] = x;
  st->comp_pos[pl->a2] = y;
  st->comp_pos[pl->a3] = z;
}

/* Sweep (radians, > 0) of an arc move, full turns included. */
static void arc_angle(swarf_move *mv, const swarf_gc_cc_plane *pl, int turns) {
  int n = turns < 0 ? -turns : turns;
  mv->angle =
      swarf_gc_arc_sweep(mv->start[pl->a1], mv->start[pl->a2], mv->end[pl->a1], mv->end[pl->a2],
                         mv->center[pl->a1], mv->center[pl->a2], turns > 0) +
      TWO_PI * (n - 1);
  mv->rise = (turns > 0 ? 1 : -1) * (mv->end[pl->a3] - mv->start[pl->a3]);
}

/* ---- the held move ------------------------------------------------------- */

/* The first held motion, or NULL (LinuxCNC's qc().front()). */
swarf_gc_call *swarf_gc_cc_front(swarf_gc_out *o) {
  swarf_gc_out_take_held(o);
  for (size_t i = o->ready; i < o->count; i++)
    if (o->calls[i].kind <= SWARF_GC_CALL_ARC) return &o->calls[i];
  return NULL;
}

/* A held arc ends at (x, y): it must keep its radius and, seen from the
 * recorded end point `ep` (NULL: none), not grow past what it was by more
 * than LinuxCNC allows. */
static int move_arc_end(swarf_gc_call *c, const swarf_gc_cc_plane *pl, const double *ep, double x,
                        double y, int column, swarf_error *f) {
  swarf_move *mv = &c->move;
  double c1 = mv->center[pl->a1], c2 = mv->center[pl->a2];
  double r1 = hypot(mv->end[pl->a1] - c1, mv->end[pl->a2] - c2), r2 = hypot(x - c1, y - c2);
  double l2 = ep ? swarf_gc_cc_find_turn(ep[0], ep[1], c1, c2, c->turns, x, y) : 0;
  if (fabs(r1 - r2) / pl->s > .01)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ARC_BUG, column, r1 / pl->s, r2 / pl->s);
  if (c->sweep != 0 && ep != NULL && fabs(l2) > fabs(c->sweep) + (pl->s == 1 ? .0254 : .001))
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ARC_GOUGE, column);
  mv->end[pl->a1] = x;
  mv->end[pl->a2] = y;
  arc_angle(mv, pl, c->turns);
  return SWARF_OK;
}

/* A held line ends at (x, y): seen from `ep` (NULL: none), it must not
 * turn back against its programmed direction. */
static int move_line_end(swarf_gc_call *c, const swarf_gc_cc_plane *pl, const double *ep, double x,
                         double y, int column, swarf_error *f) {
  swarf_move *mv = &c->move;
  if (ep != NULL && c->dir[0] * (x - ep[0]) + c->dir[1] * (y - ep[1]) < 0)
    return c->kind == SWARF_GC_CALL_TRAVERSE
               ? SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_TRAVERSE_GOUGE, column)
               : SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_FEED_GOUGE, column);
  mv->end[pl->a1] = x;
  mv->end[pl->a2] = y;
  return SWARF_OK;
}

void swarf_gc_cc_dequeue(swarf_gc_state *st, swarf_gc_exec *ex) {
  swarf_gc_out_flush(ex->out, st);
  st->comp_end_valid = 0;
}

void swarf_gc_cc_set_endpoint(swarf_gc_state *st, double x, double y) {
  st->comp_end[0] = x;
  st->comp_end[1] = y;
  st->comp_end_valid = 1;
}

/* Every held move ends at (x, y), then all held calls go out
 * (LinuxCNC's move_endpoint_and_flush). */
int swarf_gc_cc_move_ends(swarf_gc_state *st, swarf_gc_exec *ex, double x, double y, int column,
                          swarf_error *f) {
  swarf_gc_out *o = ex->out;
  swarf_gc_cc_plane pl = swarf_gc_cc_plane_of(st);
  const double *prev = NULL, *ep = st->comp_end_valid ? st->comp_end : NULL;
  swarf_gc_out_take_held(o);
  if (o->ready == o->count) return SWARF_OK;
  for (size_t i = o->ready; i < o->count; i++) {
    swarf_gc_call *c = &o->calls[i];
    int status = SWARF_OK;
    if (c->kind == SWARF_GC_CALL_TEXT) continue;
    if (prev != NULL) memcpy(c->move.start, prev, sizeof c->move.start);
    if (c->kind == SWARF_GC_CALL_ARC)
      status = move_arc_end(c, &pl, ep, x, y, column, f);
    else if (c->kind <= SWARF_GC_CALL_FEED)
      status = move_line_end(c, &pl, ep, x, y, column, f);
    else
      memcpy(c->move.end, c->move.start, sizeof c->move.end);
    if (status != SWARF_OK) return status;
    prev = c->move.end;
  }
  swarf_gc_cc_dequeue(st, ex);
  swarf_gc_cc_set_endpoint(st, x, y);
  return SWARF_OK;
}

/* ---- adding moves -------------------------------------------------------- */

/* A held line from `at` to (x, y) in the plane, the rest of `end`. */
void swarf_gc_cc_hold_line(swarf_gc_state *st, swarf_gc_exec *ex, const swarf_gc_cc_plane *pl,
                           swarf_gc_call_kind kind, const double at[SWARF_NAXES], double x,
                           double y, const double end[SWARF_NAXES], double d1, double d2,
                           int column) {
  double e[SWARF_NAXES];
  swarf_gc_call *c;
  memcpy(e, end, sizeof e);
  e[pl->a1] = x;
  e[pl->a2] = y;
  c = swarf_gc_out_hold_line(ex->out, st, kind, at, e, column);
  if (c != NULL) c->dir[0] = d1, c->dir[1] = d2;
}

/* A held arc from `at` to (x, y, z) about (c1, c2), axes A B C to `end`'s. */
void swarf_gc_cc_hold_arc(swarf_gc_state *st, swarf_gc_exec *ex, const swarf_gc_cc_plane *pl,
                          const double at[SWARF_NAXES], double x, double y, double z, double c1,
                          double c2, int turns, double sweep, const double end[SWARF_NAXES],
                          int column) {
  swarf_move mv;
  swarf_gc_call *c;
  memset(&mv, 0, sizeof mv);
  memcpy(mv.start, at, sizeof mv.start);
  memcpy(mv.end, end, sizeof mv.end);
  mv.end[pl->a1] = x, mv.end[pl->a2] = y, mv.end[pl->a3] = z;
  mv.center[pl->a1] = c1, mv.center[pl->a2] = c2, mv.center[pl->a3] = at[pl->a3];
  mv.normal[pl->a3] = turns > 0 ? 1 : -1;
  arc_angle(&mv, pl, turns);
  c = swarf_gc_out_hold_arc(ex->out, st, &mv, turns, column);
  if (c != NULL) c->sweep = sweep;
}

/* Convex corner: an arc about the programmed corner to (mx, my), or a
 * traverse for G0; A B C reach `end`'s on it. The tool is then there. */
int swarf_gc_cc_corner_convex(swarf_gc_state *st, swarf_gc_exec *ex, const swarf_gc_cc_plane *pl,
                              swarf_gc_call_kind kind, double mx, double my,
                              const double end[SWARF_NAXES], double at[SWARF_NAXES], int column) {
  double e[SWARF_NAXES];
  memcpy(e, end, sizeof e);
  e[pl->a1] = mx, e[pl->a2] = my, e[pl->a3] = st->comp_pos[pl->a3];
  if (kind == SWARF_GC_CALL_TRAVERSE)
    swarf_gc_cc_hold_line(st, ex, pl, kind, at, mx, my, e, 0, 0, column);
  else
    swarf_gc_cc_hold_arc(st, ex, pl, at, mx, my, e[pl->a3], st->pos[pl->a1], st->pos[pl->a2],
                         st->comp_side == LEFT ? -1 : 1, 0, e, column);
  swarf_gc_cc_dequeue(st, ex);
  swarf_gc_cc_set_endpoint(st, mx, my);
  memcpy(at, e, sizeof e);
  return SWARF_OK;
}
