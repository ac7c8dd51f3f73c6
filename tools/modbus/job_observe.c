/* SPDX-License-Identifier: MPL-2.0 */
/* job_observe.c -- the simulation side of the status service: the
 * observer called from the simulation's progress callback after every move. It fills its own
 * snapshot and publishes it without waiting (job.h), refreshes the removed volume now and then (a
 * pass over the grid, so at most every 0.5 s and never more than ~2 % of the run), and obeys pause
 * and abort commands. Pausing is the one place where the simulation waits, and it waits on the
 * command only (a flag polled every 50 ms), never on the network.
 */
#include <math.h>
#include <string.h>
#include <time.h>

#include "modbus_private.h"

void swarf_job_observer_init(swarf_job_observer *ob, swarf_job *status) {
  memset(ob, 0, sizeof *ob);
  ob->status = status;
  swarf_job_read(status, &ob->snap);
  ob->snap.state = SWARF_JOB_RUNNING;
  ob->snap.start = swarf_job_now();
  swarf_job_publish_final(status, &ob->snap);
}

static void refresh_volume(swarf_job_observer *ob, const swarf_sim_report *sofar,
                           const swarf_stock *stock, double now) {
  double v, cost;
  if (stock == NULL || now < ob->next_volume) return;
  v = swarf_stock_volume(stock);
  cost = swarf_job_now() - now;
  if (isfinite(v)) ob->snap.removed = sofar->volume_before - v;
  ob->next_volume = now + (cost * 50.0 > 0.5 ? cost * 50.0 : 0.5);
}

static void hold_while_paused(swarf_job_observer *ob) {
  const struct timespec tick = {0, 50000000};
  ob->snap.paused = 1;
  while (swarf_job_pause_requested(ob->status) && !swarf_job_abort_requested(ob->status)) {
    swarf_job_publish(ob->status, &ob->snap);
    nanosleep(&tick, NULL);
  }
  ob->snap.paused = 0;
}

int swarf_job_observe(swarf_job_observer *ob, const swarf_sim_progress *p) {
  double now = swarf_job_now();
  ob->snap.line = p->line;
  ob->snap.tool = p->tool;
  ob->snap.moves_done = p->report->moves;
  ob->snap.alarms = p->report->alarms;
  ob->snap.collisions = p->report->collisions;
  refresh_volume(ob, p->report, p->stock, now);
  if (swarf_job_pause_requested(ob->status)) hold_while_paused(ob);
  swarf_job_publish(ob->status, &ob->snap);
  return swarf_job_abort_requested(ob->status);
}

void swarf_job_observer_final(swarf_job_observer *ob, int rc, const swarf_sim_report *rep) {
  ob->snap.state = rc == 0 ? SWARF_JOB_FINISHED : SWARF_JOB_FAILED;
  ob->snap.error = rc;
  ob->snap.paused = 0;
  ob->snap.end = swarf_job_now();
  if (rep != NULL) {
    if (rc == 0) ob->snap.line = rep->lines;
    ob->snap.moves_done = rep->moves;
    ob->snap.alarms = rep->alarms;
    ob->snap.collisions = rep->collisions;
    if (rc == 0) ob->snap.removed = rep->volume_before - rep->volume_after;
  }
  swarf_job_publish_final(ob->status, &ob->snap);
}
