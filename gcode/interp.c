/* SPDX-License-Identifier: MPL-2.0 */
/* interp.c -- the modal state, and the execution of one checked block.
 *
 * swarf_gc_execute runs a block on a copy of the state that the caller
 * made, in LinuxCNC's order (execute_block):
 *   the checks of cutter compensation (ccomp.c);
 *   comment/message; feed mode, F, S, T; M6 M61, M3/M4/M5, M7/M8/M9 (and
 *   the M codes that make no motion); G4; plane, units, cutter comp (G40-G42.1), tool
 *   length, coordinate system, path control, distance modes, retract mode;
 *   group 0 (G10 G28 G30 G52 G92); motion (with G53); then M0/M1/M2/M30/M60.
 * The calls it makes go to the out list; the caller commits the copy and
 * hands the calls out only if the whole block succeeded.
 *
 * One LinuxCNC behaviour is kept on purpose: F is set before G20/G21 on the
 * same line take effect, so "G20 F10" read in mm mode means 10 mm/min.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gcode_private.h"

void swarf_gc_state_init(swarf_gc_state *st) {
  memset(st, 0, sizeof *st);
  st->modal.motion = 800;
  st->modal.plane = 170;
  st->modal.units = 210;
  st->modal.distance = 900;
  st->modal.arc_distance = 911;
  st->modal.feed_mode = 940;
  st->modal.cutter_comp = 400;
  st->modal.tool_length = 490;
  st->modal.coord_system = 540;
  st->modal.path_control = 640;
  st->modal.retract = 990; /* rs274 starts in G99 */
  st->modal.spindle_mode = 970;
}

double swarf_gc_scale(const swarf_gc_state *st) {
  return st->modal.units == 200 ? SWARF_GC_MM_PER_INCH : 1.0;
}

int swarf_gc_system_index(const swarf_gc_state *st) {
  int c = st->modal.coord_system;
  return c <= 590 ? (c - 540) / 10 : 6 + (c - 591);
}

static int code_of(const swarf_gc_block *b, int group) {
  return b->g[group].code;
}

/* The text of a (DEBUG,...) or (PRINT,...) comment with each parameter
 * replaced by its value (%f, as LinuxCNC). */
static void substitute(const char *t, size_t n, const swarf_gc_params *ps, char *out, size_t cap) {
  size_t o = 0;
  for (size_t i = 0; i < n && o + 32 < cap;) {
    if (t[i] == '#' && ps != NULL) {
      swarf_gc_lexer lx;
      swarf_error f;
      double v;
      swarf_gc_lexer_init(&lx, t, n, ps);
      lx.pos = i;
      if (swarf_gc_expr_value(&lx, &v, &f) == SWARF_OK) {
        o += (size_t)snprintf(out + o, cap - o, "%f", v);
        while (lx.pos > i + 1 && (t[lx.pos - 1] == ' ' || t[lx.pos - 1] == '\t'))
          lx.pos--; /* the blanks after the number are text */
        i = lx.pos;
        continue;
      }
    }
    out[o++] = t[i++];
  }
  out[o] = '\0';
}

/* (MSG,...), (DEBUG,...), (PRINT,...) become MESSAGE, others COMMENT. */
static void run_comment(const swarf_gc_block *b, swarf_gc_exec *ex) {
  static const char *kinds[] = {"msg,", "debug,", "print,"};
  const char *t = b->comment;
  size_t n = b->comment_len, k;
  if (t == NULL || !ex->out->want_text) return;
  for (size_t i = 0; i < 3; i++) {
    size_t len = strlen(kinds[i]);
    for (k = 0; k < len && k < n && tolower((unsigned char)t[k]) == kinds[i][k]; k++)
      ;
    if (k == len) {
      char msg[1024];
      substitute(t + len, n - len, i > 0 ? ex->params : NULL, msg, sizeof msg);
      swarf_gc_out_text_now(ex->out, "MESSAGE(\"%s\")", msg);
      return;
    }
  }
  while (n > 0 && (*t == ' ' || *t == '\t'))
    t++, n--;
  swarf_gc_out_text(ex->out, "COMMENT(\"%.*s\")", (int)n, t);
}

