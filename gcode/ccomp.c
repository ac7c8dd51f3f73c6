/* SPDX-License-Identifier: MPL-2.0 */
/* ccomp.c -- cutter radius compensation (G40, G41, G42, G41.1, G42.1), as
 * LinuxCNC 2.9's interpreter does it.
 *
 * G41/G42 take the radius from the tool table (D: tool number, default the
 * tool in the spindle); G41.1/G42.1 take D as the diameter (a negative one
 * swaps the side). Compensation works in the plane's first and second axes
 * (G17: X, Y; G18: Z, X), the side seen from the plane's normal.
 *
 * LinuxCNC's path, in plane coordinates (op: programmed start, p:
 * programmed end, c: the compensated tool point now):
 *   - entry move (first move after G41/G42): a line to p offset by the
 *     radius perpendicular to the move; an arc to its end offset along the
 *     radius, with a new centre on that radius, equidistant from c;
 *   - later moves end at p offset perpendicular to the move (lines) or
 *     along the radius (arcs). A convex corner gets an arc about op (a
 *     straight traverse for G0); a concave one moves the end of the held
 *     move to where the two offset paths cross;
 *   - one move is held back (with the calls queued after it, see
 *     gcode_private.h's swarf_gc_out) until the next one says where it
 *     ends; G40, M0, M1, M2 and the end of the program release it;
 *   - G40 leaves the tool where it is: the next move (a line) starts there.
 * Angles within SMALL (0.05 rad, LinuxCNC's TOLERANCE_CONCAVE_CORNER) count
 * as tangent. Positions are program mm; messages name the motion word.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ccomp.h"

int swarf_gc_comp_active(const swarf_gc_state *st) {
  return st->comp_side != 0 && st->comp_radius > 0;
}

/* ---- turning compensation on and off ------------------------------------ */

static int comp_radius(const swarf_gc_block *b, const swarf_gc_state *st, const swarf_gc_exec *ex,
                       double *radius, int *side, swarf_error *f) {
  const swarf_gc_code_word *cw = &b->g[SWARF_GC_GROUP_CUTTER_COMP];
  const swarf_gc_word *d = swarf_gc_block_word(b, 'D');
  int tool = st->tool;
  if (cw->code == 411 || cw->code == 421) {
    if (!d->present)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_D_MISSING, cw->column,
                           cw->code == 411 ? "41.1" : "42.1");
    *radius = d->value * swarf_gc_scale(st) / 2;
    if (*radius < 0) *radius = -*radius, *side = *side == LEFT ? RIGHT : LEFT;
    return SWARF_OK;
  }
  if (d->present) {
    if (d->value < 0 || d->value != floor(d->value) || d->value >= ex->ntools)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_D_NOT_WHOLE, d->column, cw->code / 10);
    tool = (int)d->value;
  }
  if (tool > 0 && (tool >= ex->ntools || isnan(ex->tools[tool][0])))
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_TOOL_NOT_FOUND, d->present ? d->column : cw->column,
                         tool);
  *radius = tool > 0 ? ex->tools[tool][1] / 2 : 0;
  return SWARF_OK;
}

static int comp_on(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, swarf_error *f) {
  const swarf_gc_code_word *cw = &b->g[SWARF_GC_GROUP_CUTTER_COMP];
  int side = cw->code == 410 || cw->code == 411 ? LEFT : RIGHT, status;
  double radius = 0;
  if (st->comp_side) return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ON_WHEN_ON, cw->column);
  if (st->modal.plane == 190) return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_PLANE, cw->column);
  status = comp_radius(b, st, ex, &radius, &side, f);
  if (status != SWARF_OK) return status;
  swarf_gc_out_text(ex->out, "COMMENT(\"interpreter: cutter radius compensation on %s\")",
                    side == LEFT ? "left" : "right");
  st->modal.cutter_comp = cw->code;
  st->comp_side = side;
  st->comp_radius = radius;
  st->comp_first = 1;
  st->comp_end_valid = 0; /* an entry arc records no end point: none is known */
  if (!st->comp_exit) memcpy(st->comp_pos, st->pos, sizeof st->comp_pos);
  return SWARF_OK;
}

/* G40: the held move goes out as it is; the tool stays at its end. */
static int comp_off(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                    swarf_error *f) {
  if (swarf_gc_comp_active(st) && !st->comp_first) {
    int status = swarf_gc_cc_move_ends(st, ex, st->comp_pos[swarf_gc_cc_plane_of(st).a1],
                                       st->comp_pos[swarf_gc_cc_plane_of(st).a2],
                                       b->g[SWARF_GC_GROUP_CUTTER_COMP].column, f);
    if (status != SWARF_OK) return status;
    st->comp_exit = 1;
    st->arc_not_allowed = 1;
  }
  st->modal.cutter_comp = 400;
  st->comp_side = 0;
  st->comp_first = 1;
  swarf_gc_out_text(ex->out, "COMMENT(\"interpreter: cutter radius compensation off\")");
  return SWARF_OK;
}

int swarf_gc_comp_set(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                      swarf_error *f) {
  int code = b->g[SWARF_GC_GROUP_CUTTER_COMP].code;
  if (code < 0) return SWARF_OK;
  return code == 400 ? comp_off(b, st, ex, f) : comp_on(b, st, ex, f);
}

/* ---- what compensation refuses ------------------------------------------ */

static int refuse_nonmodal(const swarf_gc_block *b, const swarf_gc_state *st, swarf_error *f) {
  const swarf_gc_code_word *g0 = &b->g[SWARF_GC_GROUP_NONMODAL];
  const swarf_gc_word *l = swarf_gc_block_word(b, 'L'), *p = swarf_gc_block_word(b, 'P');
  switch (g0->code) {
  case 530:
    if (swarf_gc_comp_active(st)) return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_G53, g0->column);
    return SWARF_OK;
  case 280:
  case 300:
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_G28_G30, g0->column);
  case 520:
  case 920:
  case 921:
  case 922:
  case 923:
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_AXIS_OFFSETS, g0->column);
  case 100:
    if (l->present && (l->value == 2 || l->value == 20) && p->present &&
        (p->value == 0 || (int)p->value == swarf_gc_system_index(st) + 1))
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_ACTIVE_SYSTEM, g0->column);
    return SWARF_OK;
  default:
    return SWARF_OK;
  }
}

int swarf_gc_comp_check(const swarf_gc_block *b, const swarf_gc_state *st, swarf_error *f) {
  const swarf_gc_code_word *g;
  if (!st->comp_side) return SWARF_OK;
  if ((g = &b->g[SWARF_GC_GROUP_PLANE])->code >= 0 && g->code != st->modal.plane)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_PLANE_CHANGE, g->column);
  if ((g = &b->g[SWARF_GC_GROUP_TOOL_LENGTH])->code >= 0)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_TOOL_OFFSET, g->column);
  if ((g = &b->g[SWARF_GC_GROUP_COORD_SYSTEM])->code >= 0)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_COORD_SYSTEM, g->column);
  if ((g = &b->g[SWARF_GC_GROUP_PATH_CONTROL])->code >= 0)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_CONTROL_MODE, g->column);
  if ((g = &b->m[SWARF_GC_MGROUP_TOOL])->code == 60)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_COMP_TOOL_CHANGE, g->column);
  return refuse_nonmodal(b, st, f);
}
