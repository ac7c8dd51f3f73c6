/* SPDX-License-Identifier: MPL-2.0 */
/* setup.c -- the machine a simulation runs on (sim_private.h): its length
 * unit, work offsets and start position, given to the parser before the
 * program runs; the workpiece frame the moves are brought into; the check
 * for a units word; the design the result is compared with.
 *
 * The workpiece frame is G54's as set up (offsets file, then cfg.g54): the
 * parser hands out machine coordinates (G53 moves go where the machine puts
 * them), and w = Rz(-rot) (m - origin) brings them onto the stock.
 */
#include <math.h>
#include <string.h>
#include <time.h>

#include "sim_private.h"

#define DEG (3.14159265358979323846 / 180.0)

/* X0 Y0, SWARF_SIM_CLEARANCE above the material (any table rotation on a
 * rotary machine: above its bounding sphere about the pivot). */
static void default_start(const swarf_sim *s, double w[3]) {
  const double *lo = s->mat_lo, *hi = s->mat_hi, *pv = s->cfg.machine.pivot;
  double r2 = 0;
  w[0] = w[1] = 0;
  w[2] = hi[2] + SWARF_SIM_CLEARANCE;
  if (s->cfg.machine.kind == SWARF_MACHINE_XYZ) return;
  for (int c = 0; c < 8; c++) {
    double d2 = 0;
    for (int k = 0; k < 3; k++) {
      double v = ((c >> k) & 1 ? hi[k] : lo[k]) - pv[k];
      d2 += v * v;
    }
    if (d2 > r2) r2 = d2;
  }
  w[2] = pv[2] + sqrt(r2) + SWARF_SIM_CLEARANCE;
}

/* Units, the parameter file, G54, in that order (the parameters are in the
 * machine's unit). */
static swarf_status setup_offsets(const swarf_sim_config *cfg, swarf_gcode_parser *p,
                                  swarf_error *err) {
  swarf_gcode_units u =
      cfg->units == SWARF_GCODE_UNITS_INCH ? SWARF_GCODE_UNITS_INCH : SWARF_GCODE_UNITS_MM;
  double unit = u == SWARF_GCODE_UNITS_INCH ? 25.4 : 1.0;
  swarf_status st = swarf_gcode_parser_set_units(p, u, err);
  if (st == SWARF_OK && cfg->offsets_file != NULL)
    st = swarf_gcode_parser_load_params(p, cfg->offsets_file, err);
  for (int k = 0; st == SWARF_OK && cfg->g54_set && k < 3; k++)
    st = swarf_gcode_parser_set_param(p, 5221 + k, cfg->g54[k] / unit, err);
  return st;
}

/* The parser's tool table is the tools given, with their length offsets
 * (G43 H<n> applies tool n's; an H of a tool not given is an error at its
 * line). With length 0 (tools given by --tool alone) G43 changes nothing. */
static void set_tools(const swarf_sim_config *cfg, swarf_gcode_parser *parser) {
  swarf_gcode_parser_clear_tools(parser);
  for (int i = 0; i < cfg->ntools; i++)
    swarf_gcode_parser_set_tool(parser, cfg->tools[i].number, cfg->tools[i].length,
                                cfg->tools[i].cutter.diameter);
}

swarf_status swarf_sim_setup_parser(const swarf_sim_config *cfg, swarf_gcode_parser *parser,
                                    const double start_w[3], swarf_sim_frame *frame,
                                    swarf_error *err) {
  double origin[SWARF_NAXES], rot = 0, m[SWARF_NAXES] = {0};
  const double *w = start_w;
  swarf_status st;
  if (cfg == NULL || parser == NULL || frame == NULL)
    return swarf_error_set(err, SWARF_ERR_ARG,
                           "swarf_sim_setup_parser: no config, parser or frame");
  if ((st = setup_offsets(cfg, parser, err)) != SWARF_OK) return st;
  if (cfg->ntools > 0) set_tools(cfg, parser);
  swarf_gcode_parser_work_system(parser, 1, origin, &rot);
  memcpy(frame->origin, origin, sizeof frame->origin);
  frame->cos_rot = cos(rot * DEG);
  frame->sin_rot = sin(rot * DEG);
  if (w == NULL) return SWARF_OK; /* the parser's own start, machine 0,0,0 */
  m[0] = frame->cos_rot * w[0] - frame->sin_rot * w[1] + origin[0];
  m[1] = frame->sin_rot * w[0] + frame->cos_rot * w[1] + origin[1];
  m[2] = w[2] + origin[2];
  return swarf_gcode_parser_set_start(parser, m, err);
}

