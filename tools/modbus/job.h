/* SPDX-License-Identifier: MPL-2.0 */
/* job.h -- the job's status snapshot, published by the simulation and read
 * by the status services (Modbus server, RTU server, push client).
 *
 * Role: the one place where the simulation thread and the network threads
 * meet. The simulation publishes with swarf_job_publish, which never
 * waits: it takes a tiny lock with trylock and, when a reader holds it (for a
 * copy of a few hundred bytes, never across I/O), skips that publication (the
 * next move publishes again). Readers copy the whole snapshot under the lock.
 * Commands (pause, resume, abort) travel the other way as atomics.
 *
 * Thread-safety: every function may be called from any thread once the
 * handle exists; swarf_job_new/free are not concurrent with anything.
 * Units: seconds (monotonic clock), mm^3.
 */
#ifndef SWARF_JOB_H
#define SWARF_JOB_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  SWARF_JOB_IDLE = 0,
  SWARF_JOB_RUNNING = 1,
  SWARF_JOB_FINISHED = 2,
  SWARF_JOB_FAILED = 3
} swarf_job_state;

/* Error codes (register 11); the first three match the exit status. */
typedef enum {
  SWARF_JOB_OK = 0,
  SWARF_JOB_ERR_INTERNAL = 1, /* I/O, memory */
  SWARF_JOB_ERR_INPUT = 2,    /* bad G-code or tool table */
  SWARF_JOB_ERR_ABORTED = 3   /* aborted by a Modbus command */
} swarf_job_error;

/* Commands (holding register 64). */
typedef enum {
  SWARF_JOB_CMD_NONE = 0,
  SWARF_JOB_CMD_PAUSE = 1,
  SWARF_JOB_CMD_RESUME = 2,
  SWARF_JOB_CMD_ABORT = 3
} swarf_job_command;

#define SWARF_JOB_NAME_LEN 64 /* program name bytes, NUL padded */

typedef struct {
  int state;               /* swarf_job_state */
  int error;               /* swarf_job_error */
  int paused;              /* 1 while a pause command holds the simulation */
  int commands;            /* 1 when writes of commands are accepted */
  long line;               /* source line of the current move (final: lines read) */
  long moves_done;         /* motion moves done */
  long moves_total;        /* motion moves in the program, 0 while unknown */
  double removed;          /* mm^3 removed so far (refreshed now and then) */
  long alarms;             /* alarms raised by the simulation */
  long collisions;         /* among them: shank, holder and fixture collisions */
  int tool;                /* tool in the spindle, 0 none */
  unsigned long heartbeat; /* publications so far */
  double start, end;       /* monotonic seconds; end 0 while not ended */
  int last_command;        /* last command accepted */
  char program[SWARF_JOB_NAME_LEN];
} swarf_job_snapshot;

typedef struct swarf_job swarf_job;

/* A new status, idle, for `program` (its base name is kept). NULL when out
 * of memory. The caller owns it and frees it after every reader stopped. */
swarf_job *swarf_job_new(const char *program);
void swarf_job_free(swarf_job *s);

/* Simulation side: copy *snap in unless a reader holds the lock (never
 * waits). Keeps moves_total, commands and last_command, which belong to
 * other writers; bumps the heartbeat. Returns 1 if published. */
int swarf_job_publish(swarf_job *s, const swarf_job_snapshot *snap);
/* The same, waiting for the lock (bounded by a reader's copy): for the
 * final state, which must not be skipped. */
void swarf_job_publish_final(swarf_job *s, const swarf_job_snapshot *snap);
/* Moves in the program, once a pre-count knows them. */
void swarf_job_set_total(swarf_job *s, long moves_total);
void swarf_job_set_commands(swarf_job *s, int enabled);

/* Reader side: a consistent copy. */
void swarf_job_read(swarf_job *s, swarf_job_snapshot *out);

/* Command side (network threads): returns 0, or -1 if commands are off or
 * the value is not a command. The simulation polls them below. */
int swarf_job_command_post(swarf_job *s, int command);
int swarf_job_pause_requested(swarf_job *s);
int swarf_job_abort_requested(swarf_job *s);

double swarf_job_now(void); /* monotonic seconds */

#ifdef __cplusplus
}
#endif
#endif
