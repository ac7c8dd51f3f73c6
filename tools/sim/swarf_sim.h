/* SPDX-License-Identifier: MPL-2.0 */
/* swarf_sim.h -- libswarf's simulation: a streaming handle from program text
 * (or rigid motions) to the remaining stock.
 *
 * Role: wires the stages. Program text streams through the G-code
 * interpreter, each move becomes a rigid motion of the cutter on the
 * configured machine, its exact swept volume is built and removed from the
 * stock in batches. The handle knows nothing of command-line flags, exit
 * codes, terminals or Modbus: those are its clients' (tools/cli, tools/modbus).
 *
 * Shape (cmark's streaming parser, libmodbus's opaque handle):
 *
 *   swarf_sim_config *cfg = swarf_sim_config_new();  defaults: xyz, 0.2 mm voxel, band 3
 *   ... stock, tools, callbacks ...
 *   swarf_sim *sim;
 *   swarf_error err;
 *   if (swarf_sim_new(cfg, "part.ngc", &sim, &err) != SWARF_OK) ...
 *   swarf_sim_config_free(cfg);               the handle keeps its own copy
 *   swarf_sim_feed(sim, text, len);           any number of times, any split
 *   swarf_sim_finish(sim);                    last line, last batch, final report
 *   swarf_stock *stock = swarf_sim_take_stock(sim);   now the caller's
 *   swarf_sim_free(sim);
 *
 * Every call returns a swarf_status. After a failure the handle refuses
 * further input (SWARF_ERR_STATE) and swarf_sim_error says what and where
 * (file:line:column for G-code). Memory is bounded by the batch, not by the
 * program. Callbacks run in the caller's thread, inside feed/finish/
 * add_motion; they must not call back into the same handle.
 *
 * Units: mm, radians, seconds (G-code's inches and degrees are converted by
 * the interpreter). Thread safety: one thread at a time per handle; distinct
 * handles are independent; removal runs on TBB's threads inside.
 */
#ifndef SWARF_SIM_H
#define SWARF_SIM_H

#include <stddef.h>

#include "engine.h"
#include "gcode.h"
#include "stock.h"
#include "swarf_status.h"
#include "toolpath.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SWARF_SIM_MAX_TOOLS 64
#define SWARF_SIM_MAX_ALARMS 16 /* alarms kept in the report; all go to the callback */

/* ---- Configuration -------------------------------------------------------- */

#define SWARF_SIM_MAX_HOLDER 8 /* cylinders and cones of a holder */
#define SWARF_SIM_MAX_FIXTURES 16

/* One piece of a holder: a cylinder (d0 == d1) or a cone frustum from
 * diameter d0 at its bottom to d1 at its top, `height` tall (mm). */
typedef struct {
  double d0, d1, height;
} swarf_sim_holder_part;

/* A tool in the tool table: the cutter and, when stickout > 0, the assembly
 * above its flutes, all bodies of revolution about the tool axis:
 *   z in [0, L]:         the cutter (cutter.length = L, the flute length)
 *   z in [L, S]:         the shank, diameter `shank` (0: the cutter's D)
 *   z from S upward:     the holder's pieces, stacked, the first on the
 *                        holder face at z = S (the stick-out)
 * Shank and holder never cut; entering material is a collision (SHANK,
 * HOLDER alarms). With stickout 0 nothing above the flutes is modelled. */
typedef struct {
  int number;          /* T number, >= 1 */
  swarf_cutter cutter; /* the cutting body (engine.h); diameter 0: none (a table entry
                        * without a diameter: cutting with it is an error) */
  double length;       /* G43 length offset, mm; 0: the controlled point is the tip */
  double stickout;     /* S, tip to holder face, mm; 0: no shank or holder modelled */
  double shank;        /* N, shank diameter, mm; 0: the cutter's diameter */
  int nholder;         /* pieces of the holder; 0: none */
  swarf_sim_holder_part holder[SWARF_SIM_MAX_HOLDER];
} swarf_sim_tool;

