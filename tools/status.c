/* status.c -- the status snapshot shared by the simulation and the status
 * services (see status.h). The handle owns its lock and its copy of the
 * snapshot; callers own the snapshots they pass in or read out.
 */
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "status.h"

struct swarf_status {
  pthread_mutex_t lock; /* guards snap, held only for copies */
  swarf_status_snapshot snap;
  atomic_int pause, abort;
};

double swarf_status_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

swarf_status *swarf_status_new(const char *program) {
  swarf_status *s = calloc(1, sizeof *s);
  const char *base = program ? strrchr(program, '/') : NULL;
  if (s == NULL) return NULL;
  pthread_mutex_init(&s->lock, NULL);
  atomic_init(&s->pause, 0);
  atomic_init(&s->abort, 0);
  base = base ? base + 1 : program ? program : "";
  strncpy(s->snap.program, base, SWARF_STATUS_NAME_LEN - 1);
  s->snap.start = swarf_status_now();
  return s;
}

void swarf_status_free(swarf_status *s) {
  if (s == NULL) return;
  pthread_mutex_destroy(&s->lock);
  free(s);
}

/* Under the lock: take the simulation's fields, keep the others'. */
static void merge(swarf_status *s, const swarf_status_snapshot *in) {
  swarf_status_snapshot keep = s->snap;
  s->snap = *in;
  s->snap.moves_total = keep.moves_total;
  s->snap.commands = keep.commands;
  s->snap.last_command = keep.last_command;
  s->snap.heartbeat = keep.heartbeat + 1;
  memcpy(s->snap.program, keep.program, sizeof keep.program);
}

int swarf_status_publish(swarf_status *s, const swarf_status_snapshot *snap) {
  if (s == NULL || snap == NULL || pthread_mutex_trylock(&s->lock) != 0) return 0;
  merge(s, snap);
  pthread_mutex_unlock(&s->lock);
  return 1;
}

void swarf_status_publish_final(swarf_status *s, const swarf_status_snapshot *snap) {
  if (s == NULL || snap == NULL) return;
  pthread_mutex_lock(&s->lock);
  merge(s, snap);
  pthread_mutex_unlock(&s->lock);
}

void swarf_status_set_total(swarf_status *s, long moves_total) {
  if (s == NULL) return;
  pthread_mutex_lock(&s->lock);
  s->snap.moves_total = moves_total;
  pthread_mutex_unlock(&s->lock);
}

void swarf_status_set_commands(swarf_status *s, int enabled) {
  if (s == NULL) return;
  pthread_mutex_lock(&s->lock);
  s->snap.commands = enabled != 0;
  pthread_mutex_unlock(&s->lock);
}

void swarf_status_read(swarf_status *s, swarf_status_snapshot *out) {
  if (s == NULL || out == NULL) return;
  pthread_mutex_lock(&s->lock);
  *out = s->snap;
  pthread_mutex_unlock(&s->lock);
}

int swarf_status_command_post(swarf_status *s, int command) {
  int ok;
  if (s == NULL) return -1;
  pthread_mutex_lock(&s->lock);
  ok = s->snap.commands && command >= SWARF_STATUS_CMD_PAUSE && command <= SWARF_STATUS_CMD_ABORT;
  if (ok) s->snap.last_command = command;
  pthread_mutex_unlock(&s->lock);
  if (!ok) return -1;
  if (command == SWARF_STATUS_CMD_PAUSE) atomic_store(&s->pause, 1);
  if (command == SWARF_STATUS_CMD_RESUME) atomic_store(&s->pause, 0);
  if (command == SWARF_STATUS_CMD_ABORT) atomic_store(&s->abort, 1);
  return 0;
}

int swarf_status_pause_requested(swarf_status *s) {
  return s ? atomic_load(&s->pause) : 0;
}

int swarf_status_abort_requested(swarf_status *s) {
  return s ? atomic_load(&s->abort) : 0;
}
