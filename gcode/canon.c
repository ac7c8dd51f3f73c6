/* SPDX-License-Identifier: MPL-2.0 */
/* canon.c -- the canonical calls one block makes, held until it commits.
 *
 * A block's calls go into an out list (owned by the parser, reused from one
 * block to the next, so memory stays flat): motions carry both the values
 * rs274 prints (program coordinates in the active unit, for --canon) and the
 * machine-frame swarf_move the simulator consumes; other calls are text,
 * formatted only when someone listens (want_text).
 *
 * Held calls (cutter compensation, see swarf_gc_out): a motion is built in
 * program mm and made final (printed values, machine frame) when it is let
 * go, with the unit and offsets in force then, as rs274 prints a queued
 * move. A call pushed while others are held waits behind them, except the
 * ones LinuxCNC does not queue (swarf_gc_out_text_now).
 *
 * Machine frame, as LinuxCNC's motion controller does it (emccanon.cc,
 * rotate_and_offset_pos): p += G92; rotate (x, y) by the system's XY
 * rotation; p += work offset; p += tool length offset. All in mm.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gcode_private.h"

#define DEG (3.14159265358979323846 / 180.0)
#define MAX_CALLS ((size_t)1 << 22) /* calls one block may make */

void swarf_gc_out_init(swarf_gc_out *o) {
  memset(o, 0, sizeof *o);
}

void swarf_gc_out_clear(swarf_gc_out *o) {
  free(o->calls);
  free(o->text);
  memset(o, 0, sizeof *o);
}

void swarf_gc_out_reset(swarf_gc_out *o) {
  o->count = 0;
  o->ready = 0;
  o->text_len = 0;
  o->overflow = 0;
  o->prefix = NULL;
  o->pending = 0;
}

void swarf_gc_out_start(swarf_gc_out *o, const swarf_gc_out *held, long line) {
  swarf_gc_out_reset(o);
  o->line = line;
  o->prefix = held;
  o->pending = held != NULL ? held->count : 0;
}

static swarf_gc_call *push(swarf_gc_out *o, swarf_gc_call_kind kind) {
  swarf_gc_call *c;
  if (o->count == o->cap) {
    size_t cap = o->cap ? 2 * o->cap : 16;
    swarf_gc_call *grown = cap > MAX_CALLS ? NULL : realloc(o->calls, cap * sizeof *grown);
    if (grown == NULL) {
      o->overflow = 1;
      return NULL;
    }
    o->calls = grown;
    o->cap = cap;
  }
  c = &o->calls[o->count++];
  c->kind = kind;
  c->nprog = 0;
  c->turns = 0;
  c->sweep = 0;
  c->dir[0] = c->dir[1] = 0;
  c->print = SWARF_GC_PRINT_MOTION;
  c->move.line = o->line;
  return c;
}

/* Room for n more bytes of text; returns the offset they go at, or -1. */
static long text_room(swarf_gc_out *o, size_t n) {
  if (o->text_len + n > o->text_cap) {
    size_t cap = o->text_cap ? o->text_cap : 1024;
    char *grown;
    while (cap < o->text_len + n)
      cap *= 2;
    grown = realloc(o->text, cap);
    if (grown == NULL) {
      o->overflow = 1;
      return -1;
    }
    o->text = grown;
    o->text_cap = cap;
  }
  return (long)o->text_len;
}

static swarf_gc_call *push_textv(swarf_gc_out *o, const char *fmt, va_list ap) {
  va_list again;
  int n;
  long at;
  swarf_gc_call *c;
  va_copy(again, ap);
  n = vsnprintf(NULL, 0, fmt, ap);
  if (n < 0 || (at = text_room(o, (size_t)n + 1)) < 0 ||
      (c = push(o, SWARF_GC_CALL_TEXT)) == NULL) {
    va_end(again);
    return NULL;
  }
  c->text_at = (size_t)at;
  vsnprintf(o->text + at, (size_t)n + 1, fmt, again);
  va_end(again);
  o->text_len += (size_t)n + 1;
  return c;
}

