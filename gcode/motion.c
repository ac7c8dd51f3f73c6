/* SPDX-License-Identifier: MPL-2.0 */
/* motion.c -- G0, G1, G2, G3 (with G53), and the dispatch to canned cycles.
 *
 * End points are program coordinates in mm: axis words in the active unit,
 * made absolute (G91 adds to the current point). Under G53 the words are
 * machine coordinates and are turned back into program coordinates, as
 * LinuxCNC does, so that the canon shows where the move goes in the active
 * system. Under G93 (inverse time) every feed move first sets its feed rate:
 * the move's length (XYZ, else ABC) times F, at least 0.1 units a minute,
 * as interp_inverse.cc does (rs274 prints SET_FEED_RATE(0.1000) for G93 G1
 * or G2 with F0): so a G93 F0 line and arc alike move at that crawl, and no
 * move, compensated or not, ever carries a feed of 0.
 */
#include <math.h>
#include <string.h>

#include "gcode_private.h"

#define INVERSE_RATE_MIN 0.1 /* units/min: LinuxCNC's floor of an inverse-time rate */

static const char axes[SWARF_NAXES] = {'X', 'Y', 'Z', 'A', 'B', 'C'};

static int is_g53(const swarf_gc_block *b) {
  return b->g[SWARF_GC_GROUP_NONMODAL].code == 530;
}

void swarf_gc_find_end(const swarf_gc_block *b, const swarf_gc_state *st, double end[SWARF_NAXES]) {
  int incremental = st->modal.distance == 910;
  double s = swarf_gc_scale(st);
  if (is_g53(b)) {
    double m[SWARF_NAXES];
    swarf_gc_to_machine(st, st->pos, m);
    for (int i = 0; i < SWARF_NAXES; i++) {
      const swarf_gc_word *w = swarf_gc_block_word(b, axes[i]);
      if (w->present) m[i] = w->value * (i < 3 ? s : 1.0);
    }
    swarf_gc_from_machine(st, m, end);
    for (int i = 0; i < SWARF_NAXES; i++)
      if (!swarf_gc_block_word(b, axes[i])->present) end[i] = st->pos[i];
    return;
  }
  for (int i = 0; i < SWARF_NAXES; i++) {
    const swarf_gc_word *w = swarf_gc_block_word(b, axes[i]);
    double v = w->value * (i < 3 ? s : 1.0);
    end[i] = !w->present ? st->pos[i] : incremental ? st->pos[i] + v : v;
  }
}

/* Length for inverse time: XYZ distance, else ABC (program units). */
static double inverse_length(const swarf_gc_state *st, const double *end, const swarf_move *arc) {
  double d = 0, r = 0;
  if (arc != NULL) {
    double v[3];
    for (int i = 0; i < 3; i++)
      v[i] = arc->start[i] - arc->center[i];
    r = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    d = hypot(r * arc->angle, arc->rise);
  } else
    d = sqrt(pow(end[0] - st->pos[0], 2) + pow(end[1] - st->pos[1], 2) +
             pow(end[2] - st->pos[2], 2));
  if (d > 0) return d / swarf_gc_scale(st);
  return sqrt(pow(end[3] - st->pos[3], 2) + pow(end[4] - st->pos[4], 2) +
              pow(end[5] - st->pos[5], 2));
}

static int inverse_feed(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                        const double *end, const swarf_move *arc, swarf_error *f) {
  double len, rate;
  if (st->modal.feed_mode != 930) return SWARF_OK;
  if (!swarf_gc_block_has(b, 'F'))
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_INVERSE_FEED_MISSING, b->motion_column,
                         b->motion == 10 ? "G1" : "arc");
  len = inverse_length(st, end, arc);
  rate = fmax(INVERSE_RATE_MIN, len * st->feed);
  swarf_gc_out_text(ex->out, "SET_FEED_RATE(%.4f)", rate);
  return SWARF_OK;
}

/* Under G93, the feed (mm/min) of the block's moves from call `first` on
 * (a swarf_gc_out_size, which stays right if held calls are taken in):
 * the programmed move's length times F. */
static void fix_inverse(swarf_gc_exec *ex, const swarf_gc_state *st, const double *end,
                        const swarf_move *arc, size_t first) {
  double len, feed;
  int xyz;
  if (st->modal.feed_mode != 930) return;
  len = inverse_length(st, end, arc);
  xyz = len > 0 &&
        (arc != NULL ||
         fabs(end[0] - st->pos[0]) + fabs(end[1] - st->pos[1]) + fabs(end[2] - st->pos[2]) > 0);
  feed = fmax(INVERSE_RATE_MIN, len * st->feed) * (xyz ? swarf_gc_scale(st) : 1);
  for (size_t i = first - ex->out->pending; i < ex->out->count; i++)
    if (ex->out->calls[i].kind != SWARF_GC_CALL_TEXT) ex->out->calls[i].move.feed = feed;
}

