/* SPDX-License-Identifier: MPL-2.0 */
/* cycle.c -- canned cycles G73, G81-G89 expanded into moves, LinuxCNC's way.
 *
 * In the active plane (G17: position X Y, drill along Z; G18: Z X along Y;
 * G19: Y Z along X), as rs274ngc's convert_cycle does: first up to the R
 * plane if below it; then for each of L repeats, a rapid to the hole at the
 * current height, the cycle's own moves, and the retract to the clearance
 * height (G98: the higher of the old height and R; G99: R). Under G91, R is
 * relative to the old height, the bottom relative to R, and the position
 * advances by X Y on every repeat. R, bottom, P and Q stay from the previous
 * block of the same cycle. The whole cycle is framed by exact-path mode.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gcode_private.h"

#define PECK_RETRACT_INCH 0.010 /* LinuxCNC's G83_RAPID_DELTA / G73 chip break */

typedef struct {
  int a1, a2, a3;    /* plane position axes and the drill axis */
  char drill_letter; /* the word holding the bottom */
  double r, bottom, clear, q, p;
  double middle; /* G87: the top of the back bore */
} cycle_geom;

typedef struct {
  const swarf_gc_block *b;
  swarf_gc_state *st;
  swarf_gc_exec *ex;
  cycle_geom g;
} cycle_run;

static void plane_of(const swarf_gc_state *st, cycle_geom *g) {
  int p = st->modal.plane;
  g->a1 = p == 180 ? 2 : p == 190 ? 1 : 0;
  g->a2 = p == 180 ? 0 : p == 190 ? 2 : 1;
  g->a3 = p == 180 ? 1 : p == 190 ? 0 : 2;
  g->drill_letter = p == 180 ? 'Y' : p == 190 ? 'X' : 'Z';
}

static void move_to(cycle_run *c, swarf_gc_call_kind kind, double depth) {
  double end[SWARF_NAXES];
  memcpy(end, c->st->pos, sizeof end);
  end[c->g.a3] = depth;
  swarf_gc_out_straight(c->ex->out, c->st, kind, end, c->b->motion_column);
  c->st->pos[c->g.a3] = depth;
}

static void traverse(cycle_run *c, double depth) {
  move_to(c, SWARF_GC_CALL_TRAVERSE, depth);
}

static void feed(cycle_run *c, double depth) {
  move_to(c, SWARF_GC_CALL_FEED, depth);
}

static void dwell(cycle_run *c, double p) {
  swarf_gc_out_dwell(c->ex->out, c->st, p, c->b->motion_column);
}

/* Pecks one G73 or G83 line may make, repeats included: a Q far below the
 * depth (Q0.000001) would otherwise make millions of moves on one line. */
#define MAX_PECKS 100000

static void text(cycle_run *c, const char *call) {
  swarf_gc_out_text(c->ex->out, "%s", call);
}

static const char *spindle_on(const swarf_gc_state *st) {
  return st->spindle_dir < 0 ? "START_SPINDLE_COUNTERCLOCKWISE(0)" : "START_SPINDLE_CLOCKWISE(0)";
}

/* Pecks of G73 (chip break: back up a little) and G83 (back out to R). */
static void pecks(cycle_run *c, int full_retract) {
  double delta = PECK_RETRACT_INCH * SWARF_GC_MM_PER_INCH;
  double depth;
  for (depth = c->g.r - c->g.q; depth > c->g.bottom; depth -= c->g.q) {
    feed(c, depth);
    if (full_retract) traverse(c, c->g.r);
    traverse(c, depth + delta);
  }
  feed(c, c->g.bottom);
  traverse(c, c->g.clear);
}

/* LinuxCNC 2.9 prints the feeds of G84 in the XZ plane with the axes out of
 * order, (Y, Z, X) in the X Y Z places; the canon text keeps that, so that
 * it matches rs274 call for call; the machine move goes where it should. */