/* A call just pushed: final at once if nothing is held before it. */
static void settle(swarf_gc_out *o, const swarf_gc_state *st) {
  if (o->pending == 0 && o->ready + 1 == o->count) swarf_gc_out_flush(o, st);
}

void swarf_gc_out_text(swarf_gc_out *o, const char *fmt, ...) {
  va_list ap;
  if (!o->want_text || o->overflow) return;
  va_start(ap, fmt);
  if (push_textv(o, fmt, ap) != NULL && o->pending == 0 && o->ready + 1 == o->count)
    o->ready = o->count;
  va_end(ap);
}

void swarf_gc_out_text_now(swarf_gc_out *o, const char *fmt, ...) {
  va_list ap;
  swarf_gc_call *c;
  if (!o->want_text || o->overflow) return;
  va_start(ap, fmt);
  c = push_textv(o, fmt, ap);
  va_end(ap);
  if (c == NULL) return;
  if (o->ready + 1 < o->count) { /* goes before the held calls */
    swarf_gc_call now = *c;
    memmove(&o->calls[o->ready + 1], &o->calls[o->ready],
            (o->count - 1 - o->ready) * sizeof *o->calls);
    o->calls[o->ready] = now;
  }
  o->ready++;
}

void swarf_gc_out_append_held(swarf_gc_out *o, const swarf_gc_out *src, size_t from) {
  for (size_t i = from; i < src->count; i++) {
    const swarf_gc_call *s = &src->calls[i];
    swarf_gc_call *c;
    long at = 0;
    size_t n = s->kind == SWARF_GC_CALL_TEXT ? strlen(src->text + s->text_at) + 1 : 0;
    if (n > 0 && (at = text_room(o, n)) < 0) return;
    if ((c = push(o, s->kind)) == NULL) return;
    *c = *s;
    if (n > 0) {
      memcpy(o->text + at, src->text + s->text_at, n);
      c->text_at = (size_t)at;
      o->text_len += n;
    }
  }
}

static void reverse(swarf_gc_call *c, size_t from, size_t to) {
  for (; from + 1 < to; from++, to--) {
    swarf_gc_call t = c[from];
    c[from] = c[to - 1];
    c[to - 1] = t;
  }
}

void swarf_gc_out_take_held(swarf_gc_out *o) {
  size_t mid = o->count;
  if (o->pending == 0) return;
  o->pending = 0;
  swarf_gc_out_append_held(o, o->prefix, 0);
  /* [ready, mid) this block's, [mid, count) the earlier ones': swap them. */
  reverse(o->calls, o->ready, mid);
  reverse(o->calls, mid, o->count);
  reverse(o->calls, o->ready, o->count);
}

static void rotate_xy(double deg, double *x, double *y) {
  double c, s, u = *x, v = *y;
  if (deg == 0) return;
  c = cos(deg * DEG);
  s = sin(deg * DEG);
  *x = u * c - v * s;
  *y = u * s + v * c;
}

const double *swarf_gc_origin(const swarf_gc_state *st) {
  return st->ext_system > 0 ? st->ext_origin : st->systems[swarf_gc_system_index(st)];
}

double swarf_gc_rotation(const swarf_gc_state *st) {
  return st->ext_system > 0 ? 0.0 : st->rotations[swarf_gc_system_index(st)];
}

void swarf_gc_to_machine(const swarf_gc_state *st, const double p[SWARF_NAXES],
                         double m[SWARF_NAXES]) {
  const double *origin = swarf_gc_origin(st);
  for (int i = 0; i < SWARF_NAXES; i++)
    m[i] = p[i] + st->g92[i];
  rotate_xy(swarf_gc_rotation(st), &m[0], &m[1]);
  for (int i = 0; i < SWARF_NAXES; i++)
    m[i] += origin[i] + st->tlo[i];
}

void swarf_gc_from_machine(const swarf_gc_state *st, const double m[SWARF_NAXES],
                           double p[SWARF_NAXES]) {
  const double *origin = swarf_gc_origin(st);
  for (int i = 0; i < SWARF_NAXES; i++)
    p[i] = m[i] - origin[i] - st->tlo[i];
  rotate_xy(-swarf_gc_rotation(st), &p[0], &p[1]);
  for (int i = 0; i < SWARF_NAXES; i++)
    p[i] -= st->g92[i];
}