static int straight(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                    swarf_error *f) {
  double end[SWARF_NAXES];
  size_t first = swarf_gc_out_size(ex->out);
  int status = SWARF_OK;
  swarf_gc_find_end(b, st, end);
  if (b->motion == 10) {
    if (st->feed <= 0 && st->modal.feed_mode != 930)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_G1_ZERO_FEED, b->motion_column);
    status = inverse_feed(b, st, ex, end, NULL, f);
    if (status != SWARF_OK) return status;
    first = swarf_gc_out_size(ex->out);
  }
  if (swarf_gc_comp_active(st))
    status = swarf_gc_comp_straight(b, st, ex, end, f);
  else
    swarf_gc_out_straight(ex->out, st, b->motion == 0 ? SWARF_GC_CALL_TRAVERSE : SWARF_GC_CALL_FEED,
                          end, b->motion_column);
  if (status != SWARF_OK) return status;
  if (b->motion == 10) fix_inverse(ex, st, end, NULL, first);
  memcpy(st->pos, end, sizeof st->pos);
  st->comp_exit = 0;
  st->arc_not_allowed = 0;
  return SWARF_OK;
}

static int arc(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, swarf_error *f) {
  swarf_move mv;
  size_t first;
  int turns, status;
  if (st->arc_not_allowed)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARC_AFTER_COMP_OFF, b->motion_column);
  memset(&mv, 0, sizeof mv);
  memcpy(mv.start, st->pos, sizeof mv.start);
  swarf_gc_find_end(b, st, mv.end);
  if (st->modal.feed_mode == 930 && st->feed <= 0 && !swarf_gc_block_has(b, 'F'))
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_INVERSE_FEED_MISSING, b->motion_column, "arc");
  status = swarf_gc_arc(b, st, &mv, &turns, f);
  if (status == SWARF_OK) status = inverse_feed(b, st, ex, mv.end, &mv, f);
  if (status != SWARF_OK) return status;
  first = swarf_gc_out_size(ex->out);
  if (swarf_gc_comp_active(st))
    status = swarf_gc_comp_arc(b, st, ex, &mv, turns, f);
  else
    swarf_gc_out_arc(ex->out, st, &mv, turns, b->motion_column);
  if (status != SWARF_OK) return status;
  fix_inverse(ex, st, mv.end, &mv, first);
  memcpy(st->pos, mv.end, sizeof st->pos);
  return SWARF_OK;
}

/* G38.2-G38.5: a straight feed to the target with the probe on. A
 * simulation has no probe input, so the probe never trips: the move ends at
 * the target, #5070 (tripped) is 0 and #5061-#5069 hold the target, as
 * rs274 reports. LinuxCNC's motion would stop G38.2 and G38.4 with an
 * error when the probe does not trip; the simulation goes on and says so
 * in a note. */
int swarf_gc_probe(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, swarf_error *f) {
  double end[SWARF_NAXES], d = 0, s = swarf_gc_scale(st);
  size_t before;
  swarf_gc_find_end(b, st, end);
  for (int i = 0; i < SWARF_NAXES; i++)
    d += fabs(end[i] - st->pos[i]);
  if (st->comp_side != 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_PROBE_WITH_COMP, b->motion_column);
  if (d < 1e-9) return SWARF_GC_FAIL(f, SWARF_GCODE_E_PROBE_TOO_CLOSE, b->motion_column);
  if (st->feed <= 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_PROBE_ZERO_FEED, b->motion_column);
  swarf_gc_out_text(ex->out, "TURN_PROBE_ON()");
  before = ex->out->count;
  swarf_gc_out_straight(ex->out, st, SWARF_GC_CALL_FEED, end, b->motion_column);
  if (ex->out->count > before) ex->out->calls[ex->out->count - 1].print = SWARF_GC_PRINT_PROBE;
  swarf_gc_out_text(ex->out, "TURN_PROBE_OFF()");
  memcpy(st->pos, end, sizeof st->pos);
  ex->params->num[5070] = 0;
  for (int i = 0; i < SWARF_NAXES; i++)
    ex->params->num[5061 + i] = end[i] / (i < 3 ? s : 1.0);
  swarf_gc_note(
      ex->notes, b->motion_column,
      "G38.%d: no probe input in a simulation: the probe did not trip; the move ends "
      "at the target (#5070 = 0)%s",
      b->motion % 10,
      (b->motion == 382 || b->motion == 384) ? " (a real machine stops with an error here)" : "");
  return SWARF_OK;
}

static int is_cycle(int m) {
  return m == 730 || m == 740 || m == 760 || (m >= 810 && m <= 890);
}

int swarf_gc_motion(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                    swarf_error *f) {
  int m = b->motion, status;
  if (m < 0) return SWARF_OK;
  if (swarf_gc_fanuc_like(st) && b->g[SWARF_GC_GROUP_NONMODAL].code == 530 &&
      b->g[SWARF_GC_GROUP_MOTION].code < 0)
    return straight(b, st, ex, f); /* Fanuc's G53 rapid leaves the modal motion */
  if (!is_cycle(m)) st->cycle_il_set = st->cycle_after_g87 = 0; /* the cycles end */
  if (is_cycle(m)) {
    st->spline_last = 0;
    status = swarf_gc_cycle(b, st, ex, f);
    if (status == SWARF_OK) st->modal.motion = m;
    return status;
  }
  if (m == 50 || m == 51 || (m >= 382 && m <= 385)) {
    status = m <= 51 ? swarf_gc_spline(b, st, ex, f) : swarf_gc_probe(b, st, ex, f);
    if (status != SWARF_OK) return status;
    st->modal.motion = m;
    st->spline_last = m == 50; /* the next G5 may leave out I J */
    return SWARF_OK;
  }
  st->spline_last = 0;
  if (m <= 30) st->motion01 = m;
  st->modal.motion = m;
  if (m == 800) return SWARF_OK;
  if (m == 0 || m == 10) return straight(b, st, ex, f);
  return arc(b, st, ex, f);
}
