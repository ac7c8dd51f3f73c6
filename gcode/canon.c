/* canon.c -- the canonical calls one block makes, held until it commits.
 *
 * A block's calls go into an out list (owned by the parser, reused from one
 * block to the next, so memory stays flat): motions carry both the values
 * rs274 prints (program coordinates in the active unit, for --canon) and the
 * machine-frame swarf_move the simulator consumes; other calls are text,
 * formatted only when someone listens (want_text).
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
  o->text_len = 0;
  o->overflow = 0;
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
  return c;
}

void swarf_gc_out_text(swarf_gc_out *o, const char *fmt, ...) {
  va_list ap;
  int n;
  swarf_gc_call *c;
  if (!o->want_text || o->overflow) return;
  va_start(ap, fmt);
  n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (n < 0) return;
  if (o->text_len + (size_t)n + 1 > o->text_cap) {
    size_t cap = o->text_cap ? o->text_cap : 1024;
    char *grown;
    while (cap < o->text_len + (size_t)n + 1)
      cap *= 2;
    grown = realloc(o->text, cap);
    if (grown == NULL) {
      o->overflow = 1;
      return;
    }
    o->text = grown;
    o->text_cap = cap;
  }
  if ((c = push(o, SWARF_GC_CALL_TEXT)) == NULL) return;
  c->text_at = o->text_len;
  va_start(ap, fmt);
  vsnprintf(o->text + o->text_len, (size_t)n + 1, fmt, ap);
  va_end(ap);
  o->text_len += (size_t)n + 1;
}

static void rotate_xy(double deg, double *x, double *y) {
  double c, s, u = *x, v = *y;
  if (deg == 0) return;
  c = cos(deg * DEG);
  s = sin(deg * DEG);
  *x = u * c - v * s;
  *y = u * s + v * c;
}

void swarf_gc_to_machine(const swarf_gc_state *st, const double p[SWARF_NAXES],
                         double m[SWARF_NAXES]) {
  int k = swarf_gc_system_index(st);
  for (int i = 0; i < SWARF_NAXES; i++)
    m[i] = p[i] + st->g92[i];
  rotate_xy(st->rotations[k], &m[0], &m[1]);
  for (int i = 0; i < SWARF_NAXES; i++)
    m[i] += st->systems[k][i] + st->tlo[i];
}

void swarf_gc_from_machine(const swarf_gc_state *st, const double m[SWARF_NAXES],
                           double p[SWARF_NAXES]) {
  int k = swarf_gc_system_index(st);
  for (int i = 0; i < SWARF_NAXES; i++)
    p[i] = m[i] - st->systems[k][i] - st->tlo[i];
  rotate_xy(-st->rotations[k], &p[0], &p[1]);
  for (int i = 0; i < SWARF_NAXES; i++)
    p[i] -= st->g92[i];
}

static void base_move(swarf_move *mv, const swarf_gc_state *st, swarf_move_kind kind, int column) {
  memset(mv, 0, sizeof *mv);
  mv->kind = kind;
  swarf_gc_to_machine(st, st->pos, mv->start);
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

void swarf_gc_out_straight(swarf_gc_out *o, const swarf_gc_state *st, swarf_gc_call_kind kind,
                           const double end[SWARF_NAXES], int column) {
  swarf_gc_call *c = push(o, kind);
  if (c == NULL) return;
  base_move(&c->move, st, kind == SWARF_GC_CALL_TRAVERSE ? SWARF_MOVE_RAPID : SWARF_MOVE_LINE,
            column);
  swarf_gc_to_machine(st, end, c->move.end);
  set_prog(c, st, end, SWARF_NAXES);
}

/* Plane axes (first, second, third) of the state's plane, as rs274 prints. */
static void plane_axes(const swarf_gc_state *st, int ax[3]) {
  int p = st->modal.plane;
  ax[0] = p == 180 ? 2 : p == 190 ? 1 : 0;
  ax[1] = p == 180 ? 0 : p == 190 ? 2 : 1;
  ax[2] = p == 180 ? 1 : p == 190 ? 0 : 2;
}

void swarf_gc_out_arc(swarf_gc_out *o, const swarf_gc_state *st, const swarf_move *mv, int turns,
                      int column) {
  swarf_gc_call *c = push(o, SWARF_GC_CALL_ARC);
  double k = 1.0 / swarf_gc_scale(st), cm[SWARF_NAXES] = {0};
  int ax[3], r = swarf_gc_system_index(st);
  if (c == NULL) return;
  base_move(&c->move, st, SWARF_MOVE_ARC, column);
  swarf_gc_to_machine(st, mv->end, c->move.end);
  memcpy(cm, mv->center, 3 * sizeof(double));
  swarf_gc_to_machine(st, cm, cm);
  for (int i = 0; i < 3; i++)
    c->move.center[i] = cm[i] - st->tlo[i] + st->tlo[i];
  memcpy(c->move.normal, mv->normal, sizeof c->move.normal);
  rotate_xy(st->rotations[r], &c->move.normal[0], &c->move.normal[1]);
  c->move.angle = mv->angle;
  c->move.rise = mv->rise;
  plane_axes(st, ax);
  c->prog[0] = mv->end[ax[0]] * k;
  c->prog[1] = mv->end[ax[1]] * k;
  c->prog[2] = mv->center[ax[0]] * k;
  c->prog[3] = mv->center[ax[1]] * k;
  c->prog[4] = turns;
  c->prog[5] = mv->end[ax[2]] * k;
  c->prog[6] = mv->end[3];
  c->prog[7] = mv->end[4];
  c->prog[8] = mv->end[5];
  c->nprog = 9;
}

void swarf_gc_out_dwell(swarf_gc_out *o, const swarf_gc_state *st, double seconds, int column) {
  swarf_gc_call *c = push(o, SWARF_GC_CALL_DWELL);
  if (c == NULL) return;
  base_move(&c->move, st, SWARF_MOVE_DWELL, column);
  c->move.dwell = seconds;
  c->prog[0] = seconds;
  c->nprog = 1;
}

void swarf_gc_out_tool(swarf_gc_out *o, const swarf_gc_state *st, int column) {
  swarf_gc_call *c = push(o, SWARF_GC_CALL_TOOL);
  if (c == NULL) return;
  base_move(&c->move, st, SWARF_MOVE_TOOL_CHANGE, column);
  c->prog[0] = st->tool;
  c->nprog = 1;
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
