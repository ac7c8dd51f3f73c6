/* interp.c -- the modal state, and the execution of one checked block.
 *
 * swarf_gc_execute runs a block on a copy of the state that the caller
 * made, in LinuxCNC's order (execute_block, convert_m, convert_g):
 *   feed mode, F, S, T; M6, M3/M4/M5, M7/M8/M9; G4; plane, units, cutter
 *   comp, tool length, coordinate system, path control, distance modes;
 *   motion (G0 G1 G2 G3 G80, with G53); then M0/M1/M2/M30/M60.
 * The moves it makes go to a small fixed list; the caller commits the copy
 * and hands the moves out only if the whole block succeeded.
 *
 * One LinuxCNC behaviour is kept on purpose: F is set before G20/G21 on the
 * same line take effect, so "G20 F10" read in mm mode means 10 mm/min.
 */
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
  st->modal.path_control = 610;
}

/* mm per program length unit. */
static double unit_scale(const swarf_gc_state *st) {
  return st->modal.units == 200 ? SWARF_GC_MM_PER_INCH : 1.0;
}

static int code_of(const swarf_gc_block *b, int group) {
  return b->g[group].code;
}

/* A move at the current position with the current feed, spindle and tool. */
static swarf_move *new_move(swarf_gc_moves *out, const swarf_gc_state *st, swarf_move_kind kind,
                            int column) {
  swarf_move *mv = &out->moves[out->count++];
  memset(mv, 0, sizeof *mv);
  mv->kind = kind;
  memcpy(mv->start, st->pos, sizeof mv->start);
  memcpy(mv->end, st->pos, sizeof mv->end);
  mv->feed = st->feed;
  mv->spindle = st->spindle_dir * st->speed;
  mv->tool = st->tool;
  mv->column = column;
  return mv;
}

/* F, S and T: the words that set values before any code runs. */
static void set_values(const swarf_gc_block *b, swarf_gc_state *st) {
  if (swarf_gc_block_has(b, 'F')) st->feed = swarf_gc_block_word(b, 'F')->value * unit_scale(st);
  if (swarf_gc_block_has(b, 'S')) st->speed = swarf_gc_block_word(b, 'S')->value;
  if (swarf_gc_block_has(b, 'T'))
    st->selected_tool = (int)(swarf_gc_block_word(b, 'T')->value + 0.5);
}

static void run_m_codes(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_moves *out) {
  const swarf_gc_code_word *tool = &b->m[SWARF_GC_MGROUP_TOOL];
  int spindle = b->m[SWARF_GC_MGROUP_SPINDLE].code;
  if (tool->code == 60) {
    st->tool = st->selected_tool;
    new_move(out, st, SWARF_MOVE_TOOL_CHANGE, tool->column);
  }
  if (spindle == 30) st->spindle_dir = 1;
  if (spindle == 40) st->spindle_dir = -1;
  if (spindle == 50) st->spindle_dir = 0;
}

static void run_dwell(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_moves *out) {
  const swarf_gc_code_word *g0 = &b->g[SWARF_GC_GROUP_NONMODAL];
  if (g0->code == 40) {
    swarf_move *mv = new_move(out, st, SWARF_MOVE_DWELL, g0->column);
    mv->dwell = swarf_gc_block_word(b, 'P')->value;
  }
}

/* Plane, units, comp, tool length, coordinate system, path control and the
 * distance modes: each only records its code (no offsets in this version). */
static void set_modes(const swarf_gc_block *b, swarf_gc_modal *m) {
  struct {
    int group;
    int *slot;
  } modes[] = {
      {SWARF_GC_GROUP_PLANE, &m->plane},
      {SWARF_GC_GROUP_UNITS, &m->units},
      {SWARF_GC_GROUP_CUTTER_COMP, &m->cutter_comp},
      {SWARF_GC_GROUP_TOOL_LENGTH, &m->tool_length},
      {SWARF_GC_GROUP_COORD_SYSTEM, &m->coord_system},
      {SWARF_GC_GROUP_PATH_CONTROL, &m->path_control},
      {SWARF_GC_GROUP_DISTANCE, &m->distance},
      {SWARF_GC_GROUP_ARC_DISTANCE, &m->arc_distance},
      {SWARF_GC_GROUP_FEED_MODE, &m->feed_mode},
  };
  for (size_t i = 0; i < sizeof modes / sizeof modes[0]; i++)
    if (code_of(b, modes[i].group) >= 0) *modes[i].slot = code_of(b, modes[i].group);
}

/* The end point of the block's motion: axis words in program units, made
 * absolute (G91 adds to the current point, except under G53). */
static void find_end(const swarf_gc_block *b, const swarf_gc_state *st, double end[SWARF_NAXES]) {
  static const char axes[SWARF_NAXES] = {'X', 'Y', 'Z', 'A', 'B', 'C'};
  int incremental = st->modal.distance == 910 && code_of(b, SWARF_GC_GROUP_NONMODAL) != 530;
  for (int i = 0; i < SWARF_NAXES; i++) {
    const swarf_gc_word *w = swarf_gc_block_word(b, axes[i]);
    double v = w->value * (i < 3 ? unit_scale(st) : 1.0);
    end[i] = !w->present ? st->pos[i] : incremental ? st->pos[i] + v : v;
  }
}

static int run_motion(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_moves *out,
                      swarf_gc_fault *f) {
  swarf_move *mv;
  if (b->motion < 0) return SWARF_GCODE_OK;
  st->modal.motion = b->motion;
  if (b->motion == 800) return SWARF_GCODE_OK;
  if (b->motion == 10 && st->feed <= 0)
    return swarf_gc_fail(f, SWARF_GCODE_ERR_SEMANTIC, b->motion_column,
                         "Cannot do G1 with zero feed rate");
  mv = new_move(out, st,
                b->motion == 0    ? SWARF_MOVE_RAPID
                : b->motion == 10 ? SWARF_MOVE_LINE
                                  : SWARF_MOVE_ARC,
                b->motion_column);
  find_end(b, st, mv->end);
  if (b->motion == 0) mv->feed = 0;
  if (mv->kind == SWARF_MOVE_ARC) {
    int status = swarf_gc_arc(b, st, mv, f);
    if (status != SWARF_GCODE_OK) return status;
  }
  memcpy(st->pos, mv->end, sizeof st->pos);
  return SWARF_GCODE_OK;
}

int swarf_gc_execute(const swarf_gc_block *b, swarf_gc_state *next, swarf_gc_moves *out,
                     swarf_gc_fault *f) {
  int stop = b->m[SWARF_GC_MGROUP_STOP].code;
  int status;
  set_values(b, next);
  run_m_codes(b, next, out);
  run_dwell(b, next, out);
  set_modes(b, &next->modal);
  status = run_motion(b, next, out, f);
  if (status != SWARF_GCODE_OK) return status;
  if (stop == 20 || stop == 300) next->ended = 1;
  return SWARF_GCODE_OK;
}
