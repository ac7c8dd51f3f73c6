/* SPDX-License-Identifier: MPL-2.0 */
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
  st->ext_system = 0;
  keep_machine(st, m);
  swarf_gc_out_g5x(ex->out, st);
  swarf_gc_out_g92(ex->out, st);
  return SWARF_OK;
}

/* The largest P of the extended work offsets: Fanuc G54.1 P1-P300 (48
 * standard, 300 with the option), Haas G154 P1-P99 (and G54.1 P1-P99). */
static int ext_max(const swarf_gc_state *st) {
  return st->dialect == SWARF_GCODE_DIALECT_HAAS ? 99 : SWARF_GC_NEXT - 1;
}

int swarf_gc_select_ext(const swarf_gc_block *b, int code, swarf_gc_state *st, swarf_gc_exec *ex,
                        swarf_error *f) {
  const swarf_gc_word *pw = swarf_gc_block_word(b, 'P');
  const swarf_gc_code_word *cw = &b->g[SWARF_GC_GROUP_COORD_SYSTEM];
  double pv = pw->present ? pw->value : 1, m[SWARF_NAXES];
  int k = (int)floor(pv + 0.5);
  (void)code;
  if (pv != k || k < 1 || k > ext_max(st))
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_EXT_SYSTEM_RANGE, cw->column, cw->text, pv, ext_max(st));
  swarf_gc_to_machine(st, st->pos, m);
  st->modal.coord_system = 540;
  st->ext_system = k;
  memcpy(st->ext_origin, ex->ext[k], sizeof st->ext_origin);
  keep_machine(st, m);
  swarf_gc_out_text(ex->out, "COMMENT(\"extended work offset P%d\")", k);
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
                         swarf_error *f) {
  const swarf_gc_code_word *cw = &b->g[SWARF_GC_GROUP_TOOL_LENGTH];
  double m[SWARF_NAXES], z = 0;
  if (cw->code < 0) return SWARF_OK;
  if (cw->code == 430) {
    int h = swarf_gc_block_has(b, 'H') ? (int)(swarf_gc_block_word(b, 'H')->value + 0.5) : st->tool;
    if (tool_z(ex, h, &z) != 0) {
      if (!swarf_gc_fanuc_like(st))
        return SWARF_GC_FAIL(f, SWARF_GCODE_E_TOOL_NOT_FOUND, cw->column, h);
      z = 0; /* a Fanuc or Haas control holds its offsets */
      swarf_gc_note(ex->notes, cw->column,
                    "G43 H%d: tool %d's length offset is the control's (not in the table): "
                    "taken as 0",
                    h, h);
    }
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
                      swarf_error *f) {
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
                    swarf_error *f) {
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

/* Fanuc and Haas G10 (Fanuc 0i-MF "Programmable data input"; Haas "G10 Set
 * Offsets"): L2 P1-P6 a work system's origin, L20 P an extended one; L10
 * (or L1) P R a tool length, L11 its wear (added), L12 P R the radius
 * (Fanuc; Haas: the diameter), L13 its wear (noted only). Under G91 the
 * values are added to what is there. */
static int fanuc_g10(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, int l,
                     swarf_error *f) {
  const swarf_gc_word *pw = swarf_gc_block_word(b, 'P'), *rw = swarf_gc_block_word(b, 'R');
  int p = (int)floor(pw->value + 0.5), inc = st->modal.distance == 910, col = b->g[0].column;
  double r = rw->value * swarf_gc_scale(st), m[SWARF_NAXES];
  if (l == 2 && !inc) return set_system(b, st, ex, 0, f);
  if (l == 2 || l == 20) {
    double *o;
    if (l == 2 && (p < 0 || p > 6)) return SWARF_GC_FAIL(f, SWARF_GCODE_E_G10_P_RANGE, col, l);
    if (l == 20 && (p < 1 || p > ext_max(st)))
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_EXT_SYSTEM_RANGE, col, "G10 L20", pw->value,
                           ext_max(st));
    o = l == 20 ? ex->ext[p] : st->systems[p == 0 ? swarf_gc_system_index(st) : p - 1];
    swarf_gc_to_machine(st, st->pos, m);
    for (int i = 0; i < SWARF_NAXES; i++)
      if (has(b, i)) o[i] = (inc ? o[i] : 0) + word_mm(b, st, i);
    if (l == 20 && st->ext_system == p) memcpy(st->ext_origin, o, sizeof st->ext_origin);
    keep_machine(st, m);
    swarf_gc_out_g5x(ex->out, st);
    return SWARF_OK;
  }
  if (p < 1 || ex->tools == NULL || p >= ex->ntools)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_G10_TOOL_RANGE, col, l);
  if (isnan(ex->tools[p][0])) ex->tools[p][0] = 0;
  if (l == 1 || l == 10) ex->tools[p][0] = (inc ? ex->tools[p][0] : 0) + r;
  if (l == 11) ex->tools[p][0] += r;
  if (l == 12)
    ex->tools[p][1] =
        (inc ? ex->tools[p][1] : 0) + (st->dialect == SWARF_GCODE_DIALECT_HAAS ? r : 2 * r);
  if (l == 11 || l == 13)
    swarf_gc_note(ex->notes, col, "G10 L%d: wear offsets are %s", l,
                  l == 11 ? "added to the tool length" : "not kept (no effect on the path)");
  if (l != 1 && l != 10 && l != 11 && l != 12 && l != 13)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_G10_L_MISSING, col);
  return SWARF_OK;
}

