/* SPDX-License-Identifier: MPL-2.0 */
/* modbus_service.c -- the --modbus options of `swarf simulate` and the life
 * of the status service around one run: open the endpoints, announce them,
 * install the observer, then publish the final state, linger and stop.
 * The service owns the status, the observer, the pre-count and every
 * server and push thread; swarf_modbus_finish frees them all.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "modbus_private.h"
#include "modbus_service.h"

const char swarf_modbus_help[] =
    "\n"
    "Status over Modbus (register map: tools/doc/modbus.md; all off by default):\n"
    "  --modbus tcp:[HOST:]PORT[,unit=N]  serve the status while the job runs (FC 02,\n"
    "                   03, 04); HOST defaults to 127.0.0.1 (give 0.0.0.0 to open it\n"
    "                   to the shop network); PORT 0 picks a free port; unit default 1;\n"
    "                   up to 96 clients; when full, a newcomer replaces a misbehaving,\n"
    "                   unproven or overdue client before any polite poller\n"
    "  --modbus rtu:DEVICE,BAUD,PARITY,DATABITS,STOPBITS[,unit=N]   the same map on a\n"
    "                   serial line, e.g. rtu:/dev/ttyUSB0,19200,E,8,1,unit=3\n"
    "  --modbus-push tcp:HOST:PORT,unit=N,address=A[,interval=S]   write registers\n"
    "                   0..63 into a controller's holding registers A.. every S s\n"
    "                   (default 1) with FC 16\n"
    "  --modbus-linger S  keep serving the final state S seconds after the job\n"
    "  --modbus-commands  accept commands in holding register 64: 1 pause, 2 resume,\n"
    "                   3 abort (exit status 3); without it every write is refused\n"
    "                   with exception 01\n";

struct swarf_modbus_service {
  swarf_job *status;
  swarf_job_observer observer;
  swarf_job_count *count;
  swarf_mb_tcp *tcp[SWARF_MODBUS_MAX_ENDPOINTS];
  swarf_mb_rtu *rtu[SWARF_MODBUS_MAX_ENDPOINTS];
  swarf_mb_push *push[SWARF_MODBUS_MAX_ENDPOINTS];
  double linger;
};

static int option_error(const char *flag, const char *what) {
  fprintf(stderr, "swarf simulate: %s: %s\n(run `swarf simulate --help` for the options)\n", flag,
          what);
  return 2;
}

static int add_endpoint(const char **list, int *n, const char *flag, const char *val, int push) {
  swarf_mb_endpoint e;
  swarf_error err;
  if (*n == SWARF_MODBUS_MAX_ENDPOINTS)
    return option_error(flag, "given too many times (4 at most)");
  swarf_error_init(&err);
  if (swarf_mb_endpoint_parse(val, push, &e, &err) != SWARF_OK)
    return option_error(flag, err.message);
  list[(*n)++] = val;
  return 0;
}

int swarf_modbus_option(swarf_modbus_options *o, const char *flag, const char *val, int *i) {
  char *end;
  if (o == NULL || flag == NULL || strncmp(flag, "--modbus", 8)) return -1;
  o->any_flag = 1;
  if (!strcmp(flag, "--modbus-commands")) return o->commands = 1, 0;
  if (strcmp(flag, "--modbus") && strcmp(flag, "--modbus-push") && strcmp(flag, "--modbus-linger"))
    return -1;
  if (val == NULL) return option_error(flag, "needs a value");
  (*i)++;
  if (!strcmp(flag, "--modbus")) return add_endpoint(o->serve, &o->nserve, flag, val, 0);
  if (!strcmp(flag, "--modbus-push")) return add_endpoint(o->push, &o->npush, flag, val, 1);
  errno = 0;
  o->linger = strtod(val, &end);
  if (end == val || *end || errno || !(o->linger >= 0 && o->linger <= 86400))
    return option_error(flag, "give 0 to 86400 seconds");
  return 0;
}

static void announce(const swarf_mb_endpoint *e, const swarf_mb_tcp *tcp, int push) {
  if (push)
    fprintf(stderr, "swarf: Modbus push to %s:%s unit %d, registers %d..%d every %g s\n", e->host,
            e->port, e->unit, e->address, e->address + SWARF_MB_NREGS - 1, e->interval);
  else if (e->kind == SWARF_MB_TCP)
    fprintf(stderr, "swarf: Modbus TCP server on %s:%d unit %d\n", e->host, swarf_mb_tcp_port(tcp),
            e->unit);
  else
    fprintf(stderr, "swarf: Modbus RTU server on %s (%d %c%d%d) unit %d\n", e->device, e->baud,
            e->parity, e->data_bits, e->stop_bits, e->unit);
}

/* Open the i-th server (push == 0) or push client. */
static swarf_status open_endpoint(swarf_modbus_service *svc, const char *spec, int push, int i,
                                  swarf_error *err) {
  swarf_mb_endpoint e;
  swarf_status st = swarf_mb_endpoint_parse(spec, push, &e, err);
  if (st != SWARF_OK) return st;
  if (push)
    st = swarf_mb_push_new(&e, svc->status, &svc->push[i], err);
  else if (e.kind == SWARF_MB_TCP)
    st = swarf_mb_tcp_new(&e, svc->status, &svc->tcp[i], err);
  else
    st = swarf_mb_rtu_new(&e, svc->status, &svc->rtu[i], err);
  if (st == SWARF_OK) announce(&e, svc->tcp[i], push);
  return st;
}