static void run_feed_mode(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex) {
  int mode = code_of(b, SWARF_GC_GROUP_FEED_MODE);
  if (mode < 0) return;
  if (mode == 930 && st->modal.feed_mode != 930) st->feed = 0;
  if (mode != 930 && st->modal.feed_mode == 930) st->feed = 0;
  st->modal.feed_mode = mode;
  if (mode != 950)
    swarf_gc_out_text(ex->out, "COMMENT(\"interpreter: feed mode set to %s\")",
                      mode == 930 ? "inverse time" : "units per minute");
  swarf_gc_out_text(ex->out, "SET_FEED_MODE(0, %d)", mode == 950);
  if (mode != 930 && !swarf_gc_block_has(b, 'F'))
    swarf_gc_out_text(ex->out, "SET_FEED_RATE(0.0000)");
}

/* F, S and T: the words that set values before any code runs. */
static void set_values(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex) {
  if (swarf_gc_block_has(b, 'F')) {
    double f = swarf_gc_block_word(b, 'F')->value;
    st->feed = st->modal.feed_mode == 930 ? f : f * swarf_gc_scale(st);
    if (st->modal.feed_mode != 930) swarf_gc_out_text(ex->out, "SET_FEED_RATE(%.4f)", f);
  }
  if (swarf_gc_block_has(b, 'S')) {
    st->speed = swarf_gc_block_word(b, 'S')->value;
    swarf_gc_out_text(ex->out, "SET_SPINDLE_SPEED(0, %.4f)", st->speed);
  }
  if (swarf_gc_block_has(b, 'T')) {
    st->selected_tool = (int)(swarf_gc_block_word(b, 'T')->value + 0.5);
    swarf_gc_out_text_now(ex->out, "SELECT_TOOL(%d)", st->selected_tool);
  }
}

static void run_m_codes(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex) {
  const swarf_gc_code_word *tool = &b->m[SWARF_GC_MGROUP_TOOL];
  int spindle = b->m[SWARF_GC_MGROUP_SPINDLE].code;
  int coolant = b->m[SWARF_GC_MGROUP_COOLANT].code;
  if (tool->code == 60 || tool->code == 610) {
    if (tool->code == 610 && swarf_gc_block_has(b, 'Q'))
      st->selected_tool = (int)(swarf_gc_block_word(b, 'Q')->value + 0.5);
    st->tool = st->selected_tool;
    if (tool->code == 60)
      swarf_gc_out_text(ex->out, "CHANGE_TOOL(%d)", st->tool);
    else
      swarf_gc_out_text(ex->out, "CHANGE_TOOL_NUMBER(%d)", st->tool);
    swarf_gc_out_tool(ex->out, st, tool->column);
  }
  if (spindle == 190) { /* M19: orient (R angle, P direction mode, Q wait) */
    st->spindle_dir = 0;
    swarf_gc_out_text(ex->out, "ORIENT_SPINDLE(0, %.4f, %d)", swarf_gc_block_word(b, 'R')->value,
                      (int)(swarf_gc_block_word(b, 'P')->value + 0.5));
    if (swarf_gc_block_has(b, 'Q'))
      swarf_gc_out_text(ex->out, "SPINDLE.0.WAIT_ORIENT_COMPLETE(%.4f)",
                        swarf_gc_block_word(b, 'Q')->value);
    return;
  }
  if (spindle == 30) st->spindle_dir = 1;
  if (spindle == 40) st->spindle_dir = -1;
  if (spindle == 50) st->spindle_dir = 0;
  if (spindle >= 0)
    swarf_gc_out_text(ex->out, "%s",
                      spindle == 30   ? "START_SPINDLE_CLOCKWISE(0)"
                      : spindle == 40 ? "START_SPINDLE_COUNTERCLOCKWISE(0)"
                                      : "STOP_SPINDLE_TURNING(0)");
  if (coolant == 70) swarf_gc_out_text(ex->out, "MIST_ON()");
  if (coolant == 80) swarf_gc_out_text(ex->out, "FLOOD_ON()");
  if (coolant == 90)
    swarf_gc_out_text(ex->out, "MIST_OFF()"), swarf_gc_out_text(ex->out, "FLOOD_OFF()");
}

