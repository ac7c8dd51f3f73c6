/* SPDX-License-Identifier: MPL-2.0 */
/* verify.c -- `swarf simulate`'s setup, design and report options (verify.h).
 *
 * Options are checked as they are read (the flag named in every message);
 * the design is read before the run (a bad or misplaced design costs
 * nothing); warnings, summary lines and the report come after it.
 */
#include <errno.h>
#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "gcode.h"
#include "verify.h"

const char swarf_verify_help[] =
    "\n"
    "The machine's setup (the workpiece frame is G54's as set up here; --stock and\n"
    "--design are in it):\n"
    "  --start X,Y,Z    where the tool tip is when the program starts (mm); default\n"
    "                   X0 Y0, 10 mm above the stock, so nothing is cut before the\n"
    "                   program's first move\n"
    "  --g54 X,Y,Z      G54's origin in machine coordinates (mm): G53 moves go where\n"
    "                   the machine puts them\n"
    "  --offsets FILE   LinuxCNC's parameter file (its .var: \"5221 10.0\" a line):\n"
    "                   work offsets, G28/G30 homes, #5220 (system in force); values\n"
    "                   in the machine's unit (--units)\n"
    "  --units mm|in    the machine's length unit: programs without G20/G21 are read\n"
    "                   in it (default mm; without it such a program gets a warning)\n"
    "How the program is read (tools/doc/dialects.md):\n"
    "  --dialect NAME   linuxcnc (default), fanuc, haas or grbl\n"
    "  --block-delete   the block delete switch is on: `/` blocks are skipped (off:\n"
    "                   they run, as in LinuxCNC)\n"
    "  --subroutine-path DIRS  where `o<name> call` finds <name>.ngc (':' between\n"
    "                   directories)\n"
    "  --work-limit N   the bound on work of loops and subroutine calls: the lines\n"
    "                   they run and the moves and arc turns beyond one a line\n"
    "                   (default 5000000; a program over it stops at its line)\n"
    "Verification against the part:\n"
    "  --design FILE.stl  the part as designed (a closed mesh, mm): each move that cuts\n"
    "                   into it is told as FILE:LINE:COL: warning: gouge D mm into the\n"
    "                   design; the summary gives gouge and excess volumes\n"
    "  --tolerance MM   deviations within it are none (default half a voxel)\n"
    "  --design-cache DIR|off  where an STL design's band is kept for the next run\n"
    "                   with the same design, voxel and band (default\n"
    "                   $XDG_CACHE_HOME/swarf/designs or ~/.cache/swarf/designs; off:\n"
    "                   read the design every time)\n"
    "  --design-cache-max MB  the cache folder's bound, oldest out first (default 1024)\n"
    "  --fail-on gouge  exit status 4 when a gouge is found (outputs still written)\n"
    "  --report FILE.json  what the run did, per program line and tool, alarms, inputs\n"
    "                   (each line's removed volume is measured cut by cut: the run\n"
    "                   takes ~1.7x as long; --design alone measures only gouges)\n";

static int option_error(const char *flag, const char *what, const char *val) {
  fprintf(stderr, "swarf simulate: %s: %s%s%s%s\n(run `swarf simulate --help` for the options)\n",
          flag, what, val ? " (got \"" : "", val ? val : "", val ? "\")" : "");
  return 2;
}

int swarf_cli_read_point(const char *val, double out[3]) {
  const char *p = val;
  char *end;
  for (int k = 0; k < 3; k++) {
    errno = 0;
    out[k] = strtod(p, &end);
    if (end == p || errno || !isfinite(out[k]) || fabs(out[k]) > 1e6 ||
        *end != (k < 2 ? ',' : '\0'))
      return -1;
    p = end + 1;
  }
  return 0;
}

static int read_triple(const char *flag, const char *val, double out[3]) {
  if (swarf_cli_read_point(val, out) == 0) return 0;
  return option_error(flag, "give X,Y,Z in mm, e.g. 0,0,25", val);
}

