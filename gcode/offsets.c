/* offsets.c -- work systems, G92/G52, G10, G28/G30 and tool length offsets.
 *
 * The state keeps every offset in mm; a change of offset keeps the tool
 * where it is on the machine, so the program position is recomputed from
 * the machine position (swarf_gc_from_machine), as LinuxCNC does. Each
 * change prints the call rs274 prints (SET_G5X_OFFSET, SET_XY_ROTATION,
 * SET_G92_OFFSET, USE_TOOL_LENGTH_OFFSET). G28/G30 rapid through the
 * optional intermediate point to the stored home (machine coordinates).
 * Tool table values are mm (the parser converts the table on loading).
 */
#include <math.h>
#include <string.h>

#include "gcode_private.h"

static const char axes[SWARF_NAXES] = {'X', 'Y', 'Z', 'A', 'B', 'C'};

static void rotate_deg(double deg, double *x, double *y) {
  double c = cos(deg * 3.14159265358979323846 / 180), s = sin(deg * 3.14159265358979323846 / 180);
  double u = *x, v = *y;
  *x = u * c - v * s;
  *y = u * s + v * c;
}

static double word_mm(const swarf_gc_block *b, const swarf_gc_state *st, int axis) {
  return swarf_gc_block_word(b, axes[axis])->value * (axis < 3 ? swarf_gc_scale(st) : 1.0);
}

static int has(const swarf_gc_block *b, int axis) {
  return swarf_gc_block_word(b, axes[axis])->present;
}

/* Runs `change` on the state while the machine position stays put. */
static void keep_machine(swarf_gc_state *st, const double before[SWARF_NAXES]) {
  swarf_gc_from_machine(st, before, st->pos);
}

int swarf_gc_select_system(int code, swarf_gc_state *st, swarf_gc_exec *ex) {
  double m[SWARF_NAXES];
  swarf_gc_to_machine(st, st->pos, m);
  st->modal.coord_system = code;
  keep_machine(st, m);
  swarf_gc_out_g5x(ex->out, st);
  swarf_gc_out_g92(ex->out, st);
  return SWARF_OK;
}

/* A tool's length offset; -1 if the table has no such tool (tool 0: none). */
static int tool_z(const swarf_gc_exec *ex, int tool, double *z) {
  *z = 0;
  if (tool == 0) return 0;
  if (ex->tools == NULL || tool < 0 || tool >= ex->ntools || isnan(ex->tools[tool][0])) return -1;
  *z = ex->tools[tool][0];
  return 0;
}

int swarf_gc_tool_length(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                         swarf_gc_fault *f) {
  const swarf_gc_code_word *cw = &b->g[SWARF_GC_GROUP_TOOL_LENGTH];
  double m[SWARF_NAXES], z = 0;
  if (cw->code < 0) return SWARF_OK;
  if (cw->code == 430) {
    int h = swarf_gc_block_has(b, 'H') ? (int)(swarf_gc_block_word(b, 'H')->value + 0.5) : st->tool;
    if (tool_z(ex, h, &z) != 0)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_TOOL_NOT_FOUND, cw->column, h);
  }
  swarf_gc_to_machine(st, st->pos, m);
  memset(st->tlo, 0, sizeof st->tlo);
  if (cw->code == 430) {
    st->tlo[2] = z;
  } else if (cw->code == 431) {
    for (int i = 0; i < SWARF_NAXES; i++)
      if (has(b, i)) st->tlo[i] = word_mm(b, st, i);
  }
  st->modal.tool_length = cw->code;
  keep_machine(st, m);
  swarf_gc_out_tlo(ex->out, st);
  return SWARF_OK;
}

/* G10 L2 / L20: a work system's origin (and rotation). */
static int set_system(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, int l20,
                      swarf_gc_fault *f) {
  const swarf_gc_word *pw = swarf_gc_block_word(b, 'P');
  int active = swarf_gc_system_index(st), k;
  double m[SWARF_NAXES];
  if (!pw->present || pw->value < 0 || pw->value > 9)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_G10_P_RANGE, b->g[0].column, l20 ? 20 : 2);
  k = pw->value < 0.5 ? active : (int)(pw->value + 0.5) - 1;
  swarf_gc_to_machine(st, st->pos, m);
  if (swarf_gc_block_has(b, 'R')) st->rotations[k] = swarf_gc_block_word(b, 'R')->value;
  if (l20) {
    /* The origin that gives the current point the programmed coordinates
     * (x and y together when the system is rotated). */
    double target[SWARF_NAXES], rotated[SWARF_NAXES];
    int xy = st->rotations[k] != 0 && (has(b, 0) || has(b, 1));
    memcpy(target, st->pos, sizeof target);
    for (int i = 0; i < SWARF_NAXES; i++)
      if (has(b, i)) target[i] = word_mm(b, st, i);
    for (int i = 0; i < SWARF_NAXES; i++)
      rotated[i] = target[i] + st->g92[i];
    rotate_deg(st->rotations[k], &rotated[0], &rotated[1]);
    for (int i = 0; i < SWARF_NAXES; i++)
      if (has(b, i) || (xy && i < 2)) st->systems[k][i] = m[i] - st->tlo[i] - rotated[i];
  } else
    for (int i = 0; i < SWARF_NAXES; i++)
      if (has(b, i)) st->systems[k][i] = word_mm(b, st, i);
  if (k == active) {
    keep_machine(st, m);
    swarf_gc_out_g5x(ex->out, st);
  }
  return SWARF_OK;
}

