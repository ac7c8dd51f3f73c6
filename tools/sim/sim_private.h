/* sim_private.h -- the simulation handle's insides, shared by sim.c (the
 * calls), batch.c (queued sweeps, removal passes, rapid alarms) and lines.c
 * (per-line results). Not installed.
 */
#ifndef SWARF_SIM_PRIVATE_H
#define SWARF_SIM_PRIVATE_H

#include "assembly.h"
#include "gcode.h"
#include "move_motion.h"
#include "swarf_sim.h"

/* A move stamped at n + 1 evenly spaced poses (the benchmark baseline). */
typedef struct {
  const swarf_cutter *cutter;
  const swarf_motion *motion;
  int n;
} swarf_sim_stamp;

typedef enum { SIM_OPEN = 0, SIM_FINISHED, SIM_FAILED, SIM_TAKEN } swarf_sim_state;

struct swarf_sim {
  swarf_sim_config cfg; /* a copy: the caller's may go away */
  char name[256];
  swarf_gcode_parser *parser;
  swarf_stock *stock;
  const swarf_sim_tool *tool; /* in the spindle, NULL when empty */
  swarf_sim_state state;
  swarf_error err;
  swarf_sim_report rep;
  double t0;       /* monotonic seconds at new */
  double fraction; /* of the file read; < 0 unknown */
  /* batch: motions, their sweeps and cuts, removed in one pass */
  swarf_motion *motions;
  swarf_sweep *sweeps;
  swarf_stock_cut *cuts;
  swarf_sim_stamp *stamps;
  int n, cap;
  double pad_lo[3], pad_hi[3]; /* material box grown by the narrow band */
  /* per-line results: the open line and the closed ones not yet told */
  swarf_line_result cur;
  swarf_line_result *pending;
  int npending, pending_cap;
  swarf_sim_collide col; /* collisions (collide.c) */
  int moved;             /* a motion move was seen (the start position is the tip's) */
};

/* Record the first failure (status, place, message) and return its status. */
swarf_status swarf_sim_fail(swarf_sim *s, swarf_status st, long line, int column, const char *fmt,
                            ...)
#ifdef __GNUC__
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* batch.c. Return 0, or 1 after swarf_sim_fail. */
int swarf_sim_batch_init(swarf_sim *s);
void swarf_sim_batch_clear(swarf_sim *s);
int swarf_sim_batch_queue(swarf_sim *s, const swarf_motion *m);
int swarf_sim_batch_flush(swarf_sim *s);
/* An alarm: counted in the report (the first SWARF_SIM_MAX_ALARMS kept) and told. */
void swarf_sim_raise(swarf_sim *s, const swarf_alarm *a);

/* lines.c: count a motion in its line; tell the closed lines (all, at the end). */
int swarf_sim_lines_add(swarf_sim *s, const swarf_motion *m, int tool);
int swarf_sim_lines_flush(swarf_sim *s, int at_end);

/* collide.c: init after the stock (fixtures as level sets), clear; check a
 * motion's shank, holder and fixtures (w: its cutter sweep, own: its cut when
 * queued, NULL otherwise). Return 0, or 1 after swarf_sim_fail. */
int swarf_sim_collide_init(swarf_sim *s);
void swarf_sim_collide_clear(swarf_sim *s);
int swarf_sim_collide_move(swarf_sim *s, const swarf_motion *m, const swarf_sweep *w,
                           const swarf_stock_cut *own);

#endif