/* The options with a value. */
static int value_option(swarf_verify *v, const char *flag, const char *val) {
  char *end;
  if (!strcmp(flag, "--report")) return v->report_path = val, 0;
  if (!strcmp(flag, "--design")) return v->design_path = val, 0;
  if (!strcmp(flag, "--offsets")) return v->offsets = val, 0;
  if (!strcmp(flag, "--subroutine-path")) return v->subroutine_path = val, 0;
  if (!strcmp(flag, "--dialect")) {
    if (swarf_gcode_dialect_from_name(val, NULL) != 0)
      return option_error(flag, "give linuxcnc, fanuc, haas or grbl", val);
    return v->dialect = val, 0;
  }
  if (!strcmp(flag, "--work-limit")) {
    errno = 0;
    v->work_limit = strtol(val, &end, 10);
    if (end == val || *end || errno || v->work_limit < 1 ||
        v->work_limit > SWARF_GCODE_WORK_LIMIT_MAX)
      return option_error(flag, "give a count from 1 to 1000000000", val);
    return 0;
  }
  if (!strcmp(flag, "--start")) return v->start_set = 1, read_triple(flag, val, v->start);
  if (!strcmp(flag, "--g54")) return v->g54_set = 1, read_triple(flag, val, v->g54);
  if (!strcmp(flag, "--units")) {
    if (strcmp(val, "mm") && strcmp(val, "in")) return option_error(flag, "give mm or in", val);
    return v->units = val, 0;
  }
  if (!strcmp(flag, "--fail-on")) {
    if (strcmp(val, "gouge")) return option_error(flag, "the one condition is gouge", val);
    return v->fail_on_gouge = 1, 0;
  }
  if (!strcmp(flag, "--design-cache")) {
    if (val[0] == '\0') return option_error(flag, "give a folder, or off", val);
    if (!strcmp(val, "off")) return v->cache.off = 1, 0;
    return v->cache.dir = val, 0;
  }
  if (!strcmp(flag, "--design-cache-max")) {
    errno = 0;
    const double mb = strtod(val, &end);
    if (end == val || *end || errno || !(mb >= 1 && mb <= 1e7))
      return option_error(flag, "give megabytes, 1 to 10000000", val);
    return v->cache.max_bytes = (long long)(mb * 1024 * 1024), 0;
  }
  errno = 0;
  v->tolerance = strtod(val, &end); /* --tolerance */
  if (end == val || *end || errno || !(v->tolerance > 0 && v->tolerance < 100))
    return option_error(flag, "give a distance in mm, above 0", val);
  return 0;
}

int swarf_verify_option(swarf_verify *v, const char *flag, const char *val, int *i) {
  static const char *mine[] = {
      "--report",     "--design",       "--offsets",          "--start",   "--g54",
      "--units",      "--fail-on",      "--tolerance",        "--dialect", "--subroutine-path",
      "--work-limit", "--design-cache", "--design-cache-max", NULL};
  int k = 0;
  if (!strcmp(flag, "--block-delete")) return v->block_delete = 1, 0;
  if (val != NULL && !strcmp(flag, "--stock")) v->stock_spec = val;
  if (val != NULL && !strcmp(flag, "--machine")) v->machine_spec = val;
  if (val != NULL && !strcmp(flag, "--tool") && v->ntools < SWARF_SIM_MAX_TOOLS)
    v->tool_specs[v->ntools++] = val;
  while (mine[k] != NULL && strcmp(mine[k], flag))
    k++;
  if (mine[k] == NULL) return -1;
  if (val == NULL) return option_error(flag, "needs a value", NULL);
  (*i)++;
  return value_option(v, flag, val);
}

void swarf_verify_note(swarf_verify *v, long line, int column, const char *text) {
  char buf[400];
  if (v->notes < SWARF_VERIFY_NOTES) {
    snprintf(buf, sizeof buf, "%ld:%d: note: %s", line, column, text);
    v->note_text[v->notes] = malloc(strlen(buf) + 1);
    if (v->note_text[v->notes] != NULL) strcpy(v->note_text[v->notes], buf);
  }
  v->notes++;
}

static int check_folder(const char *flag, const char *path) {
  return swarf_cli_output_ok("simulate", flag, path); /* outputs.c */
}

