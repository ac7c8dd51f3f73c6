/* SPDX-License-Identifier: MPL-2.0 */
/* sim.c -- the simulation handle (swarf_sim.h).
 *
 * The parser calls on_move for every canonical move; motions are queued with
 * their sweeps in a fixed-size batch that is removed from the stock in one
 * pass when full and at the end (batch.c). Memory is bounded by the batch
 * size, not by the program. The handle owns the parser, the batch arrays and
 * the stock until swarf_sim_take_stock hands the stock to the caller.
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "sim_private.h"

static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

swarf_sim_config *swarf_sim_config_new(void) {
  swarf_sim_config *cfg = malloc(sizeof *cfg);
  if (cfg != NULL) swarf_sim_config_init(cfg);
  return cfg;
}

void swarf_sim_config_free(swarf_sim_config *cfg) {
  free(cfg);
}

void swarf_sim_config_init(swarf_sim_config *cfg) {
  if (cfg == NULL) return;
  memset(cfg, 0, sizeof *cfg);
  cfg->voxel = 0.2;
  cfg->half_width = 3;
  cfg->batch = 1024;
}

swarf_status swarf_sim_config_add_tool(swarf_sim_config *cfg, const swarf_sim_tool *t,
                                       swarf_error *err) {
  if (cfg == NULL || t == NULL) return swarf_error_set(err, SWARF_ERR_ARG, "no config or tool");
  if (cfg->ntools == SWARF_SIM_MAX_TOOLS)
    return swarf_error_set(err, SWARF_ERR_ARG, "too many tools (%d at most)", SWARF_SIM_MAX_TOOLS);
  for (int i = 0; i < cfg->ntools; i++)
    if (cfg->tools[i].number == t->number)
      return swarf_error_set(err, SWARF_ERR_ARG, "T%d is given twice", t->number);
  cfg->tools[cfg->ntools++] = *t;
  return SWARF_OK;
}

/* A failure: recorded once (the first one wins), the handle refuses more. */
swarf_status swarf_sim_fail(swarf_sim *s, swarf_status st, long line, int column, const char *fmt,
                            ...) {
  va_list ap;
  if (s->err.status != SWARF_OK) return s->err.status;
  swarf_error_at(&s->err, s->name, line, column, NULL);
  s->err.status = st;
  va_start(ap, fmt);
  vsnprintf(s->err.message, sizeof s->err.message, fmt, ap);
  va_end(ap);
  s->state = SIM_FAILED;
  return st;
}

static const swarf_sim_tool *find_tool(const swarf_sim *s, int number) {
  for (int i = 0; i < s->cfg.ntools; i++)
    if (s->cfg.tools[i].number == number) return &s->cfg.tools[i];
  return NULL;
}

/* Fanuc and Haas controls hold their tool data: a change to a tool not
 * given is an error only once that tool cuts (take_motion). */
static int holds_tool_data(const swarf_sim *s) {
  return s->cfg.dialect == SWARF_GCODE_DIALECT_FANUC || s->cfg.dialect == SWARF_GCODE_DIALECT_HAAS;
}

static int on_tool_change(swarf_sim *s, const swarf_move *mv) {
  const swarf_sim_tool *t = find_tool(s, mv->tool);
  s->rep.tool_changes++;
  s->unknown_tool = 0;
  if (mv->tool != 0 && t == NULL && holds_tool_data(s)) {
    s->unknown_tool = mv->tool, s->unknown_line = mv->line;
  } else if (mv->tool != 0 && t == NULL) {
    swarf_sim_fail(s, SWARF_ERR_TOOL, mv->line, mv->column,
                   "tool T%d is not in the tool table; describe it with --tool T%d=<shape>,"
                   "D<diameter>",
                   mv->tool, mv->tool);
    return 1;
  }
  s->tool = t;
  return 0;
}

/* The T number to report: the move's, or the single tool loaded at start. */
static int spindle_tool(const swarf_sim *s, int move_tool) {
  if (move_tool == 0 && s->tool != NULL) return s->tool->number;
  return move_tool;
}

static int tell_pass(swarf_sim *s, long line, int tool, double pass);