static void tap_feed(cycle_run *c, double depth) {
  feed(c, depth);
  if (c->st->modal.plane == 180 && c->ex->out->count > 0) {
    swarf_gc_call *call = &c->ex->out->calls[c->ex->out->count - 1];
    double x = call->prog[0];
    call->prog[0] = call->prog[1];
    call->prog[1] = call->prog[2];
    call->prog[2] = x;
  }
}

static void tap(cycle_run *c) {
  int dir = c->st->spindle_dir;
  text(c, "DISABLE_FEED_OVERRIDE()");
  text(c, "DISABLE_SPEED_OVERRIDE(0)");
  tap_feed(c, c->g.bottom);
  text(c, "STOP_SPINDLE_TURNING(0)");
  c->st->spindle_dir = -dir;
  text(c, spindle_on(c->st));
  dwell(c, c->g.p);
  tap_feed(c, c->g.clear);
  text(c, "STOP_SPINDLE_TURNING(0)");
  c->st->spindle_dir = dir;
  text(c, spindle_on(c->st));
  text(c, "ENABLE_FEED_OVERRIDE()");
  text(c, "ENABLE_SPEED_OVERRIDE(0)");
}

/* A rapid in the plane, at the current height. */
static void traverse_at(cycle_run *c, double u, double v) {
  double end[SWARF_NAXES];
  memcpy(end, c->st->pos, sizeof end);
  end[c->g.a1] = u, end[c->g.a2] = v;
  swarf_gc_out_straight(c->ex->out, c->st, SWARF_GC_CALL_TRAVERSE, end, c->b->motion_column);
  memcpy(c->st->pos, end, sizeof end);
}

/* G87 back boring, as rs274ngc's convert_cycle_g87: at R, shift by I J
 * with the spindle stopped and oriented, go down to the bottom through the
 * hole, shift back, start the spindle, feed up to the middle (K) and back
 * down to the bottom, stop and orient, shift, rapid out to the clearance and
 * back over the hole, start the spindle again. */
static void back_bore(cycle_run *c) {
  double x = c->st->pos[c->g.a1], y = c->st->pos[c->g.a2];
  double ox = x + c->st->cycle_i, oy = y + c->st->cycle_j;
  char orient[64];
  snprintf(orient, sizeof orient, "ORIENT_SPINDLE(0, 0.0000, %d)", c->st->spindle_dir > 0 ? 2 : 3);
  traverse_at(c, ox, oy);
  text(c, "STOP_SPINDLE_TURNING(0)");
  text(c, orient);
  traverse(c, c->g.bottom);
  traverse_at(c, x, y);
  text(c, spindle_on(c->st));
  feed(c, c->g.middle);
  feed(c, c->g.bottom);
  text(c, "STOP_SPINDLE_TURNING(0)");
  text(c, orient);
  traverse_at(c, ox, oy);
  traverse(c, c->g.clear);
  traverse_at(c, x, y);
  text(c, spindle_on(c->st));
}

/* Fanuc/Haas G76 fine boring (Fanuc 0i-MF: "the spindle stops at a fixed
 * rotation position at the bottom of the hole and the tool is moved in the
 * direction opposite to the tool tip and retracted"; the shift is Q, to +X
 * in G17 with the parameters as shipped (Haas: Setting 27, X+)): feed to
 * the bottom, dwell P, orient, shift by Q, rapid out to the clearance,
 * shift back, start the spindle. */
static void fine_bore(cycle_run *c) {
  double x = c->st->pos[c->g.a1], y = c->st->pos[c->g.a2];
  feed(c, c->g.bottom);
  if (c->g.p > 0) dwell(c, c->g.p);
  text(c, "STOP_SPINDLE_TURNING(0)");
  text(c, "ORIENT_SPINDLE(0, 0.0000, 0)");
  traverse_at(c, x + c->g.q, y);
  traverse(c, c->g.clear);
  traverse_at(c, x, y);
  text(c, spindle_on(c->st));
}