/* Codes of other controllers that make no motion: a note each. */
static void run_vendor(const swarf_gc_block *b, const swarf_gc_state *st, swarf_gc_exec *ex) {
  const swarf_gc_code_word *g = &b->g[SWARF_GC_GROUP_VENDOR], *m = &b->m[SWARF_GC_MGROUP_VENDOR];
  if (g->code >= 0)
    swarf_gc_note(ex->notes, g->column, "%s: %s: accepted, no motion", g->text,
                  g->code == 50     ? "high-speed machining mode (Fanuc G05 P10000)"
                  : g->code == 51   ? "AI contour control (Fanuc G05.1 Q1)"
                  : g->code == 80   ? "look-ahead control (Fanuc G08)"
                  : g->code == 1030 ? "block look-ahead limit (Haas G103)"
                                    : "smoothness and accuracy (Haas G187)");
  if (m->code >= 0)
    swarf_gc_note(ex->notes, m->column, "%s: %s: accepted, no motion", m->text,
                  swarf_gc_vendor_m_name(st->dialect, m->code / 10));
}

static void run_dwell(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex) {
  const swarf_gc_code_word *g0 = &b->g[SWARF_GC_GROUP_NONMODAL];
  if (g0->code == 40)
    swarf_gc_out_dwell(ex->out, st, swarf_gc_block_word(b, 'P')->value, g0->column);
}

static void run_plane_units(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex) {
  int plane = code_of(b, SWARF_GC_GROUP_PLANE), units = code_of(b, SWARF_GC_GROUP_UNITS);
  if (plane >= 0) {
    st->modal.plane = plane;
    swarf_gc_out_text_now(ex->out, "SELECT_PLANE(CANON_PLANE_%s)",
                          plane == 170   ? "XY"
                          : plane == 180 ? "XZ"
                                         : "YZ");
  }
  if (units >= 0) {
    st->modal.units = units;
    if (st->units_line == 0) st->units_line = ex->out->line;
    swarf_gc_out_text_now(ex->out, "USE_LENGTH_UNITS(CANON_UNITS_%s)",
                          units == 200 ? "INCHES" : "MM");
  }
}

static void run_path_control(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex) {
  int c = code_of(b, SWARF_GC_GROUP_PATH_CONTROL);
  if (c < 0) return;
  st->modal.path_control = c;
  if (c == 610) swarf_gc_out_text(ex->out, "SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)");
  if (c == 611) swarf_gc_out_text(ex->out, "SET_MOTION_CONTROL_MODE(CANON_EXACT_STOP)");
  if (c == 640) {
    double p = swarf_gc_block_has(b, 'P') ? swarf_gc_block_word(b, 'P')->value : 0;
    double q = swarf_gc_block_has(b, 'Q') ? swarf_gc_block_word(b, 'Q')->value : p;
    swarf_gc_out_text(ex->out, "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, %f)", p);
    swarf_gc_out_text(ex->out, "SET_NAIVECAM_TOLERANCE(%.4f)", q);
  }
}

/* Distance, arc distance, retract and spindle modes only record the code. */
static void set_modes(const swarf_gc_block *b, swarf_gc_modal *m) {
  struct {
    int group;
    int *slot;
  } modes[] = {
      {SWARF_GC_GROUP_DISTANCE, &m->distance},
      {SWARF_GC_GROUP_ARC_DISTANCE, &m->arc_distance},
      {SWARF_GC_GROUP_RETURN_MODE, &m->retract},
      {SWARF_GC_GROUP_SPINDLE_MODE, &m->spindle_mode},
  };
  for (size_t i = 0; i < sizeof modes / sizeof modes[0]; i++)
    if (code_of(b, modes[i].group) >= 0) *modes[i].slot = code_of(b, modes[i].group);
}

