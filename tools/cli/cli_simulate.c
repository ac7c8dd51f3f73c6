/* cli_simulate.c -- `swarf simulate`: options, the run, outputs and summary.
 *
 * Every option is checked before any work starts (so a typo costs nothing),
 * output folders are checked before the simulation, and outputs are written
 * by the stock module atomically (temporary name, then rename).
 */
#include <errno.h>
#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "modbus_service.h"
#include "swarf_sim.h"

static const char help[] =
    "usage: swarf simulate PROGRAM --stock box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX\n"
    "                      --tool T<n>=<shape>,D<diameter>[,R<corner>][,L<length>] ...\n"
    "                      --out FILE.vdb [--mesh FILE.stl] [--image FILE.png]\n"
    "                      [--voxel MM] [--band VOXELS] [--machine NAME[,k=v...]] [--quiet]\n"
    "\n"
    "Plays PROGRAM (RS274/NGC, LinuxCNC dialect) on the machine, removes the exact\n"
    "volume swept by the cutter from the stock and writes the remaining material.\n"
    "\n"
    "  --stock box:...  stock block in the program frame, mm (G20 programs are still\n"
    "                   converted to mm: give the stock in mm)\n"
    "  --stock cylinder:AXIS,RADIUS,START,END  a bar about the x, y or z axis through\n"
    "                   the origin, from START to END along it (rotary work)\n"
    "  --machine NAME   xyz (default); xyza[,pivot=Y,Z] (rotary table about X);\n"
    "                   xyzac-trt or xyzbc-trt[,mode=tcp|joint][,pivot=X,Y,Z] (5-axis\n"
    "                   table-rotary-tilting, tool-centre-point mode by default)\n"
    "  --tool T1=ball,D3.175,L25   a cutter: shape ball, flat or bull; D diameter,\n"
    "                   R corner radius (bull), L cutting length above the tip\n"
    "                   (default 4*D). Repeat for several tools; a single tool is\n"
    "                   loaded at the start, otherwise T<n> M6 selects one.\n"
    "                   The controlled point is the tool tip (bottom centre).\n"
    "  --voxel MM       voxel edge (default 0.2); halving it takes ~4x the time\n"
    "  --band N         narrow band half width in voxels (default 3, at least 3)\n"
    "  --out FILE.vdb   remaining material: OpenVDB float level set named \"stock\"\n"
    "  --mesh FILE.stl  its surface as a binary STL\n"
    "  --image FILE.png a shaded picture of it (OpenVDB's level-set ray tracer)\n"
    "  --quiet          no progress bar and no summary\n"
    "  --stamp MM       benchmark baseline: stamp the cutter every MM along each move\n"
    "                   instead of sweeping it exactly (what stamping simulators do)\n"
    "\n"
    "Exit status 0 on success, 2 on bad input (message FILE:LINE:COL: ...), 1 on an\n"
    "internal failure. Nothing is written unless the whole program ran.\n";

typedef struct {
  const char *program, *out, *mesh, *image;
  int quiet;
  swarf_sim_config cfg;
  swarf_modbus_options modbus;
} sim_options;

/* What the run's callbacks reach: the progress bar and the Modbus service. */
typedef struct {
  swarf_progress *bar; /* NULL when quiet */
  swarf_modbus_service *modbus;
} sim_clients;

static int usage_error(const char *what) {
  fprintf(stderr, "swarf simulate: %s\n(run `swarf simulate --help` for the options)\n", what);
  return 2;
}

static int read_double(const char *flag, const char *text, double lo, double *out) {
  char *end, what[160];
  errno = 0;
  *out = strtod(text, &end);
  if (end == text || *end != '\0' || errno || !isfinite(*out) || *out < lo) {
    snprintf(what, sizeof what, "%s: \"%s\" is not a number >= %g", flag, text, lo);
    return usage_error(what);
  }
  return 0;
}