/* One hole, from the R plane down and back. */
static void hole(cycle_run *c, int motion) {
  if (c->st->pos[c->g.a3] != c->g.r) traverse(c, c->g.r);
  switch (motion) {
  case 730:
    pecks(c, 0);
    return;
  case 830:
    pecks(c, 1);
    return;
  case 740: /* Fanuc/Haas counter tapping: G84's path (the spindle turns the other way) */
  case 840:
    tap(c);
    return;
  case 760:
    fine_bore(c);
    return;
  case 870:
    back_bore(c);
    return;
  default:
    break;
  }
  feed(c, c->g.bottom);
  if (motion == 820 || motion == 860 || motion == 880 || motion == 890) dwell(c, c->g.p);
  if (motion == 850 || motion == 890) {
    feed(c, motion == 850 ? c->g.r : c->g.clear);
    if (motion == 850) traverse(c, c->g.clear);
    return;
  }
  if (motion == 860 || motion == 880) {
    text(c, "STOP_SPINDLE_TURNING(0)");
    if (motion == 880) {
      text(c, "PROGRAM_STOP()");
      text(c, spindle_on(c->st));
      c->st->pos[c->g.a3] = c->g.clear; /* the operator takes the tool out */
      return;
    }
    traverse(c, c->g.clear);
    text(c, spindle_on(c->st));
    return;
  }
  traverse(c, c->g.clear);
}

/* G87's I J K (offsets in the plane, the middle height), kept from the last
 * G87 as R is; the spindle must turn (rs274's checks and messages). */
static int g87_words(cycle_run *c, int same, swarf_error *f) {
  const swarf_gc_block *b = c->b;
  swarf_gc_state *st = c->st;
  double s = swarf_gc_scale(st);
  double *slot[3] = {&st->cycle_i, &st->cycle_j, &st->cycle_k};
  int axis[3] = {c->g.a1, c->g.a2, c->g.a3}; /* I J K name X Y Z: in G18, K I then J */
  for (int i = 0; i < 3; i++) {
    const swarf_gc_word *w = swarf_gc_block_word(b, "IJK"[axis[i]]);
    if (w->present)
      *slot[i] = w->value * s;
    else if (!same)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_G87_WORD_MISSING, b->motion_column, "IJK"[axis[i]]);
  }
  if (st->spindle_dir == 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_G87_SPINDLE, b->motion_column);
  return SWARF_OK;
}

/* R, bottom, Q, P from the block or kept from the same cycle before. */
static int cycle_words(cycle_run *c, swarf_error *f) {
  const swarf_gc_block *b = c->b;
  swarf_gc_state *st = c->st;
  int same = st->modal.motion == b->motion;
  double s = swarf_gc_scale(st);
  const swarf_gc_word *zw = swarf_gc_block_word(b, c->g.drill_letter);
  if (swarf_gc_block_has(b, 'R'))
    st->cycle_r = swarf_gc_block_word(b, 'R')->value * s;
  else if (!same)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_CYCLE_R_MISSING, b->motion_column);
  if (zw->present)
    st->cycle_z = zw->value * s;
  else if (!same)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_CYCLE_DEPTH_MISSING, b->motion_column, c->g.drill_letter);
  if (swarf_gc_block_has(b, 'P'))
    st->cycle_p = swarf_gc_block_word(b, 'P')->value;
  else if (!same)
    st->cycle_p = 0;
  if (swarf_gc_block_has(b, 'Q'))
    st->cycle_q = fabs(swarf_gc_block_word(b, 'Q')->value) * s;
  else if ((b->motion == 730 || b->motion == 830) && !same)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_CYCLE_Q_MISSING, b->motion_column);
  if ((b->motion == 730 || b->motion == 830) && st->cycle_q <= 0)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_CYCLE_Q_NOT_POSITIVE, b->motion_column);
  if (b->motion == 870) return g87_words(c, same, f);
  return SWARF_OK;
}

static int cycle_heights(cycle_run *c, double old, swarf_error *f) {
  swarf_gc_state *st = c->st;
  if (st->modal.distance == 910) {
    c->g.r = old + st->cycle_r;
    c->g.bottom = c->g.r + st->cycle_z;
  } else {
    c->g.r = st->cycle_r;
    c->g.bottom = st->cycle_z;
  }
  if (c->g.r < c->g.bottom)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_CYCLE_R_BELOW_DEPTH, c->b->motion_column,
                         c->g.drill_letter);
  c->g.q = st->cycle_q;
  c->g.p = st->cycle_p;
  c->g.middle = st->modal.distance == 910 ? c->g.bottom + st->cycle_k : st->cycle_k;
  return SWARF_OK;
}