/* A body no part of the tool may enter, cutter included (a vice, a clamp):
 * an axis-aligned box in the workpiece frame, mm, or a closed STL mesh in
 * that frame (read at the stock's voxel by swarf_sim_new; lo and hi are then
 * its bounds, set by the handle). */
typedef struct {
  double lo[3], hi[3];
  const char *stl; /* NULL: the box; else the mesh's path, borrowed until swarf_sim_new
                    * returns */
} swarf_sim_fixture;

typedef enum {
  SWARF_SIM_STOCK_BOX = 0, /* lo..hi */
  SWARF_SIM_STOCK_CYLINDER /* about axis (0 x, 1 y, 2 z) through the origin, radius,
                            * from lo[axis] to hi[axis] along it */
} swarf_sim_stock_kind;

typedef struct {
  swarf_sim_stock_kind kind;
  double lo[3], hi[3]; /* the box, or the cylinder's bounding box, mm */
  int axis;
  double radius;
} swarf_sim_stock_spec;

typedef struct swarf_sim swarf_sim;
typedef struct swarf_sim_report swarf_sim_report;

/* What happens on a tool's way that a machinist must hear about. The cut is
 * still made as the machine would make it. */
typedef enum {
  SWARF_ALARM_RAPID = 0, /* a rapid (G0) cuts into material still there */
  SWARF_ALARM_SHANK,     /* the shank enters material (non-cutting part) */
  SWARF_ALARM_HOLDER,    /* the holder enters material */
  SWARF_ALARM_FIXTURE,   /* any part of the tool enters a fixture */
  SWARF_ALARM_GOUGE,     /* material removed inside the design */
  SWARF_ALARM_NO_TOOL    /* a feed move runs into material with an empty spindle (T0 M6) */
} swarf_alarm_kind;
#define SWARF_ALARM_KINDS 6

typedef struct {
  swarf_alarm_kind kind;
  long line;    /* source line of the move, 1-based */
  int column;   /* source column of its motion word */
  int tool;     /* T number in the spindle */
  double depth; /* mm, deepest penetration found (NaN when not measured) */
  double at[3]; /* mm, workpiece frame: where (NaN when not measured) */
  int index;    /* FIXTURE: which fixture (1-based); 0 otherwise */
  int part;     /* FIXTURE: the part that entered it: 0 cutter, 1 shank, 2 holder;
                 * SHANK 1, HOLDER 2; 0 otherwise */
} swarf_alarm;

/* Progress, after every motion move (and after each chunk of a file), and
 * within a long removal pass (pass >= 0). */
typedef struct {
  double fraction;                /* of the program read, 0..1; < 0 while unknown */
  long line;                      /* source line of the move */
  int tool;                       /* T number in the spindle, 0 none */
  const swarf_sim_report *report; /* counts so far */
  const swarf_stock *stock;       /* the stock as of the last removal pass (read only) */
  double pass; /* during a removal pass (at least every cfg.tick s, so a long move
                * does not hold progress still): the fraction of it done, 0..1,
                * line: its last move's; -1 after a move */
} swarf_sim_progress;

/* Per source line that moved the tool, in program order, once its moves have
 * been removed from the stock (so it may lag the feed by a batch). */
typedef struct {
  long line;
  int tool;
  long moves;
  double time_s;  /* at programmed feeds */
  double path_mm; /* tip path */
  double removed; /* mm^3 this line removed from the stock as it stood; NaN unless
                   * cfg.line_volumes */
} swarf_line_result;

