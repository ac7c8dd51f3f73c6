/* SPDX-License-Identifier: MPL-2.0 */
/* check.c -- a block against the modal state, before anything is executed.
 *
 * Decides which motion the block makes (LinuxCNC's enhance_block: the motion
 * word, else the modal motion if there are axis words, or I/J/K words in arc
 * mode) and checks what LinuxCNC's read_* and check_items functions check:
 * values in range, words with no code to use them, G4 and G53 companions,
 * canned cycle words. Group 0 codes that take axis words (G10 G28 G30 G52
 * G92) keep them from the modal motion.
 * Reads the state, changes nothing but the block's motion fields.
 */
#include <math.h>
#include <string.h>

#include "gcode_private.h"

#define MOTION_G0 0
#define MOTION_G1 10
#define MOTION_G2 20
#define MOTION_G3 30
#define MOTION_G80 800
#define MAX_ARC_TURNS 10000 /* a bound of ours, not LinuxCNC's: keeps arcs finite */

#define L(c) SWARF_GC_LETTER(c)
#define AXES (L('X') | L('Y') | L('Z') | L('A') | L('B') | L('C'))
#define OFFSETS (L('I') | L('J') | L('K'))

/* Column of the leftmost present word among `letters` (SWARF_GC_LETTER
 * bits), 0 if none. */
static int first_column(const swarf_gc_block *b, unsigned letters) {
  int column = 0;
  letters &= b->letters;
  for (int i = 0; letters != 0; i++, letters >>= 1)
    if ((letters & 1) && (column == 0 || b->words[i].column < column)) column = b->words[i].column;
  return column;
}

static int is_arc(int motion) {
  return motion == MOTION_G2 || motion == MOTION_G3;
}

static int is_cycle(int motion) {
  return motion == 730 || motion == 740 || motion == 760 || motion == 870 ||
         (motion >= 810 && motion <= 890);
}

/* Group 0 codes that take the axis words for themselves (and G43.1: its
 * axis words are the offset, it makes no move). */
static int axis_user(int g0) {
  return g0 == 100 || g0 == 280 || g0 == 300 || g0 == 520 || g0 == 920;
}

/* Fanuc and Haas: canned cycles are a modal group of their own (group 09),
 * G0-G3 stay in force under them (group 01): after G80, or with G80 on the
 * line, axis words move in the last of G0-G3 (Fanuc 0i-MF Operator's Manual,
 * "Canned cycle cancel": "the G code of group 01 is restored"). G53 moves at
 * rapid whatever the modal motion ("G53 ... the tool moves at rapid
 * traverse"). */
static int fanuc_motion(swarf_gc_block *b, const swarf_gc_state *st, int axis_column,
                        int ijk_column) {
  const swarf_gc_code_word *g1 = &b->g[SWARF_GC_GROUP_MOTION];
  int modal = st->modal.motion == MOTION_G80 ? st->motion01 : st->modal.motion;
  if (g1->code >= 0) {
    b->motion = g1->code == MOTION_G80 && axis_column ? st->motion01 : g1->code;
    b->motion_column = g1->column;
  } else if (b->g[SWARF_GC_GROUP_NONMODAL].code == 530 && axis_column) {
    b->motion = MOTION_G0;
    b->motion_column = axis_column;
  } else if (axis_column) {
    b->motion = modal;
    b->motion_column = axis_column;
  } else if (ijk_column && is_arc(modal)) {
    b->motion = modal;
    b->motion_column = ijk_column;
  }
  return SWARF_OK;
}

/* Fanuc and Haas words that read differently: a dwell P without a decimal
 * point is milliseconds (Fanuc: "P cannot use a decimal point ... 1 ms";
 * Haas G04: "P1000 = 1 second ... P1. = 1 second"), G4 X is seconds, and a
 * canned cycle's K is its repeat count (L on LinuxCNC and older Fanucs). */
static void fanuc_words(swarf_gc_block *b) {
  swarf_gc_word *p = &b->words['P' - 'A'], *x = &b->words['X' - 'A'];
  int g0 = b->g[SWARF_GC_GROUP_NONMODAL].code, g1 = b->g[SWARF_GC_GROUP_MOTION].code;
  if (g0 == 40 && x->present && !p->present) {
    *p = *x;
    x->present = 0;
    b->letters &= ~L('X');
    b->letters |= L('P');
    return;
  }
  if (p->present && (g0 == 40 || is_cycle(g1)) && strchr(p->text, '.') == NULL &&
      strchr(p->text, '#') == NULL && strchr(p->text, '[') == NULL)
    p->value /= 1000.0;
}

static void fanuc_repeats(swarf_gc_block *b) {
  swarf_gc_word *k = &b->words['K' - 'A'];
  if (!is_cycle(b->motion) || b->motion == 870 || !k->present || swarf_gc_block_has(b, 'L')) return;
  b->words['L' - 'A'] = *k;
  k->present = 0;
  b->letters = (b->letters & ~L('K')) | L('L');
}