/* After a move: the fraction of the program read, from the parser's bytes
 * when the program's size is known. */
static int tell_progress(swarf_sim *s, long line, int tool) {
  if (s->size > 0) {
    const double f = (double)swarf_gcode_parser_bytes(s->parser) / (double)s->size;
    s->fraction = f > 1.0 ? 1.0 : f;
  }
  return tell_pass(s, line, tool, -1.0);
}

/* Within a removal pass (the stock's tick): progress with the last queued
 * move's line and the fraction of the pass done. */
static int on_tick(void *user, double done) {
  swarf_sim *s = user;
  const swarf_motion *m = s->n > 0 ? &s->motions[s->n - 1] : NULL;
  return tell_pass(s, m ? m->line : 0, spindle_tool(s, m ? m->tool : 0), done);
}

/* Several processes: the stock is this one's slab only (not shown), and a
 * stop is obeyed at the next batch, on all of them (slab.c). */
static int tell_pass(swarf_sim *s, long line, int tool, double pass) {
  const int slabs = swarf_sim_slabs(s);
  swarf_sim_progress p = {s->fraction, line, tool, &s->rep, slabs ? NULL : s->stock, pass};
  if (s->cfg.cb.progress == NULL || s->cfg.cb.progress(s->cfg.cb.user, &p) == 0) return 0;
  if (slabs) return s->abort_pending = 1, 0;
  swarf_sim_fail(s, SWARF_ERR_ABORTED, line, 0, "aborted by the caller");
  return 1;
}

/* Count a motion, tell the caller, and queue its sweep if it can cut. */
static int take_motion(swarf_sim *s, swarf_motion *m) {
  int tool = spindle_tool(s, m->tool);
  s->rep.moves++;
  s->rep.rapids += m->rapid;
  s->rep.arcs += m->kind == SWARF_MOTION_HELIX;
  s->rep.path_mm += m->length;
  s->rep.machining_s += m->duration;
  if (swarf_sim_lines_add(s, m, tool) != 0) return 1;
  if (tell_progress(s, m->line, tool)) return 1;
  if (swarf_motion_is_null(m)) return 0;
  if (s->unknown_tool != 0 && !m->rapid) {
    swarf_sim_fail(s, SWARF_ERR_TOOL, m->line, m->column,
                   "a feed move with tool T%d (changed at line %ld), which is not in the tool "
                   "table; describe it with --tool T%d=<shape>,D<diameter>",
                   s->unknown_tool, s->unknown_line, s->unknown_tool);
    return 1;
  }
  if (s->tool == NULL) return swarf_sim_batch_check_empty(s, m);
  if (!(s->tool->cutter.diameter > 0)) {
    swarf_sim_fail(s, SWARF_ERR_TOOL, m->line, m->column,
                   "tool T%d has no shape (diameter 0 in the tool table); describe it with "
                   "--tool T%d=<shape>,D<diameter> or in a tool library",
                   s->tool->number, s->tool->number);
    return 1;
  }
  return swarf_sim_batch_queue(s, m);
}

/* The parser's positions are the machine's: with G43 the controlled point
 * is the tip of the tool whose length H names, without it the spindle's
 * gauge line. The simulator follows the tip of the tool in the spindle,
 * which lies its length below: G43 with that tool's H puts it where the
 * program says, as on the machine. One exception: the machine's start
 * position (0,0,0, where no homing put it) is taken as the tip's, so the
 * first straight move starts there and not a tool length below. */
static const swarf_move *tip_move(swarf_sim *s, const swarf_move *mv, swarf_move *buf) {
  const double len = s->tool != NULL ? s->tool->length : 0.0;
  const int first = !s->moved && mv->kind != SWARF_MOVE_ARC;
  s->moved = 1;
  if (len == 0.0) return mv;
  *buf = *mv;
  if (!first) buf->start[SWARF_AXIS_Z] -= len;
  buf->end[SWARF_AXIS_Z] -= len;
  buf->center[2] -= len;
  return buf;
}

/* The machine for the tool in the spindle: a spindle head's pivot lies
 * --machine's head=L above the gauge line, so the tool's length further
 * above its tip (swarf_machine.head is measured from the tip). */