typedef struct {
  /* Non-zero return stops the run: the call returns SWARF_ERR_ABORTED. Must
   * not block for long (the Modbus pause is the one wait, on its own flag). */
  int (*progress)(void *user, const swarf_sim_progress *p);
  void (*alarm)(void *user, const swarf_alarm *a);
  void (*line)(void *user, const swarf_line_result *r);
  void *user;
  /* What the G-code front end accepted without acting on it (a vendor M
   * code, a grbl `$` line, a probe move that found nothing): gcode.h's
   * notes, with the program line and column. NULL: none. */
  void (*note)(void *user, long line, int column, const char *text);
  /* Each canonical move as the simulation cuts it: in the workpiece frame,
   * at the tip of the tool in the spindle (arcs with their centre and
   * normal there), before it is cut. NULL: none. */
  void (*move)(void *user, const swarf_move *m);
} swarf_sim_callbacks;

/* Several processes on one stock (MPI ranks: the CLI's cli_mpi.c; any
 * transport will do). Every process runs the same handle on the same
 * program and input; the stock's index space is cut into slabs, one a
 * process, balanced by the work each will do (a first pass over the
 * program estimates it, feed_file only; text fed directly gets slabs of
 * equal size). Each removes in its slab only; the queries that read the
 * stock (rapid and collision alarms) and the measured removals (line
 * volumes, gouges) are combined at once, so every process raises the same
 * alarms in program order; finish gathers the slabs into rank 0's stock,
 * which is then the one-process grid voxel for voxel, with the same report.
 * The other ranks' stocks hold their slab only: write rank 0's. A progress
 * callback asking to stop is obeyed at the next batch, on every rank.
 * A transport failure ends the run (SWARF_ERR_INTERNAL). */
typedef struct {
  int rank, size; /* this process, 0..size-1; size 1: one process (no calls) */
  /* Every process calls it with its n bytes; recv (size * n bytes) gets all
   * of them in rank order. 0 on success. */
  int (*allgather)(void *user, const void *send, size_t n, void *recv);
  /* Every process calls it with its n bytes (n may differ); on rank 0, take
   * gets each other rank's bytes in rank order (a non-zero return stops).
   * 0 on success, on every rank. */
  int (*gather)(void *user, const void *send, size_t n,
                int (*take)(void *ctx, int rank, const void *buf, size_t n), void *ctx);
  void *user;
} swarf_sim_comm;