/* G10 L1 / L10 / L11: a tool table entry. */
static int set_tool(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, int l,
                    swarf_gc_fault *f) {
  const swarf_gc_word *pw = swarf_gc_block_word(b, 'P');
  int t = (int)(pw->value + 0.5);
  double m[SWARF_NAXES];
  if (!pw->present || t < 1 || ex->tools == NULL || t >= ex->ntools)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_G10_TOOL_RANGE, b->g[0].column, l);
  if (swarf_gc_block_has(b, 'R'))
    ex->tools[t][1] = 2 * swarf_gc_block_word(b, 'R')->value * swarf_gc_scale(st);
  if (isnan(ex->tools[t][0])) ex->tools[t][0] = 0;
  if (!has(b, 2)) return SWARF_OK;
  if (l == 1) {
    ex->tools[t][0] = word_mm(b, st, 2);
    return SWARF_OK;
  }
  swarf_gc_to_machine(st, st->pos, m);
  /* L10: Z is where the current point is in the active system with the
   * new offset; L11 the same in G59.3 (the fixture system). */
  {
    int k = l == 11 ? 8 : swarf_gc_system_index(st);
    double base = m[2] - st->tlo[2] - st->systems[k][2] - (l == 11 ? 0 : st->g92[2]);
    ex->tools[t][0] = base - word_mm(b, st, 2);
  }
  return SWARF_OK;
}

static int run_g10(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                   swarf_gc_fault *f) {
  const swarf_gc_word *lw = swarf_gc_block_word(b, 'L');
  int l = lw->present ? (int)(lw->value + 0.5) : -1;
  if (l == 2 || l == 20) return set_system(b, st, ex, l == 20, f);
  if (l == 1 || l == 10 || l == 11) return set_tool(b, st, ex, l, f);
  return SWARF_GC_FAIL(f, SWARF_GCODE_E_G10_L_MISSING, lw->present ? lw->column : b->g[0].column);
}

/* G92 family and G52. */
static void run_g92(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, int code) {
  double m[SWARF_NAXES];
  swarf_gc_to_machine(st, st->pos, m);
  for (int i = 0; i < SWARF_NAXES; i++) {
    if (code == 920 && has(b, i)) st->g92[i] = st->pos[i] + st->g92[i] - word_mm(b, st, i);
    if (code == 520 && has(b, i)) st->g92[i] = word_mm(b, st, i);
    if (code == 921 || code == 922) st->g92[i] = 0;
    if (code == 923) st->g92[i] = st->g92_saved[i];
  }
  if (code == 920 || code == 520 || code == 921) memcpy(st->g92_saved, st->g92, sizeof st->g92);
  st->g92_on = code == 920 || code == 520 || code == 923;
  keep_machine(st, m);
  swarf_gc_out_g92(ex->out, st);
}

/* G28/G30: rapid to the intermediate point (if any axis word), then home. */
static void run_home(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, int code) {
  const double *home = code == 280 ? st->g28 : st->g30;
  double mid[SWARF_NAXES], m[SWARF_NAXES], end[SWARF_NAXES];
  int any = swarf_gc_block_has_axis(b);
  int column = b->g[0].column;
  /* rs274 always makes the first move, to where it is when no axis word. */
  if (any) swarf_gc_find_end(b, st, mid);
  else memcpy(mid, st->pos, sizeof mid);
  swarf_gc_out_straight(ex->out, st, SWARF_GC_CALL_TRAVERSE, mid, column);
  memcpy(st->pos, mid, sizeof st->pos);
  swarf_gc_to_machine(st, st->pos, m);
  for (int i = 0; i < SWARF_NAXES; i++)
    if (!any || has(b, i)) m[i] = home[i] + st->tlo[i];
  swarf_gc_from_machine(st, m, end);
  swarf_gc_out_straight(ex->out, st, SWARF_GC_CALL_TRAVERSE, end, column);
  memcpy(st->pos, end, sizeof st->pos);
}

static void store_home(swarf_gc_state *st, int code) {
  double m[SWARF_NAXES];
  swarf_gc_to_machine(st, st->pos, m);
  for (int i = 0; i < SWARF_NAXES; i++)
    m[i] -= st->tlo[i];
  memcpy(code == 281 ? st->g28 : st->g30, m, sizeof m);
}

int swarf_gc_offsets(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                     swarf_gc_fault *f) {
  int code = b->g[SWARF_GC_GROUP_NONMODAL].code;
  switch (code) {
  case 100:
    return run_g10(b, st, ex, f);
  case 280:
  case 300:
    run_home(b, st, ex, code);
    return SWARF_OK;
  case 281:
  case 301:
    store_home(st, code);
    return SWARF_OK;
  case 520:
  case 920:
  case 921:
  case 922:
  case 923:
    run_g92(b, st, ex, code);
    return SWARF_OK;
  default:
    return SWARF_OK;
  }
}
