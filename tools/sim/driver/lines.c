/* SPDX-License-Identifier: MPL-2.0 */
/* lines.c -- per-line results of the simulation (swarf_line_result).
 *
 * Moves are summed into the open line; when a move of another line comes,
 * the open line is closed and waits in `pending` until the batch holding
 * its moves has been removed, then the line callback hears of it. The
 * pending list is as long as the batch: when it is full, the batch is
 * removed early. Removed volumes are NaN unless measured (cfg.line_volumes):
 * each cut of a batch carries the id of its line (cur_id when queued), and
 * the measured removal adds its volume to that line before it is told.
 */
#include <math.h>
#include <string.h>

#include "sim_private.h"

static void open_line(swarf_sim *s, const swarf_motion *m, int tool) {
  memset(&s->cur, 0, sizeof s->cur);
  s->cur.line = m->line;
  s->cur.tool = tool;
  s->cur.removed = s->measured && s->cfg.line_volumes ? 0.0 : NAN;
  s->cur_id++;
}

void swarf_sim_lines_removed(swarf_sim *s, long id, double removed) {
  long j = id - (s->cur_id - s->npending);
  if (s->cfg.cb.line == NULL || !s->cfg.line_volumes) return;
  if (j >= 0 && j < s->npending)
    s->pending[j].removed += removed;
  else if (id == s->cur_id && s->cur.moves > 0)
    s->cur.removed += removed;
}

int swarf_sim_lines_add(swarf_sim *s, const swarf_motion *m, int tool) {
  if (s->cfg.cb.line == NULL) return 0;
  if (s->cur.moves > 0 && (s->cur.line != m->line || s->cur.tool != tool)) {
    if (s->npending == s->pending_cap && swarf_sim_batch_flush(s) != 0) return 1;
    s->pending[s->npending++] = s->cur;
    s->cur.moves = 0;
  }
  if (s->cur.moves == 0) open_line(s, m, tool);
  s->cur.moves++;
  s->cur.time_s += m->duration;
  s->cur.path_mm += m->length;
  return 0;
}

int swarf_sim_lines_flush(swarf_sim *s, int at_end) {
  if (s->cfg.cb.line == NULL) return 0;
  for (int i = 0; i < s->npending; i++)
    s->cfg.cb.line(s->cfg.cb.user, &s->pending[i]);
  s->npending = 0;
  if (at_end && s->cur.moves > 0) {
    s->cfg.cb.line(s->cfg.cb.user, &s->cur);
    s->cur.moves = 0;
  }
  return 0;
}