typedef struct {
  swarf_machine machine;      /* kinematics (toolpath.h); zero: xyz */
  swarf_sim_stock_spec stock; /* the initial stock, unless swarf_sim_new_with_stock */
  double voxel;               /* voxel edge, mm */
  int half_width;             /* narrow band, voxels each side (>= 3) */
  int batch;                  /* moves removed per stock pass (default 1024) */
  swarf_sim_tool tools[SWARF_SIM_MAX_TOOLS];
  int ntools;       /* one tool: loaded at the start; more: T<n> M6 selects */
  int line_volumes; /* 1: measure each line's removed volume (swarf_line_result) */
  swarf_sim_fixture fixtures[SWARF_SIM_MAX_FIXTURES];
  int nfixtures; /* fixtures (FIXTURE alarms, index 1-based in this order) */
  /* Measure the depth (a bisection: ~8 passes over the part's blocks) of the
   * first N collisions of each kind only, the later ones get NaN; 0: all. */
  long collision_depths;
  /* Benchmark baseline only: when > 0 each move is not swept exactly but
   * stamped at poses stamp_step mm apart, as stamping simulators do. */
  double stamp_step;
  swarf_sim_callbacks cb;
  /* The machine's setup. The workpiece frame (the stock's, the design's,
   * the motions', the report's) is G54's as set up here before the program
   * runs: machine = Rz(G54 rotation) workpiece + G54 origin. Zero values: a
   * metric machine, no offsets, the tool at X0 Y0 at a safe height. */
  int units;                /* swarf_gcode_units: the machine's length unit (programs
                             * without G20/G21 run in it; offsets_file holds it); 0: mm */
  const char *offsets_file; /* LinuxCNC parameter file (gcode.h), read by new (borrowed
                             * until it returns); NULL: none */
  int g54_set;              /* 1: G54's origin is g54 (after offsets_file) */
  double g54[3];            /* mm, machine frame */
  int start_set;            /* 1: the tool tip starts at start; 0: X0 Y0, Z
                             * SWARF_SIM_CLEARANCE above the stock (a rotary machine:
                             * above the stock's sphere about the pivot) */
  double start[3];          /* mm, workpiece frame */
  /* How the program is read (gcode.h): its dialect (swarf_gcode_dialect,
   * 0: LinuxCNC), the block delete switch (1: `/` blocks are skipped), the
   * directories where `o<name> call` finds <name>.ngc (':'-separated,
   * borrowed until new returns; NULL: none), and whether the text is a
   * fragment (1: it need not end; 0: a LinuxCNC program must end with M2,
   * M30 or a closing `%`, as rs274 requires: swarf_gcode_parser_set_fragment). */
  int dialect;
  int block_delete;
  const char *subroutine_path;
  int fragment;
  long work_limit; /* the bound on work (swarf_gcode_parser_set_work_limit); 0: the default */
  /* The part as designed (a level set, stock.h): each move that removes
   * material deeper than `tolerance` inside it raises SWARF_ALARM_GOUGE
   * (depth: that move's deepest, as measured against the stock as it stood,
   * so a gouge is the first move's that cut into the design), and finish
   * compares the result with it (report.deviation). Borrowed: it must
   * outlive the handle. NULL: none. */
  const swarf_stock *design;
  double tolerance; /* mm; <= 0: half the stock's voxel */
  /* Threads the stock passes run on (swarf_stock_set_threads): 0 all cores. */
  int threads;
  /* Seconds between progress calls during a removal pass (0: 0.25; < 0: after
   * every chunk of blocks). */
  double tick;
  const swarf_sim_comm *comm; /* several processes (borrowed; must outlive the handle);
                               * NULL: one */
  int tally;                  /* 1: plan slabs and count the blocks removal visits in each, for
                               * swarf_sim_balance (one process) */
} swarf_sim_config;

/* How far above the stock the tool starts by default, mm. */
#define SWARF_SIM_CLEARANCE 10.0

/* Defaults: xyz machine, 0.2 mm voxel, band 3, batch 1024, no tools, no stock
 * (a stock or an existing stock handle must be given). */
SWARF_API void swarf_sim_config_init(swarf_sim_config *cfg);
/* The workpiece frame of a machine's setup: machine = Rz(rot) workpiece +
 * origin (G54 as set up; XYZ, mm). */
typedef struct {
  double origin[3], cos_rot, sin_rot;
} swarf_sim_frame;

/* The machine's setup exactly as swarf_sim_new makes it, on a parser of the
 * caller's (`swarf parse` lists the moves in the frame `swarf simulate` cuts
 * in): cfg's length unit, offsets file and G54, its tools as the parser's
 * tool table when it has any (their G43 lengths), then the start, start_w
 * (the tool tip in the workpiece frame, mm; NULL: the machine's 0,0,0).
 * *frame gets the workpiece frame. Call before the parser's first feed. */
SWARF_API swarf_status swarf_sim_setup_parser(const swarf_sim_config *cfg,
                                              swarf_gcode_parser *parser, const double start_w[3],
                                              swarf_sim_frame *frame, swarf_error *err);
/* A machine point (XYZ, mm) in the workpiece frame. */
SWARF_API void swarf_sim_frame_point(const swarf_sim_frame *frame, const double m[3], double w[3]);

/* A config on the heap, initialised as swarf_sim_config_init does (the
 * struct is over half a megabyte: too big for a small thread's stack).
 * NULL when out of memory. Free it with swarf_sim_config_free (NULL is
 * fine); swarf_sim_new copies what it needs, so it may be freed after. */
SWARF_API swarf_sim_config *swarf_sim_config_new(void);

