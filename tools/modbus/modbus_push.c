/* SPDX-License-Identifier: MPL-2.0 */
/* modbus_push.c -- push mode: swarf as a Modbus TCP client that writes the
 * status block (registers 0..63 of the map) into a controller's holding
 * registers at address A, every `interval` seconds, with FC 16.
 *
 * Its own thread does all the I/O (connect and response timeouts 0.5 s), so
 * a controller that is down or slow only delays the next push; a failure is
 * reported once on stderr and the push is retried at the next interval.
 * swarf_mb_push_free pushes the final state once more, then stops. The
 * pusher owns its libmodbus context; the status must outlive it.
 */
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "modbus_private.h"

struct swarf_mb_push {
  pthread_t thread;
  pthread_mutex_t lock; /* guards stop */
  pthread_cond_t wake;
  int stop;
  swarf_job *status;
  swarf_mb_endpoint e;
  modbus_t *ctx;
  int connected, warned;
};

static void warn(struct swarf_mb_push *p, const char *what) {
  if (p->warned) return;
  p->warned = 1;
  fprintf(stderr, "swarf: Modbus push to %s:%s failed: %s; retrying every %g s\n", p->e.host,
          p->e.port, what, p->e.interval);
}

static void push_once(struct swarf_mb_push *p) {
  swarf_job_snapshot s;
  uint16_t regs[SWARF_MB_NREGS];
  if (!p->connected && modbus_connect(p->ctx) != 0) {
    warn(p, modbus_strerror(errno));
    return;
  }
  p->connected = 1;
  swarf_job_read(p->status, &s);
  swarf_mb_map_registers(&s, swarf_job_now(), regs);
  if (modbus_write_registers(p->ctx, p->e.address, SWARF_MB_NREGS, regs) != SWARF_MB_NREGS) {
    warn(p, modbus_strerror(errno));
    modbus_close(p->ctx);
    p->connected = 0;
  }
}

static void *loop(void *arg) {
  struct swarf_mb_push *p = arg;
  pthread_mutex_lock(&p->lock);
  while (!p->stop) {
    struct timespec until;
    pthread_mutex_unlock(&p->lock);
    push_once(p);
    clock_gettime(CLOCK_REALTIME, &until);
    until.tv_sec += (time_t)p->e.interval;
    until.tv_nsec += (long)((p->e.interval - (double)(time_t)p->e.interval) * 1e9);
    if (until.tv_nsec >= 1000000000L) until.tv_sec++, until.tv_nsec -= 1000000000L;
    pthread_mutex_lock(&p->lock);
    while (!p->stop && pthread_cond_timedwait(&p->wake, &p->lock, &until) == 0) {
    }
  }
  pthread_mutex_unlock(&p->lock);
  push_once(p); /* the final state */
  return NULL;
}

swarf_status swarf_mb_push_new(const swarf_mb_endpoint *e, swarf_job *status, swarf_mb_push **out,
                               swarf_error *err) {
  struct swarf_mb_push *p;
  swarf_status st;
  if (out == NULL || e == NULL || status == NULL || e->kind != SWARF_MB_TCP)
    return swarf_error_set(err, SWARF_ERR_ARG, "swarf_mb_push_new: no TCP endpoint");
  *out = NULL;
  if ((p = calloc(1, sizeof *p)) == NULL)
    return swarf_error_set(err, SWARF_ERR_MEMORY, "out of memory");
  p->e = *e;
  p->status = status;
  p->ctx = modbus_new_tcp_pi(e->host, e->port);
  if (p->ctx == NULL) {
    st = swarf_error_set(err, SWARF_ERR_ARG, "--modbus-push: %s:%s: %s", e->host, e->port,
                         modbus_strerror(errno));
    free(p);
    return st;
  }
  modbus_set_slave(p->ctx, e->unit);
  modbus_set_response_timeout(p->ctx, 0, 500000);
  pthread_mutex_init(&p->lock, NULL);
  pthread_cond_init(&p->wake, NULL);
  if (pthread_create(&p->thread, NULL, loop, p) != 0) {
    st = swarf_error_set(err, SWARF_ERR_INTERNAL, "--modbus-push: cannot start the push thread");
    modbus_free(p->ctx);
    free(p);
    return st;
  }
  *out = p;
  return SWARF_OK;
}

void swarf_mb_push_free(swarf_mb_push *p) {
  if (p == NULL) return;
  pthread_mutex_lock(&p->lock);
  p->stop = 1;
  pthread_cond_signal(&p->wake);
  pthread_mutex_unlock(&p->lock);
  pthread_join(p->thread, NULL);
  modbus_close(p->ctx);
  modbus_free(p->ctx);
  pthread_mutex_destroy(&p->lock);
  pthread_cond_destroy(&p->wake);
  free(p);
}