/* One option at argv[*i]; advances *i past its value. */
static int parse_option(sim_options *o, int argc, char **argv, int *i) {
  const char *flag = argv[*i], *val = *i + 1 < argc ? argv[*i + 1] : NULL;
  char msg[256];
  double d;
  int rc = swarf_modbus_option(&o->modbus, flag, val, i);
  if (rc >= 0) return rc;
  if (!strcmp(flag, "--quiet")) return o->quiet = 1, 0;
  if (val == NULL) {
    snprintf(msg, sizeof msg, "%s needs a value", flag);
    return usage_error(msg);
  }
  (*i)++;
  if (!strcmp(flag, "--out")) return o->out = val, 0;
  if (!strcmp(flag, "--mesh")) return o->mesh = val, 0;
  if (!strcmp(flag, "--image")) return o->image = val, 0;
  if (!strcmp(flag, "--voxel")) {
    if (read_double(flag, val, 1e-3, &o->cfg.voxel)) return 2;
    return 0;
  }
  if (!strcmp(flag, "--band")) {
    if (read_double(flag, val, 3, &d) || d > 64) return usage_error("--band: give 3 to 64 voxels");
    return o->cfg.half_width = (int)d, 0;
  }
  if (!strcmp(flag, "--batch")) {
    if (read_double(flag, val, 1, &d)) return 2;
    return o->cfg.batch = (int)d, 0;
  }
  if (!strcmp(flag, "--stamp")) {
    if (read_double(flag, val, 1e-3, &o->cfg.stamp_step)) return 2;
    return 0;
  }
  if (!strcmp(flag, "--stock")) {
    swarf_error err;
    if (swarf_sim_parse_stock(val, &o->cfg.stock, &err)) return usage_error(err.message);
    return 0;
  }
  if (!strcmp(flag, "--machine")) {
    swarf_error err;
    if (swarf_machine_parse(&o->cfg.machine, val, &err) != SWARF_OK) return usage_error(err.message);
    return 0;
  }
  if (!strcmp(flag, "--tool")) return -1; /* handled by the caller */
  snprintf(msg, sizeof msg, "unknown option \"%s\"", flag);
  return usage_error(msg);
}

static int add_tool(sim_options *o, const char *spec) {
  char msg[600];
  swarf_sim_tool t;
  swarf_error err;
  if (swarf_sim_parse_tool(spec, &t, &err)) return usage_error(err.message);
  if (swarf_sim_config_add_tool(&o->cfg, &t, &err)) {
    snprintf(msg, sizeof msg, "--tool: %s", err.message);
    return usage_error(msg);
  }
  return 0;
}

/* Refuse an output whose folder does not exist or is not writable. */
static int check_output(const char *flag, const char *path) {
  char copy[4096], what[4200];
  if (path == NULL) return 0;
  snprintf(copy, sizeof copy, "%s", path);
  if (access(dirname(copy), W_OK) == 0) return 0;
  snprintf(what, sizeof what, "%s: cannot write \"%s\": %s", flag, path, strerror(errno));
  return usage_error(what);
}

static int parse_args(sim_options *o, int argc, char **argv) {
  int have_stock = 0, rc;
  memset(o, 0, sizeof *o);
  swarf_sim_config_init(&o->cfg);
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) return fputs(help, stdout), fputs(swarf_modbus_help, stdout), 1;
    if (argv[i][0] != '-' || argv[i][1] == '\0') {
      if (o->program) return usage_error("give one PROGRAM only");
      o->program = argv[i];
      continue;
    }
    have_stock |= !strcmp(argv[i], "--stock");
    rc = parse_option(o, argc, argv, &i);
    if (rc == -1) rc = add_tool(o, argv[i]);
    if (rc) return rc;
  }
  if (!o->program) return usage_error("no PROGRAM given");
  if (!have_stock) return usage_error("--stock box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX is required");
  if (o->cfg.ntools == 0) return usage_error("--tool is required, e.g. --tool T1=ball,D3.175");
  if (!o->out) return usage_error("--out FILE.vdb is required");
  return check_output("--out", o->out) || check_output("--mesh", o->mesh) ||
                 check_output("--image", o->image)
             ? 2
             : 0;
}

/* Refuse a voxel so small that the narrow band of the box would not fit in
 * memory (about 4.5 bytes per active voxel plus tree overhead). */
static int check_size(const swarf_sim_config *cfg) {
  double d[3], area, voxels;
  char what[256];
  for (int k = 0; k < 3; k++) d[k] = cfg->stock.hi[k] - cfg->stock.lo[k];
  area = 2.0 * (d[0] * d[1] + d[1] * d[2] + d[0] * d[2]);
  voxels = area / (cfg->voxel * cfg->voxel) * 2.0 * cfg->half_width;
  if (voxels < 2e9) return 0;
  snprintf(what, sizeof what,
           "--voxel %g: the stock's surface alone would need ~%.0f GB; use --voxel %.3g or more",
           cfg->voxel, voxels * 8.0 / 1e9, cfg->voxel * sqrt(voxels / 2e9) * 1.01);
  return usage_error(what);
}

static int write_outputs(const sim_options *o, const swarf_stock *stock, size_t *ntri) {
  char msg[512];
  int rc = swarf_stock_write_vdb(stock, o->out, msg, sizeof msg);
  if (rc == 0 && o->mesh) rc = swarf_stock_write_stl(stock, o->mesh, ntri, msg, sizeof msg);
  if (rc == 0 && o->image) rc = swarf_stock_write_png(stock, o->image, 1024, 768, msg, sizeof msg);
  if (rc != 0) fprintf(stderr, "swarf simulate: %s\n", msg);
  return rc == 0 ? 0 : 1;
}

