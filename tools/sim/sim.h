/* sim.h -- the simulation driver: G-code -> motions -> sweeps -> stock.
 *
 * Role: wires the stages for `swarf simulate` (and for the tests, which run
 * the same driver on programs held in memory). It streams the program
 * through the parser, turns each move into a rigid motion, builds the swept
 * volume of the cutter in the spindle and removes batches of them from the
 * stock. It owns the tool table and the report; the caller owns the stock
 * it gets back.
 *
 * Units: mm, seconds. One simulation per thread; the stock uses TBB inside.
 */
#ifndef SWARF_SIM_H
#define SWARF_SIM_H

#include <stddef.h>

#include "engine.h"
#include "stock.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SWARF_SIM_MAX_TOOLS 64
#define SWARF_SIM_MAX_ALARMS 16

typedef struct {
  int number; /* T number */
  swarf_cutter cutter;
} swarf_sim_tool;

typedef struct {
  long lines;          /* program lines read */
  long moves;          /* motion moves (rapid, line, arc) */
  long cutting_moves;  /* moves whose sweep touched the stock's bounds */
  long rapids, arcs;   /* counts among moves */
  long tool_changes;
  double path_mm;      /* tip path length */
  double machining_s;  /* at programmed feeds (rapids at SWARF_RAPID_RATE) */
  double volume_before, volume_after; /* stock volume, mm^3 */
  double seconds;      /* wall time of the run */
  /* Alarms: rapid moves (G0) that cut into material still there when they
   * run (deeper than half a voxel), the first SWARF_SIM_MAX_ALARMS of them
   * with their source line and column. The cut is still made, as the
   * machine would make it. */
  long alarms;
  long alarm_line[SWARF_SIM_MAX_ALARMS];
  int alarm_column[SWARF_SIM_MAX_ALARMS];
} swarf_sim_report;

typedef struct {
  double stock_lo[3], stock_hi[3]; /* box stock, mm (a cylinder: its bounding box) */
  int stock_cylinder;              /* 1: cylinder about axis cyl_axis (0 x, 1 y, 2 z) through
                                    * the origin, radius cyl_radius, from stock_lo to stock_hi
                                    * along the axis */
  int cyl_axis;
  double cyl_radius;
  swarf_machine machine;           /* kinematics (all zero: the xyz machine) */
  double voxel;                    /* voxel edge, mm */
  int half_width;                  /* narrow band, voxels each side (>= 3) */
  swarf_sim_tool tools[SWARF_SIM_MAX_TOOLS];
  int ntools;
  int batch; /* moves removed per stock pass (default 128) */
  /* Benchmark baseline only: when > 0, each move is not swept exactly but
   * stamped, i.e. the cutter is placed at poses spaced stamp_step mm apart
   * along the path, as stamping simulators do. */
  double stamp_step;
  /* Called now and then with the fraction of the program read (0..1). */
  void (*progress)(void *ctx, double fraction, long moves);
  void *progress_ctx;
  /* Called after every motion move with the report so far, the move's
   * source line, the tool in the spindle (0: none) and the stock as of the
   * last pass. A non-zero return stops the run (status 3, "aborted"). It
   * runs in the simulation's thread: it must not block (tools/modbus/job.h). */
  int (*observe)(void *ctx, const swarf_sim_report *sofar, long line, int tool,
                 const swarf_stock *stock);
  void *observe_ctx;
} swarf_sim_config;

/* Parse a tool specification "T<n>=<shape>,D<diameter>[,R<corner>][,L<length>]"
 * (shape: ball, flat, bull). Returns 0, or -1 with a reason in msg. */
int swarf_sim_parse_tool(const char *spec, swarf_sim_tool *out, char *msg, size_t msglen);

/* Parse "box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX". Returns 0 or -1 with a reason. */
int swarf_sim_parse_box(const char *spec, double lo[3], double hi[3], char *msg, size_t msglen);

/* Parse a --stock value, box:... or cylinder:AXIS,RADIUS,START,END (AXIS x, y
 * or z), into the stock fields of cfg. Returns 0 or -1 with a reason. */
int swarf_sim_parse_stock(const char *spec, swarf_sim_config *cfg, char *msg, size_t msglen);

/* Run the program at `path` (or, with swarf_sim_run_text, the `len` bytes of
 * `text`, named `name` in messages). On success returns 0 and *out is a new
 * stock owned by the caller. On failure returns 2 for bad input (msg holds
 * "file:line:col: what is wrong"), 1 for an internal failure or 3 when the
 * observer stopped it; *out is NULL. */
int swarf_sim_run(const swarf_sim_config *cfg, const char *path, swarf_stock **out,
                  swarf_sim_report *rep, char *msg, size_t msglen);
int swarf_sim_run_text(const swarf_sim_config *cfg, const char *name, const char *text,
                       size_t len, swarf_stock **out, swarf_sim_report *rep, char *msg,
                       size_t msglen);

#ifdef __cplusplus
}
#endif
#endif
