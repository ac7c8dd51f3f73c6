/* SPDX-License-Identifier: MPL-2.0 */
/* modbus_private.h -- the pieces of the Modbus status service, shared by its
 * files (not used outside tools/modbus_*.c):
 *
 *   modbus_map.c      the register map: snapshot -> registers and flags
 *   modbus_spec.c     endpoint strings ("tcp:HOST:PORT,unit=N", "rtu:...")
 *   modbus_request.c  one request -> the reply or the exception
 *   modbus_tcp.c      the TCP server thread (select, bounded clients)
 *   modbus_rtu.c      the RTU server thread (serial line)
 *   modbus_push.c     the push client thread (writes the block into a controller)
 *   job_observe.c  the simulation side: publishes the snapshot, obeys commands
 *   job_count.c    the pre-count of the program's moves (registers 6-7)
 *
 * Every thread only reads the status snapshot (job.h) and posts commands;
 * none of them is ever waited on by the simulation.
 */
#ifndef SWARF_MODBUS_PRIVATE_H
#define SWARF_MODBUS_PRIVATE_H

#include <stddef.h>
#include <stdint.h>

#include <modbus.h>

#include "job.h"
#include "swarf_sim.h"

/* The register map (tools/doc/modbus.md). */
#define SWARF_MB_NREGS 64      /* input registers 0..63; holding registers 0..63 the same */
#define SWARF_MB_CMD_REG 64    /* holding register: commands */
#define SWARF_MB_NAME_REG 32   /* 32..63: program name, two ASCII bytes each */
#define SWARF_MB_NBITS 7       /* discrete inputs 0..6 */
#define SWARF_MB_MAP_VERSION 2 /* +1 whenever a register is added or changes meaning */

enum {
  SWARF_MB_REG_STATE = 0,
  SWARF_MB_REG_PROGRESS = 1,
  SWARF_MB_REG_LINE = 2,
  SWARF_MB_REG_MOVES_DONE = 4,
  SWARF_MB_REG_MOVES_TOTAL = 6,
  SWARF_MB_REG_REMOVED = 8,
  SWARF_MB_REG_ALARMS = 10,
  SWARF_MB_REG_ERROR = 11,
  SWARF_MB_REG_ELAPSED = 12,
  SWARF_MB_REG_REMAINING = 14,
  SWARF_MB_REG_TOOL = 16,
  SWARF_MB_REG_HEARTBEAT = 17,
  SWARF_MB_REG_FLAGS = 18,
  SWARF_MB_REG_VERSION = 19,
  SWARF_MB_REG_COLLISIONS = 20
};

/* Fill the 64 status registers for the snapshot at monotonic time `now`. */
void swarf_mb_map_registers(const swarf_job_snapshot *s, double now, uint16_t regs[SWARF_MB_NREGS]);
/* Fill the discrete inputs (0 or 1 each). */
void swarf_mb_map_bits(const swarf_job_snapshot *s, uint8_t bits[SWARF_MB_NBITS]);

/* An endpoint given on the command line. */
typedef enum { SWARF_MB_TCP, SWARF_MB_RTU } swarf_mb_kind;

typedef struct {
  swarf_mb_kind kind;
  char host[256], port[16]; /* tcp */
  char device[256];         /* rtu */
  int baud, data_bits, stop_bits;
  char parity;     /* 'N', 'E', 'O' */
  int unit;        /* 1..247 (default 1) */
  int address;     /* push only: first register written in the controller */
  double interval; /* push only: seconds between writes (default 1) */
} swarf_mb_endpoint;

/* Parse an endpoint; `push` accepts address= and interval= (and requires
 * address=). Returns 0, or -1 with what is wrong in msg. */
swarf_status swarf_mb_endpoint_parse(const char *spec, int push, swarf_mb_endpoint *e,
                                     swarf_error *err);

/* Answers requests from the snapshot; one per server thread (it owns its
 * libmodbus mapping). */
typedef struct {
  swarf_job *status;
  modbus_mapping_t *map;
  int unit;
  int tcp;     /* 1: TCP (unit 0 and 255 also accepted), 0: RTU */
  int refused; /* set by each swarf_mb_respond: 1 if the request got an
                  exception or no answer, 0 if a normal reply */
} swarf_mb_responder;

int swarf_mb_responder_init(swarf_mb_responder *r, swarf_job *status, int unit, int tcp);
void swarf_mb_responder_clear(swarf_mb_responder *r);
/* Answer the complete request `req` (`len` bytes, as framed for ctx's
 * backend) on ctx's socket. Returns the bytes sent, 0 when no answer is due,
 * or -1 when sending failed (the caller drops the client). */
int swarf_mb_respond(swarf_mb_responder *r, modbus_t *ctx, const uint8_t *req, int len);

/* Server and client threads. Each _new checks the endpoint, opens it (so
 * that a busy port or a missing device is reported before the job starts)
 * and starts its thread; _free stops the thread and closes everything. */
typedef struct swarf_mb_tcp swarf_mb_tcp;
swarf_status swarf_mb_tcp_new(const swarf_mb_endpoint *e, swarf_job *status, swarf_mb_tcp **out,
                              swarf_error *err);
int swarf_mb_tcp_port(const swarf_mb_tcp *t); /* the port bound (for port 0) */
void swarf_mb_tcp_free(swarf_mb_tcp *t);

typedef struct swarf_mb_rtu swarf_mb_rtu;
swarf_status swarf_mb_rtu_new(const swarf_mb_endpoint *e, swarf_job *status, swarf_mb_rtu **out,
                              swarf_error *err);
void swarf_mb_rtu_free(swarf_mb_rtu *t);

typedef struct swarf_mb_push swarf_mb_push;
swarf_status swarf_mb_push_new(const swarf_mb_endpoint *e, swarf_job *status, swarf_mb_push **out,
                               swarf_error *err);
/* Push once more now (the final state), then stop and free. */
void swarf_mb_push_free(swarf_mb_push *p);

/* The simulation's observer (called from the simulation's progress callback): owns the snapshot
 * it publishes; computes the removed volume at most every half second and
 * never for more than ~2 % of the time. */
typedef struct {
  swarf_job *status;
  swarf_job_snapshot snap;
  double next_volume;
} swarf_job_observer;

void swarf_job_observer_init(swarf_job_observer *ob, swarf_job *status);
int swarf_job_observe(swarf_job_observer *ob, const swarf_sim_progress *p);
/* Publish the end of the run: rc 0 finished, else failed with error rc. */
void swarf_job_observer_final(swarf_job_observer *ob, int rc, const swarf_sim_report *rep);

/* Count the motion moves of the program at `path` in a thread of its own and
 * publish the count (registers 6-7) when done; a program that does not parse
 * leaves it 0. _free stops the count if still running. */
typedef struct swarf_job_count swarf_job_count;
swarf_job_count *swarf_job_count_new(const char *path, swarf_job *status);
void swarf_job_count_free(swarf_job_count *c);

#endif
