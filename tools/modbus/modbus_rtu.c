/* SPDX-License-Identifier: MPL-2.0 */
/* modbus_rtu.c -- the Modbus RTU status server on a serial line (RS-485).
 *
 * One thread owns the line: libmodbus frames the requests (3.5-character
 * silence, CRC, the unit filter) with a short indication timeout so that
 * the thread notices when it must stop; bad frames are flushed and
 * forgotten. A serial line has one master, so there are no clients to
 * bound here. The server owns its libmodbus context and the open device;
 * the status must outlive it.
 */
#include <errno.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <modbus-rtu.h>

#include "modbus_private.h"

struct swarf_mb_rtu {
  pthread_t thread;
  atomic_int stop;
  modbus_t *ctx;
  swarf_mb_responder resp;
};

/* The line itself failed (the adapter unplugged, the pty's other end
 * gone): every read fails at once, and the loop spun a core. */
static int line_lost(int e) {
  return e == EIO || e == EBADF || e == ENXIO || e == ENODEV || e == EPIPE || e == ECONNRESET;
}

/* Waits `s` seconds, in slices, or less when stopped. */
static void rest(struct swarf_mb_rtu *t, double s) {
  for (double done = 0; done < s && !atomic_load(&t->stop); done += 0.05) {
    struct timespec ts = {0, 50000000};
    nanosleep(&ts, NULL);
  }
}

/* Reopens a lost line, resting 0.5 s, then twice as long up to 5 s, between
 * tries, until it opens or the server stops. */
static void reopen(struct swarf_mb_rtu *t) {
  double wait = 0.5;
  modbus_close(t->ctx);
  while (!atomic_load(&t->stop)) {
    rest(t, wait);
    if (!atomic_load(&t->stop) && modbus_connect(t->ctx) == 0) return;
    wait = wait * 2 < 5 ? wait * 2 : 5;
  }
}

static void *loop(void *arg) {
  struct swarf_mb_rtu *t = arg;
  uint8_t req[MODBUS_RTU_MAX_ADU_LENGTH];
  while (!atomic_load(&t->stop)) {
    int n = modbus_receive(t->ctx, req);
    if (n > 0) {
      swarf_mb_respond(&t->resp, t->ctx, req, n);
    } else if (n < 0 && line_lost(errno)) {
      reopen(t);
    } else if (n < 0 && errno != ETIMEDOUT) {
      modbus_flush(t->ctx); /* bad CRC, garbage, overrun: start afresh */
    }
  }
  return NULL;
}

swarf_status swarf_mb_rtu_new(const swarf_mb_endpoint *e, swarf_job *status, swarf_mb_rtu **out,
                              swarf_error *err) {
  struct swarf_mb_rtu *t;
  swarf_status st = SWARF_ERR_IO;
  if (out == NULL || e == NULL || status == NULL || e->kind != SWARF_MB_RTU)
    return swarf_error_set(err, SWARF_ERR_ARG, "swarf_mb_rtu_new: no RTU endpoint");
  *out = NULL;
  if ((t = calloc(1, sizeof *t)) == NULL)
    return swarf_error_set(err, SWARF_ERR_MEMORY, "out of memory");
  atomic_init(&t->stop, 0);
  t->ctx = modbus_new_rtu(e->device, e->baud, e->parity, e->data_bits, e->stop_bits);
  if (t->ctx == NULL) {
    st = swarf_error_set(err, SWARF_ERR_ARG, "--modbus: %s: %s", e->device, modbus_strerror(errno));
    goto err;
  }
  modbus_set_slave(t->ctx, e->unit);
  modbus_set_indication_timeout(t->ctx, 0, 200000);
  modbus_set_response_timeout(t->ctx, 0, 1); /* libmodbus sleeps it on errors */
  if (modbus_connect(t->ctx) != 0) {
    st = swarf_error_set(err, SWARF_ERR_OPEN,
                         "--modbus: cannot open %s: %s (is it the right serial device?)", e->device,
                         modbus_strerror(errno));
    goto err;
  }
  if (swarf_mb_responder_init(&t->resp, status, e->unit, 0) ||
      pthread_create(&t->thread, NULL, loop, t)) {
    st = swarf_error_set(err, SWARF_ERR_INTERNAL, "--modbus: cannot start the RTU server");
    modbus_close(t->ctx);
    goto err;
  }
  *out = t;
  return SWARF_OK;
err:
  if (t->ctx) modbus_free(t->ctx);
  swarf_mb_responder_clear(&t->resp);
  free(t);
  return st;
}

void swarf_mb_rtu_free(swarf_mb_rtu *t) {
  if (t == NULL) return;
  atomic_store(&t->stop, 1);
  pthread_join(t->thread, NULL); /* within the indication timeout */
  modbus_close(t->ctx);
  modbus_free(t->ctx);
  swarf_mb_responder_clear(&t->resp);
  free(t);
}