int swarf_gc_cycle(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, swarf_error *f) {
  cycle_run c = {b, st, ex, {0}};
  const swarf_gc_word *lw = swarf_gc_block_word(b, 'L');
  int repeats = lw->present ? (int)floor(lw->value + 0.5) : 1, status;
  double old, x, y, s = swarf_gc_scale(st);
  char l1, l2;
  plane_of(st, &c.g);
  l1 = "XYZ"[c.g.a1], l2 = "XYZ"[c.g.a2];
  if (st->feed <= 0 && b->motion != 840)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_CYCLE_ZERO_FEED, b->motion_column);
  status = cycle_words(&c, f);
  /* The initial level (LinuxCNC's cycle_il, Fanuc's): the drill axis where
   * the first block of the cycles found it; G98 goes back to it, and the
   * first rapid to a hole goes at it (G99: at the current height). */
  if (!st->cycle_il_set) st->cycle_il = st->pos[c.g.a3], st->cycle_il_set = 1;
  old = st->modal.retract == 980 ? st->cycle_il : st->pos[c.g.a3];
  if (status == SWARF_OK) status = cycle_heights(&c, old, f);
  if (status != SWARF_OK) return status;
  if (repeats > 100000)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_TOO_MANY_REPEATS, lw->column, lw->text);
  if (b->motion == 730 || b->motion == 830) { /* a bound on work, not on lines */
    const double n = ceil((c.g.r - c.g.bottom) / c.g.q) * (repeats > 1 ? repeats : 1);
    const swarf_gc_word *qw = swarf_gc_block_word(b, 'Q');
    if (n > MAX_PECKS)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_CYCLE_TOO_MANY_PECKS,
                           qw->present ? qw->column : b->motion_column,
                           b->motion == 730 ? "G73" : "G83", n, MAX_PECKS);
  }
  /* Below R: up to it first. rs274 also does it (a null rapid) in G99 after
   * a G87 block, whose end it records below R. */
  if (old < c.g.r || (st->cycle_after_g87 && st->modal.retract == 990)) {
    traverse(&c, c.g.r);
    old = c.g.r;
  }
  st->cycle_after_g87 = b->motion == 870;
  c.g.clear = st->modal.retract == 990 ? c.g.r : old;
  swarf_gc_out_text(ex->out, "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)");
  x = st->pos[c.g.a1], y = st->pos[c.g.a2];
  for (int i = 0; i < repeats; i++) {
    double end[SWARF_NAXES];
    const swarf_gc_word *w1 = swarf_gc_block_word(b, l1), *w2 = swarf_gc_block_word(b, l2);
    if (st->modal.distance == 910) {
      x += w1->present ? w1->value * s : 0;
      y += w2->present ? w2->value * s : 0;
    } else {
      x = w1->present ? w1->value * s : x;
      y = w2->present ? w2->value * s : y;
    }
    memcpy(end, st->pos, sizeof end);
    end[c.g.a1] = x, end[c.g.a2] = y;
    end[c.g.a3] = i == 0 ? old : c.g.clear;
    swarf_gc_out_straight(ex->out, st, SWARF_GC_CALL_TRAVERSE, end, b->motion_column);
    memcpy(st->pos, end, sizeof end);
    hole(&c, b->motion);
  }
  if (st->modal.path_control == 640)
    swarf_gc_out_text(ex->out, "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.000000)"),
        swarf_gc_out_text(ex->out, "SET_NAIVECAM_TOLERANCE(0.0000)");
  else
    swarf_gc_out_text(ex->out, "SET_MOTION_CONTROL_MODE(CANON_EXACT_%s)",
                      st->modal.path_control == 611 ? "STOP" : "PATH");
  return SWARF_OK;
}
