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

#include "gcode_private.h"

#define PI 3.14159265358979323846
#define HALF_PI (PI / 2)
#define TWO_PI (2 * PI)
#define SMALL 0.05   /* TOLERANCE_CONCAVE_CORNER, radians */
#define EQUAL 0.0001 /* TOLERANCE_EQUAL */

#define LEFT SWARF_GC_COMP_LEFT
#define RIGHT SWARF_GC_COMP_RIGHT

int swarf_gc_comp_active(const swarf_gc_state *st) {
  return st->comp_side != 0 && st->comp_radius > 0;
}

static int fail(swarf_gc_fault *f, int column, const char *message) {
  return swarf_gc_fail(f, SWARF_GCODE_ERR_SEMANTIC, column, "%s", message);
}

/* The tool is inside an arc turning this way (LinuxCNC's TOOL_INSIDE_ARC). */
static int tool_inside(int side, int turns) {
  return (side == LEFT && turns > 0) || (side == RIGHT && turns < 0);
}

/* Signed sweep from (x1, y1) to (x2, y2) about (cx, cy), `turns` turns
 * (LinuxCNC's find_turn: a coincident end is a whole turn). */
static double find_turn(double x1, double y1, double cx, double cy, int turns, double x2,
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

typedef struct {
  int a1, a2, a3; /* first, second and normal axis */
  double s;       /* mm per program unit */
} plane;

static plane plane_of(const swarf_gc_state *st) {
  int ax[3];
  plane pl;
  swarf_gc_plane_axes(st, ax);
  pl.a1 = ax[0], pl.a2 = ax[1], pl.a3 = ax[2];
  pl.s = swarf_gc_scale(st);
  return pl;
}

static void set_current(swarf_gc_state *st, const plane *pl, double x, double y, double z) {
  st->comp_pos[pl->a1] = x;
  st->comp_pos[pl->a2] = y;
  st->comp_pos[pl->a3] = z;
}

/* Sweep (radians, > 0) of an arc move, full turns included. */
static void arc_angle(swarf_move *mv, const plane *pl, int turns) {
  int n = turns < 0 ? -turns : turns;
  mv->angle =
      swarf_gc_arc_sweep(mv->start[pl->a1], mv->start[pl->a2], mv->end[pl->a1], mv->end[pl->a2],
                         mv->center[pl->a1], mv->center[pl->a2], turns > 0) +
      TWO_PI * (n - 1);
  mv->rise = (turns > 0 ? 1 : -1) * (mv->end[pl->a3] - mv->start[pl->a3]);
}

/* ---- the held move ------------------------------------------------------- */

/* The first held motion, or NULL (LinuxCNC's qc().front()). */
static swarf_gc_call *front(swarf_gc_out *o) {
  for (size_t i = o->ready; i < o->count; i++)
    if (o->calls[i].kind <= SWARF_GC_CALL_ARC) return &o->calls[i];
  return NULL;
}

/* A held arc ends at (x, y): it must keep its radius and not grow past
 * what it was by more than LinuxCNC allows. */
static int move_arc_end(swarf_gc_call *c, const plane *pl, double x, double y, int column,
                        swarf_gc_fault *f) {
  swarf_move *mv = &c->move;
  double c1 = mv->center[pl->a1], c2 = mv->center[pl->a2];
  double r1 = hypot(mv->end[pl->a1] - c1, mv->end[pl->a2] - c2), r2 = hypot(x - c1, y - c2);
  double l2 = find_turn(mv->start[pl->a1], mv->start[pl->a2], c1, c2, c->turns, x, y);
  if (fabs(r1 - r2) / pl->s > .01)
    return swarf_gc_fail(f, SWARF_GCODE_ERR_SEMANTIC, column,
                         "BUG: cutter compensation has generated an invalid arc with mismatched "
                         "radii r1 %f r2 %f",
                         r1 / pl->s, r2 / pl->s);
  if (c->sweep != 0 && fabs(l2) > fabs(c->sweep) + (pl->s == 1 ? .0254 : .001))
    return fail(f, column,
                "Arc move in concave corner cannot be reached by the tool without gouging");
  mv->end[pl->a1] = x;
  mv->end[pl->a2] = y;
  arc_angle(mv, pl, c->turns);
  return SWARF_GCODE_OK;
}

/* A held line ends at (x, y): it must not turn back. */
static int move_line_end(swarf_gc_call *c, const plane *pl, double x, double y, int column,
                         swarf_gc_fault *f) {
  swarf_move *mv = &c->move;
  double dot = c->dir[0] * (x - mv->start[pl->a1]) + c->dir[1] * (y - mv->start[pl->a2]);
  if (dot < 0)
    return fail(f, column,
                c->kind == SWARF_GC_CALL_TRAVERSE
                    ? "Straight traverse in concave corner cannot be reached by the tool without "
                      "gouging"
                    : "Straight feed in concave corner cannot be reached by the tool without "
                      "gouging");
  mv->end[pl->a1] = x;
  mv->end[pl->a2] = y;
  return SWARF_GCODE_OK;
}

/* Every held move ends at (x, y), then all held calls go out
 * (LinuxCNC's move_endpoint_and_flush). */
static int move_ends(swarf_gc_state *st, swarf_gc_exec *ex, double x, double y, int column,
                     swarf_gc_fault *f) {
  swarf_gc_out *o = ex->out;
  plane pl = plane_of(st);
  const double *prev = NULL;
  for (size_t i = o->ready; i < o->count; i++) {
    swarf_gc_call *c = &o->calls[i];
    int status = SWARF_GCODE_OK;
    if (c->kind == SWARF_GC_CALL_TEXT) continue;
    if (prev != NULL) memcpy(c->move.start, prev, sizeof c->move.start);
    if (c->kind == SWARF_GC_CALL_ARC)
      status = move_arc_end(c, &pl, x, y, column, f);
    else if (c->kind <= SWARF_GC_CALL_FEED)
      status = move_line_end(c, &pl, x, y, column, f);
    else
      memcpy(c->move.end, c->move.start, sizeof c->move.end);
    if (status != SWARF_GCODE_OK) return status;
    prev = c->move.end;
  }
  swarf_gc_out_flush(o, st);
  return SWARF_GCODE_OK;
}

/* ---- adding moves -------------------------------------------------------- */

/* A held line from `at` to (x, y) in the plane, the rest of `end`. */
static void hold_line(swarf_gc_state *st, swarf_gc_exec *ex, const plane *pl,
                      swarf_gc_call_kind kind, const double at[SWARF_NAXES], double x, double y,
                      const double end[SWARF_NAXES], double d1, double d2, int column) {
  double e[SWARF_NAXES];
  swarf_gc_call *c;
  memcpy(e, end, sizeof e);
  e[pl->a1] = x;
  e[pl->a2] = y;
  c = swarf_gc_out_hold_line(ex->out, st, kind, at, e, column);
  if (c != NULL) c->dir[0] = d1, c->dir[1] = d2;
}

/* A held arc from `at` to (x, y, z) about (c1, c2), axes A B C to `end`'s. */
static void hold_arc(swarf_gc_state *st, swarf_gc_exec *ex, const plane *pl,
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

/* ---- turning compensation on and off ------------------------------------ */

static int comp_radius(const swarf_gc_block *b, const swarf_gc_state *st, const swarf_gc_exec *ex,
                       double *radius, int *side, swarf_gc_fault *f) {
  const swarf_gc_code_word *cw = &b->g[SWARF_GC_GROUP_CUTTER_COMP];
  const swarf_gc_word *d = swarf_gc_block_word(b, 'D');
  int tool = st->tool;
  char msg[80];
  if (cw->code == 411 || cw->code == 421) {
    if (!d->present) {
      snprintf(msg, sizeof msg, "G%s with no D word", cw->code == 411 ? "41.1" : "42.1");
      return fail(f, cw->column, msg);
    }
    *radius = d->value * swarf_gc_scale(st) / 2;
    if (*radius < 0) *radius = -*radius, *side = *side == LEFT ? RIGHT : LEFT;
    return SWARF_GCODE_OK;
  }
  if (d->present) {
    if (d->value < 0 || d->value != floor(d->value) || d->value >= ex->ntools) {
      snprintf(msg, sizeof msg, "G%d requires D word to be a whole number", cw->code / 10);
      return fail(f, d->column, msg);
    }
    tool = (int)d->value;
  }
  if (tool > 0 && (tool >= ex->ntools || isnan(ex->tools[tool][0]))) {
    snprintf(msg, sizeof msg, "Requested tool %d not found in the tool table", tool);
    return fail(f, d->present ? d->column : cw->column, msg);
  }
  *radius = tool > 0 ? ex->tools[tool][1] / 2 : 0;
  return SWARF_GCODE_OK;
}

static int comp_on(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                   swarf_gc_fault *f) {
  const swarf_gc_code_word *cw = &b->g[SWARF_GC_GROUP_CUTTER_COMP];
  int side = cw->code == 410 || cw->code == 411 ? LEFT : RIGHT, status;
  double radius = 0;
  if (st->comp_side) return fail(f, cw->column, "Cannot turn cutter radius comp on when on");
  if (st->modal.plane == 190)
    return fail(f, cw->column, "Cutter radius compensation allowed only in XY, XZ planes");
  status = comp_radius(b, st, ex, &radius, &side, f);
  if (status != SWARF_GCODE_OK) return status;
  swarf_gc_out_text(ex->out, "COMMENT(\"interpreter: cutter radius compensation on %s\")",
                    side == LEFT ? "left" : "right");
  st->modal.cutter_comp = cw->code;
  st->comp_side = side;
  st->comp_radius = radius;
  st->comp_first = 1;
  if (!st->comp_exit) memcpy(st->comp_pos, st->pos, sizeof st->comp_pos);
  return SWARF_GCODE_OK;
}

/* G40: the held move goes out as it is; the tool stays at its end. */
static int comp_off(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                    swarf_gc_fault *f) {
  if (swarf_gc_comp_active(st) && !st->comp_first) {
    int status = move_ends(st, ex, st->comp_pos[plane_of(st).a1], st->comp_pos[plane_of(st).a2],
                           b->g[SWARF_GC_GROUP_CUTTER_COMP].column, f);
    if (status != SWARF_GCODE_OK) return status;
    st->comp_exit = 1;
    st->arc_not_allowed = 1;
  }
  st->modal.cutter_comp = 400;
  st->comp_side = 0;
  st->comp_first = 1;
  swarf_gc_out_text(ex->out, "COMMENT(\"interpreter: cutter radius compensation off\")");
  return SWARF_GCODE_OK;
}

int swarf_gc_comp_set(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                      swarf_gc_fault *f) {
  int code = b->g[SWARF_GC_GROUP_CUTTER_COMP].code;
  if (code < 0) return SWARF_GCODE_OK;
  return code == 400 ? comp_off(b, st, ex, f) : comp_on(b, st, ex, f);
}

/* ---- what compensation refuses ------------------------------------------ */

static int refuse_nonmodal(const swarf_gc_block *b, const swarf_gc_state *st, swarf_gc_fault *f) {
  const swarf_gc_code_word *g0 = &b->g[SWARF_GC_GROUP_NONMODAL];
  const swarf_gc_word *l = swarf_gc_block_word(b, 'L'), *p = swarf_gc_block_word(b, 'P');
  switch (g0->code) {
  case 530:
    if (swarf_gc_comp_active(st))
      return fail(f, g0->column, "Cannot use g53 with cutter radius comp");
    return SWARF_GCODE_OK;
  case 280:
  case 300:
    return fail(f, g0->column, "Cannot use g28 or g30 with cutter radius comp");
  case 520:
  case 920:
  case 921:
  case 922:
  case 923:
    return fail(f, g0->column, "Cannot change axis offsets with cutter radius comp");
  case 100:
    if (l->present && (l->value == 2 || l->value == 20) && p->present &&
        (p->value == 0 || (int)p->value == swarf_gc_system_index(st) + 1))
      return fail(f, g0->column,
                  "Cannot change the active coordinate system with cutter radius compensation on");
    return SWARF_GCODE_OK;
  default:
    return SWARF_GCODE_OK;
  }
}

int swarf_gc_comp_check(const swarf_gc_block *b, const swarf_gc_state *st, swarf_gc_fault *f) {
  const swarf_gc_code_word *g;
  if (!st->comp_side) return SWARF_GCODE_OK;
  if ((g = &b->g[SWARF_GC_GROUP_PLANE])->code >= 0 && g->code != st->modal.plane)
    return fail(f, g->column, "Cannot change planes with cutter radius compensation on");
  if ((g = &b->g[SWARF_GC_GROUP_TOOL_LENGTH])->code >= 0)
    return fail(f, g->column, "Cannot change tool offset with cutter radius compensation on");
  if ((g = &b->g[SWARF_GC_GROUP_COORD_SYSTEM])->code >= 0)
    return fail(f, g->column,
                "Cannot change coordinate systems with cutter radius compensation on");
  if ((g = &b->g[SWARF_GC_GROUP_PATH_CONTROL])->code >= 0)
    return fail(f, g->column, "Cannot change control mode with cutter radius compensation on");
  if ((g = &b->m[SWARF_GC_MGROUP_TOOL])->code == 60)
    return fail(f, g->column, "Cannot change tools with cutter radius compensation on");
  return refuse_nonmodal(b, st, f);
}

/* ---- straight moves ------------------------------------------------------ */

/* The first move: to the end offset perpendicular to the move. */
static int straight_entry(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                          swarf_gc_call_kind kind, const double end[SWARF_NAXES],
                          swarf_gc_fault *f) {
  plane pl = plane_of(st);
  double r = st->comp_radius, at[SWARF_NAXES];
  double cx = st->comp_pos[pl.a1], cy = st->comp_pos[pl.a2], px = end[pl.a1], py = end[pl.a2];
  double alpha, x, y;
  if (hypot(px - cx, py - cy) <= r)
    return fail(f, b->motion_column,
                "Length of cutter compensation entry move is not greater than the tool radius");
  alpha = atan2(py - cy, px - cx) + (st->comp_side == LEFT ? HALF_PI : -HALF_PI);
  x = px + r * cos(alpha);
  y = py + r * sin(alpha);
  swarf_gc_tool_pos(st, at);
  hold_line(st, ex, &pl, kind, at, x, y, end, cos(alpha), sin(alpha), b->motion_column);
  st->comp_first = 0;
  set_current(st, &pl, x, y, end[pl.a3]);
  return SWARF_GCODE_OK;
}

/* Where a held arc (compensated) meets the next line's offset. */
static int arc_line_corner(const swarf_gc_call *prev, const plane *pl, int side, double r,
                           double base_dir, double opx, double opy, double *mx, double *my,
                           int column, swarf_gc_fault *f) {
  const swarf_move *mv = &prev->move;
  double pc1 = mv->center[pl->a1], pc2 = mv->center[pl->a2];
  double oldrad = hypot(pc1 - mv->end[pl->a1], pc2 - mv->end[pl->a2]);
  int inside = tool_inside(side, prev->turns), ccw = prev->turns > 0;
  double th = base_dir + (ccw ? HALF_PI : -HALF_PI), phi = atan2(pc2 - opy, pc1 - opx);
  double d = (inside ? oldrad + r : oldrad - r) * cos(th - phi);
  double l = (inside ? d - r : d + r) / oldrad, ang;
  if (l > 1.0 || l < -1.0)
    return fail(f, column,
                "Arc to straight motion makes a corner the compensated tool can't fit in without "
                "gouging");
  ang = ((inside == ccw) ? -acos(l) : acos(l)) + th + PI;
  *mx = pc1 + oldrad * cos(ang);
  *my = pc2 + oldrad * sin(ang);
  return SWARF_GCODE_OK;
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
static int line_concave(swarf_gc_state *st, swarf_gc_exec *ex, const plane *pl, const corner *k,
                        double px, double py, double at[SWARF_NAXES], int column,
                        swarf_gc_fault *f) {
  double cx = st->comp_pos[pl->a1], cy = st->comp_pos[pl->a2], r = st->comp_radius, mx = 0, my = 0;
  double opx = st->pos[pl->a1], opy = st->pos[pl->a2];
  swarf_gc_call *prev = front(ex->out);
  int status;
  if (prev == NULL || prev->kind != SWARF_GC_CALL_ARC) {
    double half = (k->beta + PI) / 2;
    if (half == 0)
      return fail(f, column, "Zero degree inside corner is invalid for cutter compensation");
    mx = cx + r / tan(half) * cos(k->theta + k->gamma);
    my = cy + r / tan(half) * sin(k->theta + k->gamma);
  } else {
    status = arc_line_corner(prev, pl, st->comp_side, r, atan2(py - opy, px - opx), opx, opy, &mx,
                             &my, column, f);
    if (status != SWARF_GCODE_OK) return status;
  }
  status = move_ends(st, ex, mx, my, column, f);
  if (status == SWARF_GCODE_OK && prev != NULL) at[pl->a1] = mx, at[pl->a2] = my;
  return status;
}

/* Convex corner: an arc about the programmed corner to (mx, my), or a
 * traverse for G0; A B C reach `end`'s on it. The tool is then there. */
static int corner_convex(swarf_gc_state *st, swarf_gc_exec *ex, const plane *pl,
                         swarf_gc_call_kind kind, double mx, double my,
                         const double end[SWARF_NAXES], double at[SWARF_NAXES], int column) {
  double e[SWARF_NAXES];
  memcpy(e, end, sizeof e);
  e[pl->a1] = mx, e[pl->a2] = my, e[pl->a3] = st->comp_pos[pl->a3];
  if (kind == SWARF_GC_CALL_TRAVERSE)
    hold_line(st, ex, pl, kind, at, mx, my, e, 0, 0, column);
  else
    hold_arc(st, ex, pl, at, mx, my, e[pl->a3], st->pos[pl->a1], st->pos[pl->a2],
             st->comp_side == LEFT ? -1 : 1, 0, e, column);
  swarf_gc_out_flush(ex->out, st);
  memcpy(at, e, sizeof e);
  return SWARF_GCODE_OK;
}

/* A later straight move: corner, then a held line to the offset end. */
static int straight_next(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                         swarf_gc_call_kind kind, const double end[SWARF_NAXES],
                         swarf_gc_fault *f) {
  plane pl = plane_of(st);
  double r = st->comp_radius, at[SWARF_NAXES], x, y;
  double cx = st->comp_pos[pl.a1], cy = st->comp_pos[pl.a2];
  double opx = st->pos[pl.a1], opy = st->pos[pl.a2], px = end[pl.a1], py = end[pl.a2];
  int col = b->motion_column, status = SWARF_GCODE_OK, concave;
  swarf_gc_call *prev = front(ex->out);
  corner k;
  swarf_gc_tool_pos(st, at);
  if (px == opx && py == opy) { /* no motion in the plane */
    hold_line(st, ex, &pl, kind, at, cx, cy, end, 0, 0, col);
    set_current(st, &pl, cx, cy, end[pl.a3]);
    return SWARF_GCODE_OK;
  }
  k = line_corner(st->comp_side, cx, cy, opx, opy, px, py);
  x = px + r * cos(k.alpha + k.gamma);
  y = py + r * sin(k.alpha + k.gamma);
  concave = k.beta < -SMALL || k.beta > PI + SMALL ||
            (k.beta > PI - SMALL && prev != NULL && prev->kind == SWARF_GC_CALL_ARC &&
             !tool_inside(st->comp_side, prev->turns));
  if (!concave && k.beta > SMALL) {
    status = move_ends(st, ex, cx, cy, col, f);
    if (status == SWARF_GCODE_OK)
      corner_convex(st, ex, &pl, kind, opx + r * cos(k.alpha + k.gamma),
                    opy + r * sin(k.alpha + k.gamma), end, at, col);
  } else if (concave)
    status = line_concave(st, ex, &pl, &k, px, py, at, col, f);
  else
    swarf_gc_out_flush(ex->out, st);
  if (status != SWARF_GCODE_OK) return status;
  hold_line(st, ex, &pl, kind, at, x, y, end, px - opx, py - opy, col);
  set_current(st, &pl, x, y, end[pl.a3]);
  return SWARF_GCODE_OK;
}

int swarf_gc_comp_straight(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                           const double end[SWARF_NAXES], swarf_gc_fault *f) {
  swarf_gc_call_kind kind = b->motion == 0 ? SWARF_GC_CALL_TRAVERSE : SWARF_GC_CALL_FEED;
  if (st->comp_first) return straight_entry(b, st, ex, kind, end, f);
  return straight_next(b, st, ex, kind, end, f);
}

/* ---- arcs ---------------------------------------------------------------- */

/* The first move is an arc: to the end offset along its radius, about a
 * new centre on that radius as far from the tool as from the new end. */
static int arc_entry(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                     const swarf_move *mv, int turns, swarf_gc_fault *f) {
  plane pl = plane_of(st);
  double r = st->comp_radius, at[SWARF_NAXES];
  double cx = st->comp_pos[pl.a1], cy = st->comp_pos[pl.a2];
  double c1 = mv->center[pl.a1], c2 = mv->center[pl.a2];
  double x = mv->end[pl.a1], y = mv->end[pl.a2], gamma, half, ab, a;
  int col = b->motion_column, inside = tool_inside(st->comp_side, turns);
  if (hypot(x - cx, y - cy) <= r)
    return fail(f, col,
                "Radius of cutter compensation entry arc is not greater than the tool radius");
  if (inside && hypot(x - c1, y - c2) <= r)
    return fail(f, col, "Tool radius not less than arc radius with comp");
  gamma = inside ? atan2(c2 - y, c1 - x) : atan2(y - c2, x - c1);
  x += r * cos(gamma);
  y += r * sin(gamma);
  half = hypot(cy - y, cx - x) / 2;
  ab = atan2(c2 - y, c1 - x);
  a = atan2(cy - y, cx - x) - ab;
  if (fabs(cos(a)) < EQUAL) return fail(f, col, "Tool radius not less than arc radius with comp");
  c1 = x + half / cos(a) * cos(ab);
  c2 = y + half / cos(a) * sin(ab);
  swarf_gc_tool_pos(st, at);
  hold_arc(st, ex, &pl, at, x, y, mv->end[pl.a3], c1, c2, turns,
           find_turn(cx, cy, c1, c2, turns, x, y), mv->end, col);
  st->comp_first = 0;
  set_current(st, &pl, x, y, mv->end[pl.a3]);
  return SWARF_GCODE_OK;
}

/* Where the held line's offset meets the new arc's offset circle. */
static int line_arc_corner(double beta, double theta, double c1, double c2, double arc_r, double r,
                           int inside, int turns, double *mx, double *my, int column,
                           swarf_gc_fault *f) {
  double cy = arc_r * sin(beta - HALF_PI);
  double dist = inside ? arc_r - r : arc_r + r;
  double l = (inside ? cy + r : cy - r) / dist, ang;
  if (l > 1.0 || l < -1.0)
    return fail(f, column,
                "Arc move in concave corner cannot be reached by the tool without gouging");
  if (inside)
    ang = turns > 0 ? theta + asin(l) : theta - asin(l);
  else
    ang = turns > 0 ? theta + PI - asin(l) : theta + PI + asin(l);
  *mx = c1 + dist * cos(ang);
  *my = c2 + dist * sin(ang);
  return SWARF_GCODE_OK;
}

/* Where the held arc (compensated) meets the new arc's offset circle. */
static int arc_arc_corner(const swarf_gc_call *prev, const plane *pl, int side, double c1,
                          double c2, double newrad, int turns, double *mx, double *my, int column,
                          swarf_gc_fault *f) {
  const swarf_move *mv = &prev->move;
  double pc1 = mv->center[pl->a1], pc2 = mv->center[pl->a2];
  double oldrad = hypot(pc1 - mv->end[pl->a1], pc2 - mv->end[pl->a2]);
  double cc = hypot(pc2 - c2, pc1 - c1), a, pull, dir, ccdir;
  if (oldrad == 0 || cc == 0)
    return fail(f, column, "Arc to arc motion is invalid because the arcs have the same center");
  a = (oldrad * oldrad + cc * cc - newrad * newrad) / (2 * oldrad * cc);
  if (a > 1.0 || a < -1.0)
    return fail(f, column,
                "Arc to arc motion makes a corner the compensated tool can't fit in without "
                "gouging");
  pull = acos(a);
  ccdir = atan2(c2 - pc2, c1 - pc1);
  dir = (tool_inside(side, prev->turns) == (turns > 0)) ? ccdir + pull : ccdir - pull;
  *mx = pc1 + oldrad * cos(dir);
  *my = pc2 + oldrad * sin(dir);
  return SWARF_GCODE_OK;
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

static int arc_concave(swarf_gc_state *st, swarf_gc_exec *ex, const plane *pl, const arc_corner *k,
                       double c1, double c2, double arc_r, int turns, double at[SWARF_NAXES],
                       int column, swarf_gc_fault *f) {
  swarf_gc_call *prev = front(ex->out);
  double r = st->comp_radius, mx = 0, my = 0;
  int status;
  if (prev == NULL || prev->kind != SWARF_GC_CALL_ARC)
    status =
        line_arc_corner(k->beta, k->theta, c1, c2, arc_r, r, k->inside, turns, &mx, &my, column, f);
  else
    status = arc_arc_corner(prev, pl, st->comp_side, c1, c2, k->inside ? arc_r - r : arc_r + r,
                            turns, &mx, &my, column, f);
  if (status == SWARF_GCODE_OK) status = move_ends(st, ex, mx, my, column, f);
  if (status == SWARF_GCODE_OK && prev != NULL) at[pl->a1] = mx, at[pl->a2] = my;
  return status;
}

static int arc_next(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                    const swarf_move *mv, int turns, swarf_gc_fault *f) {
  plane pl = plane_of(st);
  double r = st->comp_radius, at[SWARF_NAXES];
  double opx = st->pos[pl.a1], opy = st->pos[pl.a2];
  double c1 = mv->center[pl.a1], c2 = mv->center[pl.a2];
  double ex1 = mv->end[pl.a1], ex2 = mv->end[pl.a2], arc_r = hypot(c1 - ex1, c2 - ex2), gamma;
  int col = b->motion_column, status = SWARF_GCODE_OK;
  arc_corner k = arc_corner_of(st->comp_side, b->motion == 30, st->comp_pos[pl.a1],
                               st->comp_pos[pl.a2], opx, opy, c1, c2);
  if (k.inside && arc_r <= r) return fail(f, col, "Tool radius not less than arc radius with comp");
  gamma = k.inside ? atan2(c2 - ex2, c1 - ex1) : atan2(ex2 - c2, ex1 - c1);
  swarf_gc_tool_pos(st, at);
  if (k.beta < -SMALL || k.beta > PI + SMALL || (fabs(k.beta - PI) < SMALL && !k.inside))
    status = arc_concave(st, ex, &pl, &k, c1, c2, arc_r, turns, at, col, f);
  else if (k.beta > SMALL) {
    swarf_gc_out_flush(ex->out, st);
    corner_convex(st, ex, &pl, SWARF_GC_CALL_FEED, opx + r * cos(k.delta), opy + r * sin(k.delta),
                  mv->end, at, col);
  } else
    swarf_gc_out_flush(ex->out, st);
  if (status != SWARF_GCODE_OK) return status;
  ex1 += r * cos(gamma);
  ex2 += r * sin(gamma);
  hold_arc(st, ex, &pl, at, ex1, ex2, mv->end[pl.a3], c1, c2, turns,
           find_turn(opx, opy, c1, c2, turns, mv->end[pl.a1], mv->end[pl.a2]), mv->end, col);
  set_current(st, &pl, ex1, ex2, mv->end[pl.a3]);
  return SWARF_GCODE_OK;
}

int swarf_gc_comp_arc(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                      const swarf_move *mv, int turns, swarf_gc_fault *f) {
  if (st->comp_first) return arc_entry(b, st, ex, mv, turns, f);
  return arc_next(b, st, ex, mv, turns, f);
}