/* What a run of cfg may take, checked before any work (swarf_sim_new does it
 * too): voxel, band and batch in range; with stock_from_spec (the stock is
 * cfg's box or cylinder), the voxel against the stock's smallest side and
 * the grid of its surface against the memory this process can have (80 % of
 * the machine's, or of ulimit -v), with a voxel that fits in the message;
 * threads against an address-space limit. SWARF_ERR_ARG or SWARF_ERR_LIMIT
 * with what to give instead. */
SWARF_API swarf_status swarf_sim_config_check(const swarf_sim_config *cfg, int stock_from_spec,
                                              swarf_error *err);
SWARF_API void swarf_sim_config_free(swarf_sim_config *cfg);

/* Adds a tool; SWARF_ERR_ARG when the table is full or the number is taken. */
SWARF_API swarf_status swarf_sim_config_add_tool(swarf_sim_config *cfg, const swarf_sim_tool *t,
                                                 swarf_error *err);

/* ---- The run -------------------------------------------------------------- */

/* A new simulation of a program called `name` (used in messages; not
 * opened). It builds the stock from cfg->stock. The config is copied: the
 * caller may free it. On failure *out is NULL and err (may be NULL) says why. */
SWARF_API swarf_status swarf_sim_new(const swarf_sim_config *cfg, const char *name, swarf_sim **out,
                                     swarf_error *err);

/* The same on an existing stock (a .vdb read back, an earlier run's result):
 * the handle takes ownership of `stock` in every case (freed on failure). Its
 * voxel size wins over cfg->voxel. */
SWARF_API swarf_status swarf_sim_new_with_stock(const swarf_sim_config *cfg, const char *name,
                                                swarf_stock *stock, swarf_sim **out,
                                                swarf_error *err);

/* The program's size in bytes, when it is fed as text and known (0:
 * unknown): progress then gives the fraction read after every move, as it
 * does for swarf_sim_feed_file. */
SWARF_API swarf_status swarf_sim_set_program_size(swarf_sim *sim, long long bytes);

/* Feed `len` bytes of program text. Complete lines run at once. */
SWARF_API swarf_status swarf_sim_feed(swarf_sim *sim, const char *text, size_t len);

/* Feed the whole file at `path` in chunks (progress has a fraction then).
 * Does not finish. */
SWARF_API swarf_status swarf_sim_feed_file(swarf_sim *sim, const char *path);

/* Add a rigid motion directly (toolpath.h, workpiece frame), without G-code:
 * cut with tool m->tool (which must be in the table) and with the same
 * alarms and accounting as a program's moves. */
SWARF_API swarf_status swarf_sim_add_motion(swarf_sim *sim, const swarf_motion *m);

/* End the program: the last unterminated line, the last batch, the final
 * report (volume after). Further feeds get SWARF_ERR_STATE. */
SWARF_API swarf_status swarf_sim_finish(swarf_sim *sim);

/* What and where the last failure was (status SWARF_OK if none). Owned by
 * the handle. */
SWARF_API const swarf_error *swarf_sim_error(const swarf_sim *sim);

