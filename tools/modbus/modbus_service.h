/* SPDX-License-Identifier: MPL-2.0 */
/* modbus_service.h -- the Modbus status service of `swarf simulate`, as the
 * command line sees it: its options, and start/finish around the run.
 *
 * Role: while the simulation runs, it publishes a status snapshot (job.h)
 * from the simulation's progress callback (swarf_modbus_observe); TCP and RTU servers and push
 * clients, each in its own thread, serve that snapshot. The simulation never waits on the network.
 *
 * Ownership: the options are plain values owned by the caller; the service
 * returned by swarf_modbus_start is owned by the caller until
 * swarf_modbus_finish, which frees it. Not thread-safe itself: call both
 * from the thread that runs the simulation.
 */
#ifndef SWARF_MODBUS_SERVICE_H
#define SWARF_MODBUS_SERVICE_H

#include "swarf_sim.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SWARF_MODBUS_MAX_ENDPOINTS 4

typedef struct {
  const char *serve[SWARF_MODBUS_MAX_ENDPOINTS]; /* --modbus specs */
  const char *push[SWARF_MODBUS_MAX_ENDPOINTS];  /* --modbus-push specs */
  int nserve, npush;
  double linger; /* --modbus-linger, seconds */
  int commands;  /* --modbus-commands */
  int any_flag;  /* some --modbus* flag was given */
} swarf_modbus_options;

/* The --help text of the options below. */
extern const char swarf_modbus_help[];

/* If `flag` is one of --modbus, --modbus-push, --modbus-linger,
 * --modbus-commands: record it (advancing *i past its value `val`, which may
 * be NULL) and return 0, or print what is wrong and return 2. Returns -1 for
 * any other flag. Endpoint strings are checked here already. */
int swarf_modbus_option(swarf_modbus_options *o, const char *flag, const char *val, int *i);

typedef struct swarf_modbus_service swarf_modbus_service;

/* Open every endpoint and announce them on stderr. A busy port, a missing
 * device or an option that needs another fills err (its message starts with
 * the option) and returns its status, nothing left open. With no --modbus
 * option, *out is NULL and SWARF_OK returned. */
swarf_status swarf_modbus_start(const swarf_modbus_options *o, const char *program,
                                swarf_modbus_service **out, swarf_error *err);

/* Call from the simulation's progress callback (swarf_sim_callbacks): it
 * publishes the snapshot without waiting, holds while a pause command is
 * on, and returns non-zero when an abort command came. NULL: returns 0. */
int swarf_modbus_observe(swarf_modbus_service *svc, const swarf_sim_progress *p);
/* Whether an abort command stopped the run. */
int swarf_modbus_aborted(const swarf_modbus_service *svc);

/* Publish the final state (run status `rc`: 0 finished, else failed with
 * that error code; `rep` the run's report), keep serving for the linger
 * time, then stop every thread and free the service. NULL is a no-op. */
void swarf_modbus_finish(swarf_modbus_service *svc, int rc, const swarf_sim_report *rep);

#ifdef __cplusplus
}
#endif
#endif