static void run_stop(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex) {
  int stop = b->m[SWARF_GC_MGROUP_STOP].code;
  if (stop >= 0) { /* a held move goes out first */
    swarf_gc_out_flush(ex->out, st);
    st->comp_end_valid = 0;
  }
  if (stop == 0 || stop == 10 || stop == 600)
    swarf_gc_out_text(ex->out, "%s", stop == 10 ? "OPTIONAL_PROGRAM_STOP()" : "PROGRAM_STOP()");
  if (stop != 20 && stop != 300) return;
  /* LinuxCNC's program end: back to G54, no G92 rotation kept, G17 G90 G94 G40 G80 M5. */
  st->ended = 1;
  st->modal.coord_system = 540;
  swarf_gc_out_g5x(ex->out, st);
  st->modal.plane = 170;
  st->modal.distance = 900;
  st->modal.feed_mode = 940;
  st->modal.motion = 10;
  st->modal.cutter_comp = 400;
  st->comp_side = 0;
  st->comp_first = 1;
  st->spindle_dir = 0;
  swarf_gc_out_text(ex->out, "SET_FEED_MODE(0, 0)");
  swarf_gc_out_text(ex->out, "SET_FEED_RATE(0.0000)");
  swarf_gc_out_text(ex->out, "STOP_SPINDLE_TURNING(0)");
  swarf_gc_out_text(ex->out, "SET_SPINDLE_MODE(0 0.0000)");
  swarf_gc_out_text(ex->out, "PROGRAM_END()");
}

/* LinuxCNC selects a tool at its T word and stops there when the table has
 * no such tool (rs274: "Requested tool 5 not found in the tool table"); T0
 * (the empty spindle) is always there. Fanuc and Haas controls hold their
 * tool data and grbl has no tool table: any T is taken. */
static int check_tool_word(const swarf_gc_block *b, const swarf_gc_state *st,
                           const swarf_gc_exec *ex, swarf_error *f) {
  const swarf_gc_word *w = swarf_gc_block_word(b, 'T');
  int t;
  if (!w->present || st->dialect != SWARF_GCODE_DIALECT_LINUXCNC || ex->tools == NULL)
    return SWARF_OK;
  t = (int)(w->value + 0.5);
  if (t == 0 || (t < ex->ntools && !isnan(ex->tools[t][0]))) return SWARF_OK;
  return SWARF_GC_FAIL(f, SWARF_GCODE_E_TOOL_NOT_FOUND, w->column, t);
}

int swarf_gc_execute(const swarf_gc_block *b, swarf_gc_state *next, swarf_gc_exec *ex,
                     swarf_error *f) {
  int status, system = code_of(b, SWARF_GC_GROUP_COORD_SYSTEM);
  size_t moves;
  status = swarf_gc_comp_check(b, next, f);
  if (status == SWARF_OK) status = check_tool_word(b, next, ex, f);
  if (status != SWARF_OK) return status;
  run_comment(b, ex);
  run_feed_mode(b, next, ex);
  set_values(b, next, ex);
  run_m_codes(b, next, ex);
  run_vendor(b, next, ex);
  run_dwell(b, next, ex);
  run_plane_units(b, next, ex);
  status = swarf_gc_comp_set(b, next, ex, f);
  if (status == SWARF_OK) status = swarf_gc_tool_length(b, next, ex, f);
  if (status != SWARF_OK) return status;
  if (system == 541 || system == 1540)
    status = swarf_gc_select_ext(b, system, next, ex, f);
  else if (system >= 0)
    swarf_gc_select_system(system, next, ex);
  if (status != SWARF_OK) return status;
  run_path_control(b, next, ex);
  set_modes(b, &next->modal);
  moves = swarf_gc_out_size(ex->out);
  status = swarf_gc_offsets(b, next, ex, f);
  if (status == SWARF_OK) status = swarf_gc_motion(b, next, ex, f);
  if (status != SWARF_OK) return status;
  if (swarf_gc_out_size(ex->out) > moves && !swarf_gc_comp_active(next)) next->comp_exit = 0;
  run_stop(b, next, ex);
  if (ex->out->overflow) return SWARF_GC_FAIL(f, SWARF_GCODE_E_MOVES_MEMORY, 1);
  return SWARF_OK;
}