/* CPU time of the process (all threads), s. */
static double process_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int read_design(swarf_verify *v, double voxel) {
  swarf_error err;
  char msg[1024];
  swarf_error_init(&err);
  const double t0 = process_seconds();
  const int band = swarf_stock_design_band(v->frame, voxel, v->tolerance, v->views);
  const swarf_status st = swarf_sim_read_design_cached(v->design_path, voxel, band, &v->cache,
                                                       &v->design, &v->design_cached, &err);
  v->design_read_s = process_seconds() - t0;
  if (st == SWARF_OK) return 0;
  swarf_error_format(&err, msg, sizeof msg);
  fprintf(stderr, "swarf simulate: --design: %s\n", msg);
  return (int)swarf_status_classify(err.status);
}

int swarf_verify_prepare(swarf_verify *v, swarf_sim_config *cfg) {
  if (v->report_path != NULL && check_folder("--report", v->report_path)) return 2;
  if (v->tolerance > 0 && v->design_path == NULL)
    return option_error("--tolerance", "is the design's: give --design too", NULL);
  if (v->fail_on_gouge && v->design_path == NULL)
    return option_error("--fail-on gouge", "needs --design", NULL);
  if (v->design_path != NULL && read_design(v, cfg->voxel)) return 2;
  cfg->units = v->units == NULL          ? 0
               : !strcmp(v->units, "in") ? SWARF_GCODE_UNITS_INCH
                                         : SWARF_GCODE_UNITS_MM;
  cfg->offsets_file = v->offsets;
  if (v->dialect != NULL)
    swarf_gcode_dialect_from_name(v->dialect, (swarf_gcode_dialect *)&cfg->dialect);
  cfg->block_delete = v->block_delete;
  cfg->work_limit = v->work_limit;
  cfg->subroutine_path = v->subroutine_path;
  cfg->g54_set = v->g54_set;
  memcpy(cfg->g54, v->g54, sizeof cfg->g54);
  cfg->start_set = v->start_set;
  memcpy(cfg->start, v->start, sizeof cfg->start);
  cfg->design = v->design;
  cfg->tolerance = v->tolerance;
  cfg->line_volumes = v->report_path != NULL || v->lines_wanted;
  v->report = swarf_report_new();
  if (v->report == NULL) return fputs("swarf simulate: out of memory\n", stderr), 1;
  return 0;
}

void swarf_verify_alarm(swarf_verify *v, const swarf_alarm *a) {
  if (v->report != NULL) swarf_report_add_alarm(v->report, a);
}

void swarf_verify_line(swarf_verify *v, const swarf_line_result *l) {
  if (v->report != NULL) swarf_report_add_line(v->report, l);
}

void swarf_verify_warn(swarf_verify *v, const char *program, const swarf_sim_report *r) {
  size_t n = 0;
  const swarf_alarm *g = v->report ? swarf_report_gouges(v->report, &n) : NULL;
  for (long i = 0; i < v->notes && i < SWARF_VERIFY_NOTES; i++)
    if (v->note_text[i] != NULL) fprintf(stderr, "%s:%s\n", program, v->note_text[i]);
  if (v->notes > SWARF_VERIFY_NOTES)
    fprintf(stderr, "%s: %ld more notes\n", program, v->notes - SWARF_VERIFY_NOTES);
  if (r->units_missing_line > 0 && v->units == NULL)
    fprintf(stderr,
            "%s:%ld:%d: warning: this move comes before any G20/G21: the program is read in "
            "mm (say which with --units mm|in)\n",
            program, r->units_missing_line, r->units_missing_column);
  /* a .vdb design's band ends at its reach: a gouge that reaches it may be deeper */
  const double reach = r->has_deviation ? r->deviation.reach : INFINITY;
  for (size_t i = 0; i < n; i++)
    fprintf(stderr, "%s:%ld:%d: warning: gouge %.3f mm%s into the design\n", program, g[i].line,
            g[i].column, g[i].depth, g[i].depth >= reach * (1 - 1e-9) ? " or more" : "");
}

static void print_point(const double p[3]) {
  if (isfinite(p[0])) printf(" at X%.3f Y%.3f Z%.3f", p[0], p[1], p[2]);
}

