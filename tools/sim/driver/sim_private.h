/* SPDX-License-Identifier: MPL-2.0 */
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
  int unknown_tool;           /* Fanuc/Haas: the T loaded that was not given (0: none) */
  long unknown_line;          /* and the line of its change */
  swarf_sim_state state;
  swarf_error err;
  swarf_sim_report rep;
  swarf_alarm *alarms; /* every alarm, up to SWARF_SIM_KEPT_ALARMS */
  long nalarms, alarms_cap;
  double t0;       /* monotonic seconds at new */
  double fraction; /* of the file read; < 0 unknown */
  long long size;  /* the program's bytes (swarf_sim_set_program_size, feed_file); 0 unknown */
  /* batch: motions, their sweeps and cuts, removed in one pass */
  swarf_motion *motions;
  swarf_sweep *sweeps;
  swarf_stock_cut *cuts;
  swarf_stock_support_fn *supports; /* per cut: its supporting planes, or NULL (stamps) */
  swarf_sim_stamp *stamps;
  int n, cap;
  double blocks;               /* batch: the stock blocks its cuts' bounds span (estimate) */
  double pad_lo[3], pad_hi[3]; /* material box grown by the narrow band */
  double mat_lo[3], mat_hi[3]; /* material box: the spec's, or the stock's active voxels */
  /* per-line results: the open line and the closed ones not yet told */
  swarf_line_result cur;
  swarf_line_result *pending;
  int npending, pending_cap;
  swarf_sim_collide col; /* collisions (collide.c) */
  int moved;             /* a motion move was seen (the start position is the tip's) */
  long cur_id;           /* lines opened so far: cur's id; pending[i]'s is cur_id - npending + i */
  long *cut_id;          /* batch: the line each cut belongs to (measured removal) */
  swarf_stock_cut_effect *effects; /* batch: what each cut did (measured removal) */
  int measured;                    /* removal measures each cut (line volumes or a design) */
  int volumes;           /* the measured removal gives each cut's volume (lines report them) */
  double tolerance;      /* gouges deeper than this, mm */
  swarf_stock *initial;  /* the stock before the run, for the design comparison */
  swarf_sim_frame frame; /* the workpiece frame (setup.c) */
  int units_checked;     /* the first move was checked for a units word */
  /* slabs (mpi/slab.c): the index box's blocks, nb[k] a side from blo; columns
   * across ax[0], ax[1] */
  int planned;    /* the slabs are planned (several processes or a tally) */
  int slab_build; /* the stock is a shell built from cfg.stock: its slab is built at the plan */
  int blo[3], nb[3], ax[2];
  int index_lo[3], index_hi[3]; /* the stock's index box */
  double *work;                 /* estimated work per column (the survey's) */
  unsigned long long *tally;    /* cuts visiting each block (cfg.tally) */
  swarf_sim *surveyor;          /* non-NULL: this is a survey handle feeding it */
  int abort_pending;            /* a progress callback asked to stop (several processes) */
};

/* slab.c. Return 0, or 1 after swarf_sim_fail. */
int swarf_sim_slabs(const swarf_sim *s);                 /* 1 with several processes */
int swarf_sim_slab_plan(swarf_sim *s, const char *path); /* path NULL: even slabs */
/* The stock's slab [lo, hi] (index box) built from cfg.stock in place of the
 * shell (sim.c; slab_build); 0 or 1 on failure (s's error set). */
int swarf_sim_slab_stock(swarf_sim *s, const int lo[3], const int hi[3]);
void swarf_sim_slab_clear(swarf_sim *s);
/* A survey handle's cut: its estimated work added to the surveyor's slabs. */
void swarf_sim_slab_survey(swarf_sim *s, const swarf_stock_cut *c);
/* A query's hit on this process's slab made global: the first in the
 * stock's scan order among all processes'. */
int swarf_sim_slab_hit(swarf_sim *s, int *hit, double where[3]);
/* The batch's measured effects summed (volumes) and maxed (gouges). */
int swarf_sim_slab_effects(swarf_sim *s, swarf_stock_cut_effect *e, int n);
/* At each batch: a stop asked on any process stops all. */
int swarf_sim_slab_sync(swarf_sim *s);
/* At finish: the slabs gathered into rank 0's stock. */
int swarf_sim_slab_merge(swarf_sim *s);

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
/* A feed move with no tool in the spindle: SWARF_ALARM_NO_TOOL if it runs
 * into the material (batch.c). 1 after a failure. */
int swarf_sim_batch_check_empty(swarf_sim *s, const swarf_motion *m);
int swarf_sim_batch_flush(swarf_sim *s);
/* An alarm: counted in the report (the first SWARF_SIM_MAX_ALARMS kept) and told. */
void swarf_sim_raise(swarf_sim *s, const swarf_alarm *a);

/* setup.c: the machine's setup on the parser and the start (from new), the
 * moves into the workpiece frame, the first move's units check. Return
 * SWARF_OK or the status, with err filled. */
swarf_status swarf_sim_setup(swarf_sim *s, swarf_error *err);
void swarf_sim_to_workpiece(const swarf_sim *s, const swarf_move *in, swarf_move *out);
void swarf_sim_check_units(swarf_sim *s, const swarf_move *mv);
/* The design: checked against the stock and the initial stock kept (new);
 * the comparison (finish). */
swarf_status swarf_sim_design_init(swarf_sim *s, swarf_error *err);
swarf_status swarf_sim_design_compare(swarf_sim *s);

/* lines.c: count a motion in its line; tell the closed lines (all, at the end). */
int swarf_sim_lines_add(swarf_sim *s, const swarf_motion *m, int tool);
int swarf_sim_lines_flush(swarf_sim *s, int at_end);
/* Add what a removed cut of line `id` did to that line's result. */
void swarf_sim_lines_removed(swarf_sim *s, long id, double removed);

/* collide.c: init after the stock (fixtures as level sets), clear; check a
 * motion's shank, holder and fixtures (w: its cutter sweep, own: its cut when
 * queued, NULL otherwise). Return 0, or 1 after swarf_sim_fail. */
int swarf_sim_collide_init(swarf_sim *s);
void swarf_sim_collide_clear(swarf_sim *s);
int swarf_sim_collide_move(swarf_sim *s, const swarf_motion *m, const swarf_sweep *w,
                           const swarf_stock_cut *own);

#endif