static swarf_machine machine_for_tool(const swarf_sim *s) {
  swarf_machine mc = s->cfg.machine;
  if (s->tool != NULL) mc.head += s->tool->length;
  return mc;
}

static int on_move(const swarf_move *machine_mv, void *user) {
  swarf_sim *s = user;
  swarf_motion m;
  swarf_machine mc;
  swarf_move w, tip, *mv = &w;
  if (machine_mv->kind == SWARF_MOVE_TOOL_CHANGE) return on_tool_change(s, machine_mv);
  if (machine_mv->kind == SWARF_MOVE_DWELL) return 0;
  swarf_sim_to_workpiece(s, tip_move(s, machine_mv, &tip), &w);
  if (s->cfg.cb.move != NULL) s->cfg.cb.move(s->cfg.cb.user, &w);
  swarf_sim_check_units(s, mv);
  swarf_error e;
  mc = machine_for_tool(s);
  swarf_status rc = swarf_machine_motion(&mc, mv, &m, &e);
  if (rc == SWARF_ERR_MACHINE) {
    swarf_sim_fail(s, SWARF_ERR_MACHINE, mv->line, mv->column, "%s", e.message);
    return 1;
  }
  if (rc != SWARF_OK) return 0;
  return take_motion(s, &m);
}

/* The stock of cfg's spec: whole (rlo NULL), or only its slab [rlo, rhi]
 * (stock.h's swarf_stock_new_box_slab). */
static swarf_stock *build_stock(const swarf_sim_config *cfg, const int *rlo, const int *rhi,
                                swarf_error *err) {
  const swarf_sim_stock_spec *k = &cfg->stock;
  swarf_error e = {0};
  swarf_stock *st = NULL;
  swarf_status rc;
  if (k->kind == SWARF_SIM_STOCK_CYLINDER)
    rc = rlo == NULL
             ? swarf_stock_new_cylinder(k->axis, k->radius, k->lo[k->axis], k->hi[k->axis],
                                        cfg->voxel, cfg->half_width, &st, &e)
             : swarf_stock_new_cylinder_slab(k->axis, k->radius, k->lo[k->axis], k->hi[k->axis],
                                             cfg->voxel, cfg->half_width, rlo, rhi, &st, &e);
  else
    rc = rlo == NULL ? swarf_stock_new_box(k->lo, k->hi, cfg->voxel, cfg->half_width, &st, &e)
                     : swarf_stock_new_box_slab(k->lo, k->hi, cfg->voxel, cfg->half_width, rlo, rhi,
                                                &st, &e);
  if (rc != SWARF_OK) swarf_error_set(err, SWARF_ERR_ARG, "--stock: %s", e.message);
  return st;
}

/* Moves whose sweep misses the material's box grown by the band are not
 * queued: the box of a stock built from a spec, or an existing stock's
 * active voxels (which hold the band already). */
static void set_pad(swarf_sim *s, const swarf_sim_stock_spec *spec) {
  double band = swarf_stock_voxel(s->stock) * (swarf_stock_half_width(s->stock) + 1), lo[3], hi[3];
  if (spec != NULL) {
    memcpy(lo, spec->lo, sizeof lo);
    memcpy(hi, spec->hi, sizeof hi);
  } else {
    swarf_stock_bounds(s->stock, lo, hi);
    band = swarf_stock_voxel(s->stock);
  }
  memcpy(s->mat_lo, lo, sizeof lo);
  memcpy(s->mat_hi, hi, sizeof hi);
  for (int k = 0; k < 3; k++) {
    s->pad_lo[k] = lo[k] - band;
    s->pad_hi[k] = hi[k] + band;
  }
}

static void on_note(long line, int column, const char *text, void *user) {
  swarf_sim *s = user;
  if (s->cfg.cb.note != NULL) s->cfg.cb.note(s->cfg.cb.user, line, column, text);
}