void swarf_gc_tool_pos(const swarf_gc_state *st, double p[SWARF_NAXES]) {
  memcpy(p, st->pos, SWARF_NAXES * sizeof *p);
  if (swarf_gc_comp_active(st) || st->comp_exit) memcpy(p, st->comp_pos, 3 * sizeof *p);
}

/* A move from the tool's position, in program mm until it is made final. */
static void base_move(swarf_move *mv, const swarf_gc_state *st, swarf_move_kind kind, int column) {
  long line = mv->line;
  memset(mv, 0, sizeof *mv);
  mv->kind = kind;
  mv->line = line;
  swarf_gc_tool_pos(st, mv->start);
  memcpy(mv->end, mv->start, sizeof mv->end);
  mv->feed = kind == SWARF_MOVE_RAPID ? 0 : st->feed;
  mv->spindle = st->spindle_dir * st->speed;
  mv->tool = st->tool;
  mv->column = column;
}

static void set_prog(swarf_gc_call *c, const swarf_gc_state *st, const double *v, int n) {
  double k = 1.0 / swarf_gc_scale(st);
  for (int i = 0; i < n; i++)
    c->prog[i] = v[i] * (i < 3 ? k : 1.0);
  c->nprog = n;
}

void swarf_gc_plane_axes(const swarf_gc_state *st, int ax[3]) {
  int p = st->modal.plane;
  ax[0] = p == 180 ? 2 : p == 190 ? 1 : 0;
  ax[1] = p == 180 ? 0 : p == 190 ? 2 : 1;
  ax[2] = p == 180 ? 1 : p == 190 ? 0 : 2;
}

static void arc_prog(swarf_gc_call *c, const swarf_gc_state *st) {
  const swarf_move *mv = &c->move;
  double k = 1.0 / swarf_gc_scale(st);
  int ax[3];
  swarf_gc_plane_axes(st, ax);
  c->prog[0] = mv->end[ax[0]] * k;
  c->prog[1] = mv->end[ax[1]] * k;
  c->prog[2] = mv->center[ax[0]] * k;
  c->prog[3] = mv->center[ax[1]] * k;
  c->prog[4] = c->turns;
  c->prog[5] = mv->end[ax[2]] * k;
  c->prog[6] = mv->end[3];
  c->prog[7] = mv->end[4];
  c->prog[8] = mv->end[5];
  c->nprog = 9;
}

/* Program mm -> what rs274 prints, and the machine-frame move. */
static void make_final(swarf_gc_call *c, const swarf_gc_state *st) {
  swarf_move *mv = &c->move;
  if (c->kind == SWARF_GC_CALL_TEXT) return;
  if (c->kind == SWARF_GC_CALL_TRAVERSE || c->kind == SWARF_GC_CALL_FEED)
    set_prog(c, st, mv->end, SWARF_NAXES);
  if (c->kind == SWARF_GC_CALL_ARC) {
    double cm[SWARF_NAXES] = {0};
    arc_prog(c, st);
    memcpy(cm, mv->center, 3 * sizeof(double));
    swarf_gc_to_machine(st, cm, cm);
    memcpy(mv->center, cm, 3 * sizeof(double));
    rotate_xy(swarf_gc_rotation(st), &mv->normal[0], &mv->normal[1]);
  }
  swarf_gc_to_machine(st, mv->start, mv->start);
  swarf_gc_to_machine(st, mv->end, mv->end);
}

void swarf_gc_out_flush(swarf_gc_out *o, const swarf_gc_state *st) {
  swarf_gc_out_take_held(o);
  for (size_t i = o->ready; i < o->count; i++)
    make_final(&o->calls[i], st);
  o->ready = o->count;
}

swarf_gc_call *swarf_gc_out_hold_line(swarf_gc_out *o, const swarf_gc_state *st,
                                      swarf_gc_call_kind kind, const double start[SWARF_NAXES],
                                      const double end[SWARF_NAXES], int column) {
  swarf_gc_call *c = push(o, kind);
  if (c == NULL) return NULL;
  base_move(&c->move, st, kind == SWARF_GC_CALL_TRAVERSE ? SWARF_MOVE_RAPID : SWARF_MOVE_LINE,
            column);
  memcpy(c->move.start, start, sizeof c->move.start);
  memcpy(c->move.end, end, sizeof c->move.end);
  return c;
}