swarf_status swarf_sim_setup(swarf_sim *s, swarf_error *err) {
  double w[3];
  if (s->cfg.start_set)
    memcpy(w, s->cfg.start, sizeof w);
  else
    default_start(s, w);
  memcpy(s->rep.start, w, sizeof w);
  s->rep.start_default = !s->cfg.start_set;
  return swarf_sim_setup_parser(&s->cfg, s->parser, w, &s->frame, err);
}

/* Machine point -> workpiece point (XYZ; rotary axes are joint angles). */
void swarf_sim_frame_point(const swarf_sim_frame *f, const double m[3], double w[3]) {
  double x = m[0] - f->origin[0], y = m[1] - f->origin[1];
  w[0] = f->cos_rot * x + f->sin_rot * y;
  w[1] = -f->sin_rot * x + f->cos_rot * y;
  w[2] = m[2] - f->origin[2];
}

static void point_in(const swarf_sim *s, const double m[3], double w[3]) {
  swarf_sim_frame_point(&s->frame, m, w);
}

void swarf_sim_to_workpiece(const swarf_sim *s, const swarf_move *in, swarf_move *out) {
  double nx = in->normal[0], ny = in->normal[1];
  *out = *in;
  point_in(s, in->start, out->start);
  point_in(s, in->end, out->end);
  if (in->kind != SWARF_MOVE_ARC) return;
  point_in(s, in->center, out->center);
  out->normal[0] = s->frame.cos_rot * nx + s->frame.sin_rot * ny;
  out->normal[1] = -s->frame.sin_rot * nx + s->frame.cos_rot * ny;
}

void swarf_sim_check_units(swarf_sim *s, const swarf_move *mv) {
  if (s->units_checked) return;
  s->units_checked = 1;
  if (swarf_gcode_parser_units_line(s->parser) != 0) return;
  s->rep.units_missing_line = mv->line;
  s->rep.units_missing_column = mv->column;
}

/* ---- the design ------------------------------------------------------------ */

swarf_status swarf_sim_design_init(swarf_sim *s, swarf_error *err) {
  static const swarf_stock_placement same = {{0, 0, 0}, {0, 0, 0}};
  swarf_status st;
  s->tolerance = s->cfg.tolerance > 0 ? s->cfg.tolerance : 0.5 * swarf_stock_voxel(s->stock);
  s->volumes = s->cfg.line_volumes && s->cfg.cb.line != NULL;
  s->measured = s->cfg.design != NULL || s->volumes;
  if (s->cfg.design == NULL) return SWARF_OK;
  st = swarf_stock_check_design(s->stock, s->cfg.design, err);
  if (st == SWARF_OK) st = swarf_stock_place(s->stock, &same, &s->initial, err);
  return st;
}

/* CPU time of the process (all threads), s. */
static double process_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

swarf_status swarf_sim_design_compare(swarf_sim *s) {
  swarf_error err;
  swarf_status st;
  if (s->cfg.design == NULL) return SWARF_OK;
  swarf_error_init(&err);
  const double t0 = process_seconds();
  st = swarf_stock_compare(s->stock, s->cfg.design, s->initial, s->tolerance, &s->rep.deviation,
                           &err);
  s->rep.design_s = process_seconds() - t0;
  if (st != SWARF_OK) return swarf_sim_fail(s, st, 0, 0, "the design comparison: %s", err.message);
  s->rep.has_deviation = 1;
  return SWARF_OK;
}