/* The dialect, the block delete switch, the subroutine path, the notes. */
static swarf_status set_reading(swarf_sim *s, swarf_error *err) {
  swarf_status st = swarf_gcode_parser_set_dialect(s->parser, s->cfg.dialect, err);
  if (st == SWARF_OK) st = swarf_gcode_parser_set_block_delete(s->parser, s->cfg.block_delete, err);
  if (st == SWARF_OK) st = swarf_gcode_parser_set_fragment(s->parser, s->cfg.fragment, err);
  if (st == SWARF_OK && s->cfg.work_limit != 0)
    st = swarf_gcode_parser_set_work_limit(s->parser, s->cfg.work_limit, err);
  if (st == SWARF_OK && s->cfg.subroutine_path != NULL)
    st = swarf_gcode_parser_set_subroutine_path(s->parser, s->cfg.subroutine_path, err);
  if (st == SWARF_OK) swarf_gcode_parser_set_notes(s->parser, on_note, s);
  return st;
}

static swarf_status sim_init(swarf_sim *s, swarf_error *err) {
  swarf_status st;
  if (swarf_gcode_parser_new(s->name, on_move, s, &s->parser) != SWARF_OK ||
      swarf_sim_batch_init(s) != 0)
    return swarf_error_set(err, SWARF_ERR_MEMORY, "out of memory");
  if ((st = set_reading(s, err)) != SWARF_OK) return st;
  if ((st = swarf_sim_setup(s, err)) != SWARF_OK ||
      (st = swarf_sim_design_init(s, err)) != SWARF_OK)
    return st;
  if (s->cfg.ntools == 1) s->tool = &s->cfg.tools[0];
  if (swarf_sim_collide_init(s) != 0) {
    if (err != NULL) *err = s->err;
    return s->err.status != SWARF_OK ? s->err.status : SWARF_ERR_MEMORY;
  }
  s->rep.volume_before = swarf_stock_volume(s->stock);
  s->rep.volume_after = NAN;
  s->rep.removed = NAN;
  s->fraction = -1.0;
  return SWARF_OK;
}

/* The handle's settings on a stock: its threads and progress ticks. */
static swarf_status stock_settings(swarf_sim *s, const swarf_sim_config *cfg, swarf_stock *stock,
                                   swarf_error *err) {
  if (swarf_stock_set_threads(stock, cfg->threads, err) != SWARF_OK) return SWARF_ERR_ARG;
  if (cfg->cb.progress != NULL && swarf_stock_set_tick(stock, on_tick, s,
                                                       cfg->tick > 0   ? cfg->tick
                                                       : cfg->tick < 0 ? 0.0
                                                                       : 0.25,
                                                       err) != SWARF_OK)
    return SWARF_ERR_ARG;
  return SWARF_OK;
}

int swarf_sim_slab_stock(swarf_sim *s, const int lo[3], const int hi[3]) {
  swarf_error e;
  swarf_stock *st;
  swarf_error_init(&e);
  if ((st = build_stock(&s->cfg, lo, hi, &e)) == NULL ||
      stock_settings(s, &s->cfg, st, &e) != SWARF_OK) {
    swarf_stock_free(st);
    swarf_sim_fail(s, e.status != SWARF_OK ? e.status : SWARF_ERR_INTERNAL, 0, 0, "%s", e.message);
    return 1;
  }
  swarf_stock_free(s->stock);
  s->stock = st;
  s->slab_build = 0;
  return 0;
}