static void stop_all(swarf_modbus_service *svc) {
  swarf_job_count_free(svc->count);
  for (int i = 0; i < SWARF_MODBUS_MAX_ENDPOINTS; i++) {
    swarf_mb_push_free(svc->push[i]);
    swarf_mb_tcp_free(svc->tcp[i]);
    swarf_mb_rtu_free(svc->rtu[i]);
  }
  swarf_job_free(svc->status);
  free(svc);
}

swarf_status swarf_modbus_start(const swarf_modbus_options *o, const char *program,
                                swarf_modbus_service **out, swarf_error *err) {
  swarf_modbus_service *svc;
  swarf_status st = SWARF_OK;
  *out = NULL;
  if (o == NULL || !o->any_flag) return SWARF_OK;
  if (o->nserve + o->npush == 0)
    return swarf_error_set(err, SWARF_ERR_ARG,
                           "--modbus-linger/--modbus-commands: give --modbus or --modbus-push too");
  if (o->commands && o->nserve == 0)
    return swarf_error_set(err, SWARF_ERR_ARG,
                           "--modbus-commands: commands are written to a --modbus server");
  if ((svc = calloc(1, sizeof *svc)) == NULL || (svc->status = swarf_job_new(program)) == NULL) {
    free(svc);
    return swarf_error_set(err, SWARF_ERR_MEMORY, "out of memory");
  }
  svc->linger = o->linger;
  swarf_job_set_commands(svc->status, o->commands);
  for (int i = 0; i < o->nserve && st == SWARF_OK; i++)
    st = open_endpoint(svc, o->serve[i], 0, i, err);
  for (int i = 0; i < o->npush && st == SWARF_OK; i++)
    st = open_endpoint(svc, o->push[i], 1, i, err);
  if (st != SWARF_OK) {
    stop_all(svc);
    return st;
  }
  swarf_job_observer_init(&svc->observer, svc->status);
  svc->count = swarf_job_count_new(program, svc->status);
  *out = svc;
  return SWARF_OK;
}

int swarf_modbus_observe(swarf_modbus_service *svc, const swarf_sim_progress *p) {
  if (svc == NULL) return 0;
  return swarf_job_observe(&svc->observer, p);
}

int swarf_modbus_aborted(const swarf_modbus_service *svc) {
  return svc != NULL && swarf_job_abort_requested(svc->status);
}

void swarf_modbus_finish(swarf_modbus_service *svc, int rc, const swarf_sim_report *rep) {
  struct timespec left;
  if (svc == NULL) return;
  swarf_job_count_free(svc->count);
  svc->count = NULL;
  if (rc == 0 && rep != NULL) swarf_job_set_total(svc->status, rep->moves);
  swarf_job_observer_final(&svc->observer, rc, rep);
  fflush(stdout);
  left.tv_sec = (time_t)svc->linger;
  left.tv_nsec = (long)((svc->linger - floor(svc->linger)) * 1e9);
  while (nanosleep(&left, &left) != 0 && errno == EINTR) {
  }
  stop_all(svc);
}