/* Each alarm (up to the report's record of them) as a located warning. */
static void print_alarms(const sim_options *o, const swarf_sim_report *r) {
  long rapids = r->alarm_count[SWARF_ALARM_RAPID], told = 0;
  for (long i = 0; i < r->alarms && i < SWARF_SIM_MAX_ALARMS; i++) {
    if (r->alarm[i].kind != SWARF_ALARM_RAPID) continue;
    fprintf(stderr, "%s:%ld:%d: warning: rapid move (G0) cuts into the material\n", o->program,
            r->alarm[i].line, r->alarm[i].column);
    told++;
  }
  if (rapids > told)
    fprintf(stderr, "%s: warning: %ld more rapid moves cut into the material\n", o->program,
            rapids - told);
}

static void print_summary(const sim_options *o, const swarf_stock *stock,
                          const swarf_sim_report *r, double total_s, size_t ntri) {
  double removed = r->volume_before - r->volume_after;
  printf("swarf: %s\n", o->program);
  printf("  lines %ld, moves %ld (%ld rapid, %ld arcs), %ld cutting the stock, %ld tool changes\n",
         r->lines, r->moves, r->rapids, r->arcs, r->cutting_moves, r->tool_changes);
  printf("  path %.1f mm, machining time %.1f min at programmed feeds\n", r->path_mm,
         r->machining_s / 60.0);
  printf("  stock %.1f mm^3, removed %.1f mm^3 (%.1f%%), remaining %.1f mm^3\n",
         r->volume_before, removed, r->volume_before > 0 ? 100.0 * removed / r->volume_before : 0.0,
         r->volume_after);
  printf("  alarms %ld (rapid moves cutting into material)\n", r->alarms);
  printf("  simulation %.2f s (%.0f moves/s), total %.2f s\n", r->seconds,
         r->seconds > 0 ? r->moves / r->seconds : 0.0, total_s);
  printf("  grid: voxel %g mm, active voxels %llu\n", swarf_stock_voxel(stock),
         swarf_stock_active_voxels(stock));
  printf("  wrote %s", o->out);
  if (o->mesh) printf(", %s (%zu triangles)", o->mesh, ntri);
  if (o->image) printf(", %s", o->image);
  printf("\n");
}

static int on_progress(void *user, const swarf_sim_progress *p) {
  sim_clients *c = user;
  if (c->bar != NULL) swarf_progress_update(c->bar, p->fraction, p->report->moves);
  return swarf_modbus_observe(c->modbus, p);
}

/* The run's failure on stderr; returns the exit status. */
static int report_failure(const swarf_error *e, const swarf_modbus_service *mb) {
  char msg[1024];
  if (e->status == SWARF_ERR_ABORTED && swarf_modbus_aborted(mb))
    fprintf(stderr, "%s:%ld: aborted by a Modbus command\n", e->file, e->line);
  else {
    swarf_error_format(e, msg, sizeof msg);
    fprintf(stderr, "%s\n", msg);
  }
  return (int)swarf_status_classify(e->status);
}

int swarf_cli_simulate(int argc, char **argv) {
  sim_options o;
  swarf_sim_report rep;
  swarf_stock *stock = NULL;
  swarf_progress pb;
  swarf_modbus_service *mb = NULL;
  swarf_error err;
  size_t ntri = 0;
  int rc = parse_args(&o, argc, argv);
  if (rc == 1) return 0;
  if (rc || (rc = check_size(&o.cfg))) return rc;
  if ((rc = swarf_modbus_start(&o.modbus, o.program, &mb))) return rc;
  swarf_progress_init(&pb);
  sim_clients clients = {o.quiet ? NULL : &pb, mb};
  o.cfg.cb.progress = on_progress;
  o.cfg.cb.user = &clients;
  swarf_error_init(&err);
  if (swarf_sim_run(&o.cfg, o.program, &stock, &rep, &err) != SWARF_OK) {
    swarf_progress_finish(&pb);
    rc = report_failure(&err, mb);
    swarf_modbus_finish(mb, rc, &rep);
    return rc;
  }
  swarf_progress_finish(&pb);
  print_alarms(&o, &rep);
  rc = write_outputs(&o, stock, &ntri);
  if (rc == 0 && !o.quiet) print_summary(&o, stock, &rep, swarf_progress_now() - pb.start, ntri);
  swarf_modbus_finish(mb, rc, &rep);
  swarf_stock_free(stock);
  return rc;
}