/* Counts so far (final after finish). Owned by the handle. */
struct swarf_sim_report {
  long lines;         /* program lines read */
  long moves;         /* motion moves (rapid, line, arc) */
  long cutting_moves; /* moves whose sweep touched the stock's bounds */
  long rapids, arcs;  /* counts among moves */
  long tool_changes;
  double path_mm;                          /* tip path length */
  double machining_s;                      /* at programmed feeds (rapids at SWARF_RAPID_RATE) */
  double volume_before;                    /* stock volume at the start, mm^3 */
  double volume_after;                     /* at finish, mm^3 (NaN before) */
  double seconds;                          /* wall time from new to finish */
  long alarms;                             /* all alarms */
  long alarm_count[SWARF_ALARM_KINDS];     /* per swarf_alarm_kind */
  long collisions;                         /* among them: SHANK, HOLDER and FIXTURE alarms */
  double collision_s;                      /* CPU time checking for collisions, s */
  swarf_alarm alarm[SWARF_SIM_MAX_ALARMS]; /* the first ones, in program order */
  double start[3];                         /* where the tool tip started, workpiece frame, mm */
  int start_default;                       /* 1: the default start (not cfg.start) */
  long units_line;                         /* the program's first G20/G21 (0: none) */
  long units_missing_line;         /* the first move run before any G20/G21 (0: none): it ran */
  int units_missing_column;        /* in the machine's unit */
  int has_deviation;               /* 1: deviation holds the comparison with cfg.design */
  swarf_stock_deviation deviation; /* after finish (stock.h) */
  double design_s;                 /* CPU time (all threads) of that comparison, s */
  double removed;                  /* volume_before - volume_after, mm^3 (NaN before finish) */
};
SWARF_API const swarf_sim_report *swarf_sim_get_report(const swarf_sim *sim);

/* Every alarm of the run so far, in the order raised (report.alarm keeps the
 * first SWARF_SIM_MAX_ALARMS): the count, and alarm i (0 <= i < count;
 * NULL outside, or for a NULL handle), owned by the handle. The handle keeps
 * up to SWARF_SIM_KEPT_ALARMS; report.alarms counts every one. */
#define SWARF_SIM_KEPT_ALARMS 1000000L
SWARF_API long swarf_sim_alarm_count(const swarf_sim *sim);
SWARF_API const swarf_alarm *swarf_sim_alarm_at(const swarf_sim *sim, long i);

/* The stock: borrowed (valid until the next call on the handle) or taken
 * (the caller owns it and frees it with swarf_stock_free; the handle then has
 * none and refuses further input). Take it after finish for the result. */
SWARF_API const swarf_stock *swarf_sim_stock(const swarf_sim *sim);
SWARF_API swarf_stock *swarf_sim_take_stock(swarf_sim *sim);

SWARF_API void swarf_sim_free(swarf_sim *sim);

/* After a finished run with cfg.tally: how evenly `nranks` processes (>= 1)
 * would have shared the work, from the blocks each slab's removal visited
 * (*visited, may be NULL: 512 voxels a block) and the slabs the plan would
 * have given them: *max_over_mean = the busiest rank's voxels over the
 * mean (1: perfect). SWARF_ERR_STATE without a tally. */
SWARF_API swarf_status swarf_sim_balance(const swarf_sim *sim, int nranks, double *max_over_mean,
                                         double *visited);

/* ---- One-shot conveniences ------------------------------------------------ */

/* new + feed_file (or feed of `len` bytes of `text`) + finish + take_stock.
 * On success *out is the caller's stock and *rep the final report; on failure
 * *out is NULL, *rep the report so far and err (may be NULL) says why. */
SWARF_API swarf_status swarf_sim_run(const swarf_sim_config *cfg, const char *path,
                                     swarf_stock **out, swarf_sim_report *rep, swarf_error *err);
SWARF_API swarf_status swarf_sim_run_text(const swarf_sim_config *cfg, const char *name,
                                          const char *text, size_t len, swarf_stock **out,
                                          swarf_sim_report *rep, swarf_error *err);

/* ---- Specs as the command line and the Python module write them ----------- */

/* "T<n>=<shape>,D<diameter>[,R<corner>][,L<length>]" (shape ball, flat, bull). */
SWARF_API swarf_status swarf_sim_parse_tool(const char *spec, swarf_sim_tool *out,
                                            swarf_error *err);
/* "box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX" or "cylinder:AXIS,RADIUS,START,END". */
SWARF_API swarf_status swarf_sim_parse_stock(const char *spec, swarf_sim_stock_spec *out,
                                             swarf_error *err);