void swarf_gc_out_straight(swarf_gc_out *o, const swarf_gc_state *st, swarf_gc_call_kind kind,
                           const double end[SWARF_NAXES], int column) {
  double start[SWARF_NAXES];
  swarf_gc_tool_pos(st, start);
  if (swarf_gc_out_hold_line(o, st, kind, start, end, column) != NULL) settle(o, st);
}

swarf_gc_call *swarf_gc_out_hold_arc(swarf_gc_out *o, const swarf_gc_state *st,
                                     const swarf_move *mv, int turns, int column) {
  swarf_gc_call *c = push(o, SWARF_GC_CALL_ARC);
  if (c == NULL) return NULL;
  base_move(&c->move, st, SWARF_MOVE_ARC, column);
  memcpy(c->move.start, mv->start, sizeof c->move.start);
  memcpy(c->move.end, mv->end, sizeof c->move.end);
  memcpy(c->move.center, mv->center, sizeof c->move.center);
  memcpy(c->move.normal, mv->normal, sizeof c->move.normal);
  c->move.angle = mv->angle;
  c->move.rise = mv->rise;
  c->turns = turns;
  return c;
}

void swarf_gc_out_arc(swarf_gc_out *o, const swarf_gc_state *st, const swarf_move *mv, int turns,
                      int column) {
  if (swarf_gc_out_hold_arc(o, st, mv, turns, column) != NULL) settle(o, st);
}

void swarf_gc_out_dwell(swarf_gc_out *o, const swarf_gc_state *st, double seconds, int column) {
  swarf_gc_call *c = push(o, SWARF_GC_CALL_DWELL);
  if (c == NULL) return;
  base_move(&c->move, st, SWARF_MOVE_DWELL, column);
  c->move.dwell = seconds;
  c->prog[0] = seconds;
  c->nprog = 1;
  settle(o, st);
}

void swarf_gc_out_tool(swarf_gc_out *o, const swarf_gc_state *st, int column) {
  swarf_gc_call *c = push(o, SWARF_GC_CALL_TOOL);
  if (c == NULL) return;
  base_move(&c->move, st, SWARF_MOVE_TOOL_CHANGE, column);
  c->prog[0] = st->tool;
  c->nprog = 1;
  settle(o, st);
}

/* Offsets as rs274 prints them: in the active unit. */
void swarf_gc_out_g5x(swarf_gc_out *o, const swarf_gc_state *st) {
  int k = swarf_gc_system_index(st);
  double s = 1.0 / swarf_gc_scale(st);
  const double *v = st->systems[k];
  swarf_gc_out_text(o, "SET_G5X_OFFSET(%d, %.4f, %.4f, %.4f, %.4f, %.4f, %.4f)", k + 1, v[0] * s,
                    v[1] * s, v[2] * s, v[3], v[4], v[5]);
  swarf_gc_out_text(o, "SET_XY_ROTATION(%.4f)", st->rotations[k]);
}

void swarf_gc_out_g92(swarf_gc_out *o, const swarf_gc_state *st) {
  double s = 1.0 / swarf_gc_scale(st);
  const double *v = st->g92;
  swarf_gc_out_text(o, "SET_G92_OFFSET(%.4f, %.4f, %.4f, %.4f, %.4f, %.4f)", v[0] * s, v[1] * s,
                    v[2] * s, v[3], v[4], v[5]);
}

void swarf_gc_out_tlo(swarf_gc_out *o, const swarf_gc_state *st) {
  double s = 1.0 / swarf_gc_scale(st);
  const double *v = st->tlo;
  swarf_gc_out_text(o,
                    "USE_TOOL_LENGTH_OFFSET(%.4f %.4f %.4f, %.4f %.4f %.4f, 0.0000 0.0000 0.0000)",
                    v[0] * s, v[1] * s, v[2] * s, v[3], v[4], v[5]);
}