static swarf_status sim_new(const swarf_sim_config *cfg, const char *name, swarf_stock *stock,
                            const swarf_sim_stock_spec *spec, swarf_sim **out, swarf_error *err) {
  swarf_sim *s;
  swarf_status st;
  if (out != NULL) *out = NULL;
  if (cfg == NULL || out == NULL || stock == NULL) {
    swarf_stock_free(stock);
    return swarf_error_set(err, SWARF_ERR_ARG, "swarf_sim_new: no config, stock or output");
  }
  for (int i = 0; i < cfg->ntools; i++)
    if ((st = swarf_sim_check_tool(&cfg->tools[i], err)) != SWARF_OK) {
      swarf_stock_free(stock);
      return st;
    }
  if (swarf_stock_set_threads(stock, cfg->threads, err) != SWARF_OK) {
    swarf_stock_free(stock);
    return SWARF_ERR_ARG;
  }
  if ((s = calloc(1, sizeof *s)) == NULL) {
    swarf_stock_free(stock);
    return swarf_error_set(err, SWARF_ERR_MEMORY, "out of memory");
  }
  if (cfg->cb.progress != NULL && swarf_stock_set_tick(stock, on_tick, s,
                                                       cfg->tick > 0   ? cfg->tick
                                                       : cfg->tick < 0 ? 0.0
                                                                       : 0.25,
                                                       err) != SWARF_OK) {
    free(s);
    swarf_stock_free(stock);
    return SWARF_ERR_ARG;
  }
  s->t0 = now_seconds();
  s->cfg = *cfg;
  s->cfg.voxel = swarf_stock_voxel(stock);
  s->stock = stock;
  snprintf(s->name, sizeof s->name, "%s", name != NULL ? name : "program");
  set_pad(s, spec);
  if ((st = sim_init(s, err)) != SWARF_OK) {
    swarf_sim_free(s);
    return st;
  }
  *out = s;
  return SWARF_OK;
}

swarf_status swarf_sim_new_with_stock(const swarf_sim_config *cfg, const char *name,
                                      swarf_stock *stock, swarf_sim **out, swarf_error *err) {
  return sim_new(cfg, name, stock, NULL, out, err);
}

swarf_status swarf_sim_new(const swarf_sim_config *cfg, const char *name, swarf_sim **out,
                           swarf_error *err) {
  swarf_stock *stock;
  swarf_status st;
  if (out != NULL) *out = NULL;
  if (cfg == NULL || out == NULL) return swarf_error_set(err, SWARF_ERR_ARG, "no config or output");
  if ((st = swarf_sim_config_check(cfg, 1, err)) != SWARF_OK) return st;
  /* Under MPI, the processes other than rank 0 (which gathers the whole
   * stock) build only their slab, once it is planned: a shell until then.
   * Not with a design, which compares against a copy of the whole stock. */
  const int slab =
      cfg->comm != NULL && cfg->comm->size > 1 && cfg->comm->rank != 0 && cfg->design == NULL;
  static const int none_lo[3] = {8, 8, 8}, none_hi[3] = {0, 0, 0};
  if ((stock = build_stock(cfg, slab ? none_lo : NULL, slab ? none_hi : NULL, err)) == NULL)
    return SWARF_ERR_ARG;
  st = sim_new(cfg, name, stock, &cfg->stock, out, err);
  if (st == SWARF_OK) (*out)->slab_build = slab;
  return st;
}

static swarf_status check_open(swarf_sim *s) {
  if (s == NULL) return SWARF_ERR_ARG;
  if (s->state == SIM_OPEN) return SWARF_OK;
  if (s->err.status == SWARF_OK)
    swarf_error_set(&s->err, SWARF_ERR_STATE,
                    s->state == SIM_FINISHED ? "the program was finished already"
                                             : "the stock was taken already");
  return SWARF_ERR_STATE;
}

/* Map the parser's outcome: its own errors carry their place and identity;
 * a stop asked by on_move carries the handle's own error. */
static swarf_status parser_outcome(swarf_sim *s, swarf_status rc) {
  const swarf_error *e = swarf_gcode_parser_error(s->parser);
  if (rc == SWARF_OK) return SWARF_OK;
  if (s->err.status != SWARF_OK) return s->err.status;
  if (e == NULL || e->status == SWARF_OK)
    return swarf_sim_fail(s, rc, 0, 0, "%s", swarf_status_message(rc));
  s->err = *e;
  s->state = SIM_FAILED;
  return rc;
}

swarf_status swarf_sim_feed(swarf_sim *s, const char *text, size_t len) {
  swarf_status st = check_open(s);
  if (st != SWARF_OK) return st;
  if (text == NULL && len > 0) return swarf_sim_fail(s, SWARF_ERR_ARG, 0, 0, "no text");
  if (swarf_sim_slab_plan(s, NULL) != 0) return s->err.status;
  return parser_outcome(s, swarf_gcode_parser_feed(s->parser, text, len));
}