/* The program line of the deepest gouge warning (0: none); *n the warnings. */
static long deepest_line(swarf_verify *v, size_t *n) {
  const swarf_alarm *g = v->report ? swarf_report_gouges(v->report, n) : NULL;
  long line = 0;
  double d = 0;
  if (g == NULL) *n = 0;
  for (size_t i = 0; i < *n; i++)
    if (g[i].depth > d) d = g[i].depth, line = g[i].line;
  return line;
}

static void print_design(swarf_verify *v, const swarf_sim_report *r) {
  const swarf_stock_deviation *d = &r->deviation;
  size_t n;
  long line = deepest_line(v, &n);
  printf("  design %s (tolerance %.3f mm): gouge %.1f mm^3", v->design_path, d->tolerance,
         d->gouge_volume);
  if (d->gouge_volume > 0 || d->gouge_depth > 0) {
    printf(", deepest %.3f mm%s", d->gouge_depth, d->gouge_clamped ? " or more" : "");
    print_point(d->gouge_at);
    if (line > 0) printf(" (deepest move: line %ld)", line);
  }
  printf("\n    excess %.1f mm^3", d->excess_volume);
  if (d->excess_volume > 0 || d->excess_height > 0) {
    printf(", largest %.3f mm%s", d->excess_height, d->excess_clamped ? " or more" : "");
    print_point(d->excess_at);
  }
  printf("; gouge warnings on %zu program lines\n", n);
  printf("    design read %.2f s CPU, compared %.2f s CPU%s\n", v->design_read_s, r->design_s,
         v->design_cached ? " (its band from the design cache)" : "");
}

void swarf_verify_summary(swarf_verify *v, const swarf_sim_report *r) {
  double rate = 0;
  int tool = 0;
  long peak = v->report && v->report_path ? swarf_report_peak_mrr(v->report, &rate, &tool) : 0;
  printf("  start: tool tip at X%.3f Y%.3f Z%.3f%s\n", r->start[0], r->start[1], r->start[2],
         r->start_default ? " (default: X0 Y0, 10 mm above the stock, so nothing is cut before "
                            "the first move; --start X,Y,Z to change)"
                          : " (--start)");
  if (r->has_deviation) print_design(v, r);
  if (peak > 0) printf("  peak removal rate %.1f mm^3/min at line %ld (T%d)\n", rate, peak, tool);
}

static swarf_report_inputs report_inputs(const swarf_verify *v, const char *program,
                                         const swarf_sim_config *cfg) {
  swarf_report_inputs in = {program,
                            v->stock_spec,
                            v->machine_spec,
                            v->offsets,
                            v->units,
                            v->design_path,
                            v->tool_specs,
                            v->ntools,
                            cfg->voxel,
                            v->tolerance,
                            v->g54_set ? v->g54 : NULL,
                            v->start_set ? v->start : NULL};
  return in;
}

char *swarf_verify_report_text(swarf_verify *v, const char *program, const swarf_sim_config *cfg,
                               const swarf_sim_report *r, swarf_error *err) {
  const swarf_report_inputs in = report_inputs(v, program, cfg);
  return swarf_report_text(v->report, r, &in, err);
}

int swarf_verify_write_report(swarf_verify *v, const char *program, const swarf_sim_config *cfg,
                              const swarf_sim_report *r) {
  const swarf_report_inputs in = report_inputs(v, program, cfg);
  swarf_error err;
  char msg[1024];
  if (v->report_path == NULL) return 0;
  swarf_error_init(&err);
  if (swarf_report_write(v->report, r, &in, v->report_path, &err) == SWARF_OK) return 0;
  swarf_error_format(&err, msg, sizeof msg);
  fprintf(stderr, "swarf simulate: %s\n", msg);
  return 1;
}

int swarf_verify_finish(const swarf_verify *v, const swarf_sim_report *r) {
  return v->fail_on_gouge && r->alarm_count[SWARF_ALARM_GOUGE] > 0 ? 4 : 0;
}

void swarf_verify_free(swarf_verify *v) {
  for (long i = 0; i < v->notes && i < SWARF_VERIFY_NOTES; i++)
    free(v->note_text[i]);
  v->notes = 0;
  swarf_stock_free(v->design);
  swarf_report_free(v->report);
  v->design = NULL;
  v->report = NULL;
}