static int run_g10(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, swarf_error *f) {
  const swarf_gc_word *lw = swarf_gc_block_word(b, 'L');
  int l = lw->present ? (int)(lw->value + 0.5) : -1;
  if (swarf_gc_fanuc_like(st)) return fanuc_g10(b, st, ex, l, f);
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
  if (any)
    swarf_gc_find_end(b, st, mid);
  else
    memcpy(mid, st->pos, sizeof mid);
  swarf_gc_out_straight(ex->out, st, SWARF_GC_CALL_TRAVERSE, mid, column);
  memcpy(st->pos, mid, sizeof st->pos);
  swarf_gc_to_machine(st, st->pos, m);
  /* The controlled point goes home: the tool tip's program coordinate is
   * the home less the tool length offset (rs274 prints Z-5 for G28 under
   * G43.1 Z5 with the home at 0). */
  for (int i = 0; i < SWARF_NAXES; i++)
    if (!any || has(b, i)) m[i] = home[i];
  swarf_gc_from_machine(st, m, end);
  swarf_gc_out_straight(ex->out, st, SWARF_GC_CALL_TRAVERSE, end, column);
  memcpy(st->pos, end, sizeof st->pos);
}

void swarf_gc_home_cycle(swarf_gc_state *st, swarf_gc_exec *ex, const double home[SWARF_NAXES],
                         int column) {
  double m[SWARF_NAXES], end[SWARF_NAXES];
  swarf_gc_to_machine(st, st->pos, m);
  if (m[2] != home[2]) { /* Z up first, clear of the work */
    m[2] = home[2];
    swarf_gc_from_machine(st, m, end);
    swarf_gc_out_straight(ex->out, st, SWARF_GC_CALL_TRAVERSE, end, column);
    memcpy(st->pos, end, sizeof st->pos);
  }
  if (memcmp(m, home, sizeof m) != 0) { /* then the other axes */
    swarf_gc_from_machine(st, home, end);
    swarf_gc_out_straight(ex->out, st, SWARF_GC_CALL_TRAVERSE, end, column);
    memcpy(st->pos, end, sizeof st->pos);
  }
}

static void store_home(swarf_gc_state *st, int code) {
  double m[SWARF_NAXES];
  /* The controlled point's machine position, offset included (as rs274). */
  swarf_gc_to_machine(st, st->pos, m);
  memcpy(code == 281 ? st->g28 : st->g30, m, sizeof m);
}

int swarf_gc_offsets(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                     swarf_error *f) {
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