swarf_status swarf_sim_feed_file(swarf_sim *s, const char *path) {
  static const size_t chunk = 1 << 16;
  swarf_status st = check_open(s);
  struct stat sb;
  FILE *f;
  char *buf;
  size_t n;
  if (st != SWARF_OK) return st;
  if (path == NULL) return swarf_sim_fail(s, SWARF_ERR_ARG, 0, 0, "no program path");
  if (swarf_sim_slab_plan(s, path) != 0) return s->err.status;
  if ((f = fopen(path, "rb")) == NULL)
    return swarf_sim_fail(s, SWARF_ERR_OPEN, 0, 0, "cannot open the program: %s", strerror(errno));
  double total = fstat(fileno(f), &sb) == 0 && sb.st_size > 0 ? (double)sb.st_size : 0.0, done = 0;
  if (s->size <= 0) s->size = (long long)total; /* each move's fraction from the bytes read */
  if ((buf = malloc(chunk)) == NULL)
    st = swarf_sim_fail(s, SWARF_ERR_MEMORY, 0, 0, "out of memory");
  while (st == SWARF_OK && (n = fread(buf, 1, chunk, f)) > 0) {
    st = swarf_sim_feed(s, buf, n);
    done += (double)n;
    if (total > 0) s->fraction = done / total > 1.0 ? 1.0 : done / total;
    if (st == SWARF_OK && tell_progress(s, swarf_gcode_parser_lines(s->parser), spindle_tool(s, 0)))
      st = s->err.status;
  }
  if (st == SWARF_OK && ferror(f))
    st = swarf_sim_fail(s, SWARF_ERR_OPEN, 0, 0, "read error: %s", strerror(errno));
  free(buf);
  fclose(f);
  return st;
}

swarf_status swarf_sim_set_program_size(swarf_sim *s, long long bytes) {
  swarf_status st = check_open(s);
  if (st != SWARF_OK) return st;
  if (bytes < 0) return swarf_sim_fail(s, SWARF_ERR_ARG, 0, 0, "a negative program size");
  s->size = bytes;
  return SWARF_OK;
}

swarf_status swarf_sim_add_motion(swarf_sim *s, const swarf_motion *m) {
  swarf_status st = check_open(s);
  swarf_motion copy;
  if (st != SWARF_OK) return st;
  if (m == NULL) return swarf_sim_fail(s, SWARF_ERR_ARG, 0, 0, "no motion");
  if (swarf_sim_slab_plan(s, NULL) != 0) return s->err.status;
  copy = *m;
  if (m->tool != 0 && (s->tool == NULL || s->tool->number != m->tool)) {
    const swarf_sim_tool *t = find_tool(s, m->tool);
    if (t == NULL)
      return swarf_sim_fail(s, SWARF_ERR_TOOL, m->line, m->column,
                            "tool T%d is not in the tool table", m->tool);
    s->tool = t;
  }
  return take_motion(s, &copy) ? s->err.status : SWARF_OK;
}

/* The sheets of no thickness cuts that end on a stock face leave (stock.h). */
static swarf_status clear_sheets(swarf_sim *s) {
  swarf_error e;
  swarf_error_init(&e);
  if (swarf_stock_clear_sheets(s->stock, NULL, &e) != SWARF_OK)
    return swarf_sim_fail(s, e.status, 0, 0, "%s", e.message);
  return SWARF_OK;
}

swarf_status swarf_sim_finish(swarf_sim *s) {
  swarf_status st = check_open(s);
  if (st != SWARF_OK) return st;
  if (swarf_sim_slab_plan(s, NULL) != 0) return s->err.status;
  st = parser_outcome(s, swarf_gcode_parser_finish(s->parser));
  s->rep.lines = swarf_gcode_parser_lines(s->parser);
  s->rep.units_line = swarf_gcode_parser_units_line(s->parser);
  if (st == SWARF_OK && swarf_sim_batch_flush(s) != 0) st = s->err.status;
  if (st == SWARF_OK && swarf_sim_lines_flush(s, 1) != 0) st = s->err.status;
  if (st == SWARF_OK && swarf_sim_slab_merge(s) != 0) st = s->err.status;
  const int whole = !swarf_sim_slabs(s) || s->cfg.comm->rank == 0; /* the whole stock here */
  if (st == SWARF_OK && whole) st = clear_sheets(s);
  if (st == SWARF_OK && whole) st = swarf_sim_design_compare(s);
  s->rep.seconds = now_seconds() - s->t0;
  if (st != SWARF_OK) return st;
  if (whole) s->rep.volume_after = swarf_stock_volume(s->stock);
  s->rep.removed = s->rep.volume_before - s->rep.volume_after;
  s->state = SIM_FINISHED;
  return SWARF_OK;
}