static int find_motion(swarf_gc_block *b, const swarf_gc_state *st, swarf_error *f) {
  const swarf_gc_code_word *g1 = &b->g[SWARF_GC_GROUP_MOTION];
  int axis_column = first_column(b, AXES);
  int ijk_column = first_column(b, OFFSETS);
  const swarf_gc_code_word *user = &b->g[SWARF_GC_GROUP_NONMODAL];
  if (b->g[SWARF_GC_GROUP_TOOL_LENGTH].code == 431) user = &b->g[SWARF_GC_GROUP_TOOL_LENGTH];
  if (axis_user(user->code) || user->code == 431) {
    if (g1->code >= 0 && g1->code != MOTION_G80 && axis_column)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_TWO_AXIS_CODES, g1->column, user->text, g1->text);
    if (g1->code >= 0) {
      b->motion = g1->code;
      b->motion_column = g1->column;
    }
    return SWARF_OK;
  }
  if (swarf_gc_fanuc_like(st)) return fanuc_motion(b, st, axis_column, ijk_column);
  if (g1->code >= 0) {
    if (g1->code == MOTION_G80 && axis_column)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_AXES_WITH_G80, axis_column);
    b->motion = g1->code;
    b->motion_column = g1->column;
  } else if (axis_column) {
    if (st->modal.motion == MOTION_G80)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_AXES_WITHOUT_MOTION, axis_column);
    b->motion = st->modal.motion;
    b->motion_column = axis_column;
  } else if (ijk_column && is_arc(st->modal.motion)) {
    b->motion = st->modal.motion;
    b->motion_column = ijk_column;
  }
  return SWARF_OK;
}

static int is_whole(double v, double tolerance) {
  return fabs(v - floor(v + 0.5)) <= tolerance;
}

static int check_values(const swarf_gc_block *b, swarf_error *f) {
  static const char nonnegative[] = "FSNTHL";
  if (!(b->letters & (L('F') | L('S') | L('N') | L('T') | L('H') | L('L')))) return SWARF_OK;
  for (const char *l = nonnegative; *l; l++) {
    const swarf_gc_word *w = swarf_gc_block_word(b, *l);
    if (w->present && w->value < 0)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_NEGATIVE_WORD, w->column, *l, w->text);
  }
  for (const char *l = "THL"; *l; l++) {
    const swarf_gc_word *w = swarf_gc_block_word(b, *l);
    if (w->present && !is_whole(w->value, 1e-4))
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_WORD_NOT_INTEGER, w->column, w->text);
  }
  return SWARF_OK;
}

static int check_g4(const swarf_gc_block *b, swarf_error *f) {
  const swarf_gc_code_word *g0 = &b->g[SWARF_GC_GROUP_NONMODAL];
  const swarf_gc_word *p = swarf_gc_block_word(b, 'P');
  int g1 = b->g[SWARF_GC_GROUP_MOTION].code;
  if (!p->present) return SWARF_GC_FAIL(f, SWARF_GCODE_E_DWELL_P_MISSING, g0->column);
  if (p->value < 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_NEGATIVE_DWELL, p->column, p->text);
  if (is_arc(g1)) return SWARF_GC_FAIL(f, SWARF_GCODE_E_DWELL_WITH_ARC, g0->column);
  return SWARF_OK;
}

static int check_g53(const swarf_gc_block *b, const swarf_gc_state *st, swarf_error *f) {
  const swarf_gc_code_word *g0 = &b->g[SWARF_GC_GROUP_NONMODAL];
  int distance = b->g[SWARF_GC_GROUP_DISTANCE].code;
  if (b->motion != MOTION_G0 && b->motion != MOTION_G1)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_G53_MOTION, g0->column);
  if (distance == 910 || (distance < 0 && st->modal.distance == 910))
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_G53_INCREMENTAL, g0->column);
  return SWARF_OK;
}

static int check_nonmodal(const swarf_gc_block *b, const swarf_gc_state *st, swarf_error *f) {
  switch (b->g[SWARF_GC_GROUP_NONMODAL].code) {
  case 40:
    return check_g4(b, f);
  case 530:
    return check_g53(b, st, f);
  default:
    return SWARF_OK;
  }
}

static int unused(const swarf_gc_word *w, const char *users, swarf_error *f) {
  return SWARF_GC_FAIL(f, SWARF_GCODE_E_UNUSED_WORD, w->column, w->text[0], users, w->text);
}

static int check_arc_p(const swarf_gc_word *p, swarf_error *f) {
  if (!is_whole(p->value, 0.001))
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_P_NOT_INTEGER, p->column, p->text);
  if (floor(p->value + 0.5) < 1)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_P_BELOW_ONE, p->column, p->text);
  if (p->value > MAX_ARC_TURNS)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_P_TOO_LARGE, p->column, MAX_ARC_TURNS, p->text);
  return SWARF_OK;
}