/* "T<n>=<D>x<H>[,<D1>-<D2>x<H>...]": the holder of tool n, pieces stacked
 * upward from the holder face (mm): cylinders D x H and cones D1 (bottom) to
 * D2 (top) over H. Fills out->number and the holder fields only. */
SWARF_API swarf_status swarf_sim_parse_holder(const char *spec, swarf_sim_tool *out,
                                              swarf_error *err);
/* "box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX" (mm) or "stl:FILE" (out->stl then points
 * into spec, which must live until swarf_sim_new returns). */
SWARF_API swarf_status swarf_sim_parse_fixture(const char *spec, swarf_sim_fixture *out,
                                               swarf_error *err);

/* ---- The design's band, cached between runs ------------------------------ */

/* Where designs' bands are kept (design_cache.c); all zero: the default. */
typedef struct {
  const char *dir;     /* NULL: $XDG_CACHE_HOME/swarf/designs, else ~/.cache/swarf/designs */
  int off;             /* 1: read the design every time and keep nothing */
  long long max_bytes; /* the folder's bound, oldest files out first; <= 0: 1 GiB */
} swarf_design_cache;

/* swarf_stock_read_design_band, through the cache: an STL design's band at
 * `voxel` and `half_width` is kept under a key of the file's bytes, the
 * voxel, the band and the library's version, and read back (bit for bit) by
 * the next run that asks for the same. *hit (may be NULL) gets 1 when it
 * came from the cache. A .vdb design is read as it is. The cache's own
 * failures (no folder, a full disk, a damaged entry) fall back to reading
 * the design; errors are the design's. cache may be NULL (the default). */
SWARF_API swarf_status swarf_sim_read_design_cached(const char *path, double voxel, int half_width,
                                                    const swarf_design_cache *cache,
                                                    swarf_stock **out, int *hit, swarf_error *err);

/* ---- Tool tables and libraries (the tool table of cfg) ------------------- */

/* Reads a LinuxCNC tool table ("T1 P1 D6 Z+30 ;comment", tooltable.c), its
 * lengths in mm_per_unit mm (1, or 25.4 for a table in inches): each tool's
 * G43 length becomes `length`; a tool not yet in cfg is added as a flat end
 * mill of the table's diameter (none when D is 0). A bad line gives
 * SWARF_ERR_TOOL with FILE:LINE in err; cfg may then hold the lines before. */
SWARF_API swarf_status swarf_sim_config_load_tool_table(swarf_sim_config *cfg, const char *path,
                                                        double mm_per_unit, swarf_error *err);

/* Reads a tool library (JSON, library.c; tools/doc/simulate.md documents the format):
 * full assemblies that replace the description of tools already in cfg
 * (their G43 length stays unless the library gives one) or add new ones.
 * Errors: FILE:LINE: what is wrong (SWARF_ERR_TOOL, SWARF_ERR_FORMAT). */
SWARF_API swarf_status swarf_sim_config_load_tool_library(swarf_sim_config *cfg, const char *path,
                                                          swarf_error *err);

/* Puts a --tool description into cfg: the cutter and the assembly fields the
 * spec gave (S, N) replace those of a tool already there (from a table or a
 * library), whose length and holder stay; otherwise the tool is added. */
SWARF_API swarf_status swarf_sim_config_put_tool(swarf_sim_config *cfg, const swarf_sim_tool *t,
                                                 swarf_error *err);
/* Checks a tool's assembly: S, N, holder pieces finite and > 0, a holder
 * only with a stick-out (SWARF_ERR_TOOL naming the tool). swarf_sim_new
 * checks every tool of the config. */
SWARF_API swarf_status swarf_sim_check_tool(const swarf_sim_tool *t, swarf_error *err);
/* Puts a --holder into cfg: tool t->number must be there already. */
SWARF_API swarf_status swarf_sim_config_put_holder(swarf_sim_config *cfg, const swarf_sim_tool *t,
                                                   swarf_error *err);

#ifdef __cplusplus
}
#endif
#endif
