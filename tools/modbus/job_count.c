/* SPDX-License-Identifier: MPL-2.0 */
/* job_count.c -- the pre-count of a program's motion moves, so that a
 * controller knows the total (registers 6-7) and the progress in per-mille
 * while the program streams through the simulation. It parses the file once
 * more in a thread of its own (the parser alone runs ~500,000 moves/s, far
 * ahead of the simulation) and publishes the total when it is known. The
 * counter owns its thread and a copy of the path.
 */
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "gcode.h"
#include "modbus_private.h"

struct swarf_job_count {
  pthread_t thread;
  char *path;
  swarf_job *status;
  long moves;
  atomic_int stop;
};

static int count_move(const swarf_move *mv, void *user) {
  struct swarf_job_count *c = user;
  if (mv->kind != SWARF_MOVE_DWELL && mv->kind != SWARF_MOVE_TOOL_CHANGE) c->moves++;
  return atomic_load(&c->stop);
}

static void *run(void *arg) {
  struct swarf_job_count *c = arg;
  if (swarf_gcode_parse_file(c->path, count_move, c, NULL) == SWARF_OK)
    swarf_job_set_total(c->status, c->moves);
  return NULL;
}

swarf_job_count *swarf_job_count_new(const char *path, swarf_job *status) {
  struct swarf_job_count *c;
  if (path == NULL || status == NULL || (c = calloc(1, sizeof *c)) == NULL) return NULL;
  c->status = status;
  c->path = strdup(path);
  atomic_init(&c->stop, 0);
  if (c->path == NULL || pthread_create(&c->thread, NULL, run, c) != 0) {
    free(c->path);
    free(c);
    return NULL;
  }
  return c;
}

void swarf_job_count_free(swarf_job_count *c) {
  if (c == NULL) return;
  atomic_store(&c->stop, 1);
  pthread_join(c->thread, NULL);
  free(c->path);
  free(c);
}