const swarf_error *swarf_sim_error(const swarf_sim *s) {
  return s != NULL ? &s->err : NULL;
}

const swarf_sim_report *swarf_sim_get_report(const swarf_sim *s) {
  return s != NULL ? &s->rep : NULL;
}

const swarf_stock *swarf_sim_stock(const swarf_sim *s) {
  return s != NULL ? s->stock : NULL;
}

swarf_stock *swarf_sim_take_stock(swarf_sim *s) {
  swarf_stock *st;
  if (s == NULL) return NULL;
  st = s->stock;
  s->stock = NULL;
  swarf_stock_set_tick(st, NULL, NULL, 0.0, NULL); /* the ticks went to this handle */
  if (s->state == SIM_OPEN) s->state = SIM_TAKEN;
  return st;
}

void swarf_sim_free(swarf_sim *s) {
  if (s == NULL) return;
  swarf_gcode_parser_free(s->parser);
  swarf_sim_collide_clear(s);
  swarf_sim_batch_clear(s);
  swarf_stock_free(s->stock);
  swarf_stock_free(s->initial);
  swarf_sim_slab_clear(s);
  free(s->alarms);
  free(s);
}

long swarf_sim_alarm_count(const swarf_sim *s) {
  return s != NULL ? s->nalarms : 0;
}

const swarf_alarm *swarf_sim_alarm_at(const swarf_sim *s, long i) {
  return s != NULL && i >= 0 && i < s->nalarms ? &s->alarms[i] : NULL;
}

/* ---- One-shot conveniences ------------------------------------------------ */

typedef swarf_status (*feed_fn)(swarf_sim *s, const void *a, size_t len);

static swarf_status feed_path(swarf_sim *s, const void *path, size_t len) {
  (void)len;
  return swarf_sim_feed_file(s, path);
}

static swarf_status feed_text(swarf_sim *s, const void *text, size_t len) {
  swarf_status st = swarf_sim_set_program_size(s, (long long)len);
  return st == SWARF_OK ? swarf_sim_feed(s, text, len) : st;
}

static swarf_status run(const swarf_sim_config *cfg, const char *name, feed_fn feed,
                        const void *src, size_t len, swarf_stock **out, swarf_sim_report *rep,
                        swarf_error *err) {
  swarf_sim *s = NULL;
  swarf_status st;
  if (out != NULL) *out = NULL;
  if (rep != NULL) memset(rep, 0, sizeof *rep);
  if (out == NULL) return swarf_error_set(err, SWARF_ERR_ARG, "no output");
  if ((st = swarf_sim_new(cfg, name, &s, err)) != SWARF_OK) return st;
  st = feed(s, src, len);
  if (st == SWARF_OK) st = swarf_sim_finish(s);
  if (rep != NULL) *rep = s->rep;
  if (st == SWARF_OK)
    *out = swarf_sim_take_stock(s);
  else if (err != NULL)
    *err = s->err;
  swarf_sim_free(s);
  return st;
}

swarf_status swarf_sim_run(const swarf_sim_config *cfg, const char *path, swarf_stock **out,
                           swarf_sim_report *rep, swarf_error *err) {
  return run(cfg, path, feed_path, path, 0, out, rep, err);
}

swarf_status swarf_sim_run_text(const swarf_sim_config *cfg, const char *name, const char *text,
                                size_t len, swarf_stock **out, swarf_sim_report *rep,
                                swarf_error *err) {
  return run(cfg, name, feed_text, text, len, out, rep, err);
}