static int is_user_m(const swarf_gc_block *b) {
  return b->m[SWARF_GC_MGROUP_USER].code >= 0 || b->m[SWARF_GC_MGROUP_IO].code >= 0 ||
         b->m[SWARF_GC_MGROUP_VENDOR].code >= 0;
}

static int check_cycle(const swarf_gc_block *b, const swarf_gc_state *st, swarf_error *f) {
  const swarf_gc_word *w;
  int col = b->motion_column;
  for (const char *l = "ABC"; *l; l++)
    if ((w = swarf_gc_block_word(b, *l))->present)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_CYCLE_ROTARY_WORD, w->column,
                           *l == 'A'   ? "an a"
                           : *l == 'B' ? "a b"
                                       : "a c",
                           w->text);
  if (st->comp_side != 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_CYCLE_WITH_COMP, col);
  if ((w = swarf_gc_block_word(b, 'L'))->present && w->value < 1)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_ZERO_REPEATS, w->column, w->text);
  return SWARF_OK;
}

/* Words that need a code to use them (LinuxCNC's check_other_codes). */
static int check_users(const swarf_gc_block *b, const swarf_gc_state *st, swarf_error *f) {
  int arc = is_arc(b->motion), cycle = is_cycle(b->motion);
  int g0 = b->g[SWARF_GC_GROUP_NONMODAL].code;
  int g4 = g0 == 40, g10 = g0 == 100;
  int g64 = b->g[SWARF_GC_GROUP_PATH_CONTROL].code == 640;
  int user_m = is_user_m(b) || b->m[SWARF_GC_MGROUP_SPINDLE].code == 190;
  int vendor = b->g[SWARF_GC_GROUP_VENDOR].code >= 0;
  int ext = b->g[SWARF_GC_GROUP_COORD_SYSTEM].code == 541 ||
            b->g[SWARF_GC_GROUP_COORD_SYSTEM].code == 1540;
  const swarf_gc_word *w;
  if ((w = swarf_gc_block_word(b, 'H'))->present && b->g[SWARF_GC_GROUP_TOOL_LENGTH].code != 430 &&
      !g10)
    return unused(w, "G43", f);
  int spline = b->motion == 50 || b->motion == 51, g87 = b->motion == 870;
  for (const char *l = "IJK"; (b->letters & OFFSETS) && *l; l++)
    if ((w = swarf_gc_block_word(b, *l))->present && !arc && !g87 && !(spline && *l != 'K'))
      return unused(w, "G2 or G3", f);
  if ((w = swarf_gc_block_word(b, 'R'))->present && g64 &&
      b->m[SWARF_GC_MGROUP_SPINDLE].code == 190)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_M19_G64_R, w->column, w->text);
  if ((w = swarf_gc_block_word(b, 'E'))->present && !vendor) return unused(w, "G187", f);
  if ((w = swarf_gc_block_word(b, 'R'))->present && !arc && !cycle && !g10 && !vendor && !user_m)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_UNUSED_R_WORD, w->column, w->text);
  if ((w = swarf_gc_block_word(b, 'L'))->present && !cycle && !g10)
    return unused(w, "G10 or canned cycle", f);
  if ((w = swarf_gc_block_word(b, 'D'))->present && !g10 &&
      b->g[SWARF_GC_GROUP_CUTTER_COMP].code <= 400)
    return unused(w, "G41, G41.1, G42, G42.1, G71, G71.1, G71.2 or G96", f);
  if ((w = swarf_gc_block_word(b, 'P'))->present) {
    if (!arc && !g4 && !g64 && !g10 && !cycle && !user_m && !vendor && !ext && b->motion != 50)
      return unused(w, "G2, G3, G4, G10, G64, canned cycle or M code", f);
    if (arc) return check_arc_p(w, f);
  }
  int m61 = b->m[SWARF_GC_MGROUP_TOOL].code == 610, m19 = b->m[SWARF_GC_MGROUP_SPINDLE].code == 190;
  if ((w = swarf_gc_block_word(b, 'Q'))->present && !g64 && !cycle && !user_m && !vendor && !m61 &&
      !m19 && b->motion != 50)
    return unused(w, "G64, G73, G83 or M code", f);
  if (cycle) return check_cycle(b, st, f);
  return SWARF_OK;
}

int swarf_gc_block_check(swarf_gc_block *b, const swarf_gc_state *st, swarf_error *f) {
  int status = check_values(b, f);
  if (status == SWARF_OK && st->dialect == SWARF_GCODE_DIALECT_GRBL)
    status = swarf_gc_grbl_check(b, f);
  if (swarf_gc_fanuc_like(st)) fanuc_words(b);
  if (status == SWARF_OK) status = find_motion(b, st, f);
  if (swarf_gc_fanuc_like(st)) fanuc_repeats(b);
  if (status == SWARF_OK) status = check_nonmodal(b, st, f);
  if (status == SWARF_OK) status = check_users(b, st, f);
  return status;
}
