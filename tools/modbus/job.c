/* SPDX-License-Identifier: MPL-2.0 */
/* job.c -- the status snapshot shared by the simulation and the status
 * services (see job.h). The handle owns its lock and its copy of the
 * snapshot; callers own the snapshots they pass in or read out.
 */
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "job.h"

struct swarf_job {
  pthread_mutex_t lock; /* guards snap, held only for copies */
  swarf_job_snapshot snap;
  atomic_int pause, abort;
};

double swarf_job_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

swarf_job *swarf_job_new(const char *program) {
  swarf_job *s = calloc(1, sizeof *s);
  const char *base = program ? strrchr(program, '/') : NULL;
  if (s == NULL) return NULL;
  pthread_mutex_init(&s->lock, NULL);
  atomic_init(&s->pause, 0);
  atomic_init(&s->abort, 0);
  base = base ? base + 1 : program ? program : "";
  strncpy(s->snap.program, base, SWARF_JOB_NAME_LEN - 1);
  s->snap.start = swarf_job_now();
  return s;
}

void swarf_job_free(swarf_job *s) {
  if (s == NULL) return;
  pthread_mutex_destroy(&s->lock);
  free(s);
}

/* Under the lock: take the simulation's fields, keep the others'. */
static void merge(swarf_job *s, const swarf_job_snapshot *in) {
  swarf_job_snapshot keep = s->snap;
  s->snap = *in;
  s->snap.moves_total = keep.moves_total;
  s->snap.commands = keep.commands;
  s->snap.last_command = keep.last_command;
  s->snap.heartbeat = keep.heartbeat + 1;
  memcpy(s->snap.program, keep.program, sizeof keep.program);
}

int swarf_job_publish(swarf_job *s, const swarf_job_snapshot *snap) {
  if (s == NULL || snap == NULL || pthread_mutex_trylock(&s->lock) != 0) return 0;
  merge(s, snap);
  pthread_mutex_unlock(&s->lock);
  return 1;
}

void swarf_job_publish_final(swarf_job *s, const swarf_job_snapshot *snap) {
  if (s == NULL || snap == NULL) return;
  pthread_mutex_lock(&s->lock);
  merge(s, snap);
  pthread_mutex_unlock(&s->lock);
}

void swarf_job_set_total(swarf_job *s, long moves_total) {
  if (s == NULL) return;
  pthread_mutex_lock(&s->lock);
  s->snap.moves_total = moves_total;
  pthread_mutex_unlock(&s->lock);
}

void swarf_job_set_commands(swarf_job *s, int enabled) {
  if (s == NULL) return;
  pthread_mutex_lock(&s->lock);
  s->snap.commands = enabled != 0;
  pthread_mutex_unlock(&s->lock);
}

void swarf_job_read(swarf_job *s, swarf_job_snapshot *out) {
  if (s == NULL || out == NULL) return;
  pthread_mutex_lock(&s->lock);
  *out = s->snap;
  pthread_mutex_unlock(&s->lock);
}

int swarf_job_command_post(swarf_job *s, int command) {
  int ok;
  if (s == NULL) return -1;
  pthread_mutex_lock(&s->lock);
  ok = s->snap.commands && command >= SWARF_JOB_CMD_PAUSE && command <= SWARF_JOB_CMD_ABORT;
  if (ok) s->snap.last_command = command;
  pthread_mutex_unlock(&s->lock);
  if (!ok) return -1;
  if (command == SWARF_JOB_CMD_PAUSE) atomic_store(&s->pause, 1);
  if (command == SWARF_JOB_CMD_RESUME) atomic_store(&s->pause, 0);
  if (command == SWARF_JOB_CMD_ABORT) atomic_store(&s->abort, 1);
  return 0;
}

int swarf_job_pause_requested(swarf_job *s) {
  return s ? atomic_load(&s->pause) : 0;
}

int swarf_job_abort_requested(swarf_job *s) {
  return s ? atomic_load(&s->abort) : 0;
}
