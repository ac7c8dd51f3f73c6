/* SPDX-License-Identifier: MPL-2.0 */
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
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "cli_mpi.h"
#include "cli_stock.h"
#include "html.h"
#include "modbus_service.h"
#include "stock_output.h"
#include "swarf_sim.h"
#include "verify.h"

static const char help[] =
    "usage: swarf simulate PROGRAM --stock box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX\n"
    "                      --tool T<n>=<family>,<fields> ...\n"
    "                      --out FILE.vdb [--mesh FILE.stl|.obj|.ply] [--image FILE.png]\n"
    "                      [--voxel MM] [--band VOXELS] [--machine NAME[,k=v...]] [--quiet]\n"
    "\n"
    "Plays PROGRAM (RS274/NGC, LinuxCNC dialect) on the machine, removes the exact\n"
    "volume swept by the cutter from the stock and writes the remaining material.\n"
    "\n"
    "  --stock box:...  stock block in the program frame, mm (G20 programs are still\n"
    "                   converted to mm: give the stock in mm)\n"
    "  --stock cylinder:AXIS,RADIUS,START,END  a bar about the x, y or z axis through\n"
    "                   the origin, from START to END along it (rotary work)\n"
    "                   (stocks from files, --stock-transform, mesh formats and\n"
    "                   views: below)\n"
    "  --machine NAME   xyz (default); xyza[,pivot=Y,Z] (rotary table about X);\n"
    "                   xyzac-trt or xyzbc-trt[,mode=tcp|joint][,pivot=X,Y,Z] (5-axis\n"
    "                   table-rotary-tilting, tool-centre-point mode by default);\n"
    "                   xyzab-tdr[,mode=tcp|joint][,pivot=X,Y,Z] (B cradle carrying\n"
    "                   an A table); xyzbc-hh[,mode=tcp|joint][,head=L] (spindle head:\n"
    "                   C carrying B); xyzbc-ht[,mode=tcp|joint][,pivot=X,Y][,head=L]\n"
    "                   (head B, table C about Z through X,Y). head=L: the head's\n"
    "                   pivot, mm above the gauge line (the tool's length is added);\n"
    "                   needed in joint mode. Directions: tools/doc/machines.md\n"
    "  --tool T1=ball,D3.175,L25   a cutter: T number = family, fields (mm, angles in\n"
    "                   degrees; L is the cutting length above the tip, default 4*D):\n"
    "     flat|ball|bull,D<d>[,R<corner>][,L]   end mills (bull needs R; flutes may be\n"
    "                   shorter than D)\n"
    "     vee,D<d>,A<included angle>[,L]        V-bit / engraver, sharp tip\n"
    "     drill,D<d>[,A<point angle, 118>][,L]  twist drill\n"
    "     spot,D<d>[,A<point angle, 90>][,L]    spot drill\n"
    "     chamfer,D<d>,A<included angle>[,T<tip diameter, 0>][,L]   chamfer mill\n"
    "     taper,D<tip diameter>,A<half-angle>[,R<tip radius>][,L]  tapered flat/ball\n"
    "     apt,D,R,E,F,A<alpha>,B<beta>,H        APT 7-parameter cutter: corner circle\n"
    "                   (E, F, R), bottom at alpha through the tip (F = (R + E sin A)/\n"
    "                   cos A), side at beta from the axis (D = 2 (E + R/cos B)) to H\n"
    "     lollipop,D<sphere>,K<neck diameter>[,L]       undercut ball (non-convex)\n"
    "     dovetail,D<bottom>,A<flank to base>,H<flank height>[,K<neck>][,L]\n"
    "     tslot,D<d>,H<disk thickness>,K<neck diameter>[,L]\n"
    "     qss,a,b,e,f   the paper's QSS of revolution h = a(x^2+y^2) + b z^2 + e z + f\n"
    "                   (mm), its lowest point at the tip (convex or not, e.g. 2,3,0,0\n"
    "                   or 3,-3,0,0)\n"
    "                   Repeat for several tools; a single tool is loaded at the start,\n"
    "                   otherwise T<n> M6 selects one. The controlled point is the\n"
    "                   tool tip (bottom centre).\n"
    "                   Assembly fields: S<mm> stick-out (tip to holder face) and\n"
    "                   N<mm> shank diameter (default D) from L to S, e.g.\n"
    "                   T1=flat,D6,L10,S25: shank and holder never cut; entering\n"
    "                   material is a collision. Without S nothing above L exists.\n"
    "  --holder T1=20x40,20-32x10   the holder of T1: cylinders DxH and cones\n"
    "                   D1-D2xH (bottom-top diameter), stacked up from the holder\n"
    "                   face (mm); needs the tool's S\n"
    "  --tool-table FILE  a LinuxCNC tool table (T1 P1 D6 Z+30 ;comment): tool\n"
    "                   numbers, diameters (flat end mills unless described\n"
    "                   otherwise) and G43 lengths: G43 H<n> moves the controlled\n"
    "                   point as the machine does\n"
    "  --tool-table-units mm|in  the table's unit (default mm)\n"
    "  --tool-library FILE  full assemblies in JSON (tools/doc/simulate.md);\n"
    "                   --tool and --holder override the table and the library\n"
    "  --fixture box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX | stl:FILE   a body (vice,\n"
    "                   clamp; a box or a closed STL mesh, mm, workpiece frame) no\n"
    "                   part of the tool may enter, cutter included; repeatable\n"
    "  --fail-on no-tool  exit status 4 after the run (outputs written) when a feed\n"
    "                   move ran into the material with an empty spindle (T0 M6)\n"
    "  --fail-on collision  exit status 4 after the run (outputs written) when a\n"
    "                   shank, holder or fixture collision was found\n"
    "  --collision-depths N  measure the depth of the first N collisions of each\n"
    "                   kind (default 100, the warnings printed; 0: all)\n"
    "  --voxel MM       voxel edge (default 0.2); halving it takes ~4x the time\n"
    "  --band N         narrow band half width in voxels (default 3, at least 3)\n"
    "  --out FILE.vdb   remaining material: OpenVDB float level set named \"stock\"\n"
    "  --image FILE.png a shaded picture of it (OpenVDB's level-set ray tracer;\n"
    "                   with --design, coloured by the deviation, with a legend)\n"
    "  --quiet          no progress bar and no summary\n"
    "  --threads N      threads for the whole run (default 0: all cores)\n"
    "  --stamp MM       benchmark baseline: stamp the cutter every MM along each move\n"
    "                   instead of sweeping it exactly (what stamping simulators do)\n"
    "  --balance N      after the run, how evenly 2 to N processes would share the\n"
    "                   removal (busiest rank's voxels over the mean; one process)\n"
    "  --batch N        moves removed from the stock per pass (default 1024): fewer\n"
    "                   keep less memory on long 5-axis moves, the grid is the same\n"
    "\n"
    "Several processes (tools/doc/mpi.md): under mpirun or srun every rank plays the\n"
    "whole program on its slab of the stock; rank 0 prints and writes the same\n"
    "outputs, voxel for voxel, as one process. Every rank needs the program and\n"
    "the input files; only rank 0 writes.\n"
    "\n"
    "Exit status 0 on success, 2 on bad input (message FILE:LINE:COL: ..., or\n"
    "FILE:LINE: for tool tables and libraries), 1 on an internal failure, 3 aborted\n"
    "by a Modbus command, 4 with --fail-on gouge, collision or no-tool when one was\n"
    "found. Nothing is written unless the whole program ran.\n";

#define MAX_SPECS 128

typedef struct {
  const char *program, *out, *mesh, *image, *html;
  int quiet, fail_on_collision, fail_on_no_tool;
  int balance; /* --balance N */
  swarf_sim_config cfg;
  swarf_modbus_options modbus;
  swarf_verify verify;
  swarf_cli_stock stock; /* stocks from files, placement, views */
  /* tool descriptions, applied in this order once all options are read */
  const char *tool_table, *tool_library;
  double table_mm_per_unit;
  const char *tools[MAX_SPECS], *holders[MAX_SPECS];
  int ntools, nholders;
} sim_options;

/* Alarms as they come (printed after the run, in program order). */
#define MAX_KEPT_ALARMS 10000
typedef struct {
  swarf_alarm *a;
  long n, cap, dropped;
} alarm_list;

/* What the run's callbacks reach: the progress bar, the Modbus service, the
 * verification (alarms, lines). */
typedef struct {
  swarf_progress *bar; /* NULL when quiet */
  swarf_modbus_service *modbus;
  swarf_verify *verify;
  alarm_list alarms;
  swarf_html *html; /* --html: the moves (rank 0) */
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

/* The Modbus service of the options (none without --modbus flags): 0, or
 * the exit status after saying what is wrong. */
static int start_modbus(const sim_options *o, swarf_modbus_service **mb) {
  swarf_error err;
  swarf_error_init(&err);
  if (swarf_modbus_start(&o->modbus, o->program, mb, &err) == SWARF_OK) return 0;
  fprintf(stderr, "swarf simulate: %s\n", err.message);
  return (int)swarf_status_classify(err.status);
}

/* One option at argv[*i]; advances *i past its value. */
static int parse_option(sim_options *o, int argc, char **argv, int *i) {
  const char *flag = argv[*i], *val = *i + 1 < argc ? argv[*i + 1] : NULL;
  char msg[256];
  double d;
  int rc = swarf_modbus_option(&o->modbus, flag, val, i);
  if (rc >= 0) return rc;
  if (!strcmp(flag, "--fail-on") && val != NULL && !strcmp(val, "collision"))
    return (*i)++, o->fail_on_collision = 1, 0;
  if (!strcmp(flag, "--fail-on") && val != NULL && !strcmp(val, "no-tool"))
    return (*i)++, o->fail_on_no_tool = 1, 0;
  if ((rc = swarf_verify_option(&o->verify, flag, val, i)) >= 0) return rc;
  if ((rc = swarf_cli_stock_option(&o->stock, flag, val, i)) >= 0) return rc;
  if (!strcmp(flag, "--quiet")) return o->quiet = 1, 0;
  if (val == NULL) {
    snprintf(msg, sizeof msg, "%s needs a value", flag);
    return usage_error(msg);
  }
  (*i)++;
  if (!strcmp(flag, "--out")) return o->out = val, 0;
  if (!strcmp(flag, "--mesh")) return o->mesh = val, 0;
  if (!strcmp(flag, "--image")) return o->image = val, 0;
  if (!strcmp(flag, "--html")) return o->html = val, 0;
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
  if (!strcmp(flag, "--threads")) {
    if (read_double(flag, val, 0, &d)) return 2;
    if (d > 4096 || d != floor(d)) return usage_error("--threads: give 0 (all cores) to 4096");
    return o->cfg.threads = (int)d, 0;
  }
  if (!strcmp(flag, "--balance")) {
    if (read_double(flag, val, 2, &d) || d > 1024) return usage_error("--balance: give 2 to 1024");
    return o->balance = (int)d, o->cfg.tally = 1, 0;
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
    if (swarf_machine_parse(&o->cfg.machine, val, &err) != SWARF_OK)
      return usage_error(err.message);
    return 0;
  }
  if (!strcmp(flag, "--tool") || !strcmp(flag, "--holder")) {
    int *n = flag[2] == 't' ? &o->ntools : &o->nholders;
    if (*n == MAX_SPECS) return usage_error("too many --tool or --holder options");
    (flag[2] == 't' ? o->tools : o->holders)[(*n)++] = val;
    return 0;
  }
  if (!strcmp(flag, "--tool-table")) return o->tool_table = val, 0;
  if (!strcmp(flag, "--tool-library")) return o->tool_library = val, 0;
  if (!strcmp(flag, "--tool-table-units")) {
    if (strcmp(val, "mm") && strcmp(val, "in"))
      return usage_error("--tool-table-units: give mm or in");
    return o->table_mm_per_unit = val[0] == 'i' ? 25.4 : 1.0, 0;
  }
  if (!strcmp(flag, "--fixture")) {
    swarf_error err;
    if (o->cfg.nfixtures == SWARF_SIM_MAX_FIXTURES) return usage_error("--fixture: 16 at most");
    if (swarf_sim_parse_fixture(val, &o->cfg.fixtures[o->cfg.nfixtures], &err))
      return usage_error(err.message);
    return o->cfg.nfixtures++, 0;
  }
  if (!strcmp(flag, "--collision-depths")) {
    if (read_double(flag, val, 0, &d) || d != floor(d) || d > 1e9)
      return usage_error("--collision-depths: give a whole number (0: all)");
    return o->cfg.collision_depths = (long)d, 0;
  }
  snprintf(msg, sizeof msg, "unknown option \"%s\"", flag);
  return usage_error(msg);
}

/* A tool table's or library's error: FILE:LINE: what is wrong. */
static int file_error(const swarf_error *e) {
  char msg[1024];
  swarf_error_format(e, msg, sizeof msg);
  fprintf(stderr, "%s\n", msg);
  return 2;
}

/* The tool table: the table, then the library, then each --tool and --holder. */
static int build_tools(sim_options *o) {
  swarf_error err;
  char msg[700];
  swarf_error_init(&err);
  if (o->tool_table &&
      swarf_sim_config_load_tool_table(&o->cfg, o->tool_table, o->table_mm_per_unit, &err))
    return file_error(&err);
  if (o->tool_library && swarf_sim_config_load_tool_library(&o->cfg, o->tool_library, &err))
    return file_error(&err);
  int given[MAX_SPECS];
  for (int i = 0; i < o->ntools; i++) {
    swarf_sim_tool t;
    if (swarf_sim_parse_tool(o->tools[i], &t, &err)) return usage_error(err.message);
    given[i] = t.number;
    for (int k = 0; k < i; k++)
      if (given[k] == t.number) {
        snprintf(msg, sizeof msg, "--tool: T%d is given twice", t.number);
        return usage_error(msg);
      }
    if (swarf_sim_config_put_tool(&o->cfg, &t, &err)) return usage_error(err.message);
  }
  for (int i = 0; i < o->nholders; i++) {
    swarf_sim_tool t;
    if (swarf_sim_parse_holder(o->holders[i], &t, &err) ||
        swarf_sim_config_put_holder(&o->cfg, &t, &err))
      return usage_error(err.message);
  }
  for (int i = 0; i < o->cfg.ntools; i++)
    if (swarf_sim_check_tool(&o->cfg.tools[i], &err)) return usage_error(err.message);
  return 0;
}

/* 0 on the rank that writes (rank 0, or the one process). */
static int writer_rank = 0;

/* Every output can be written and none is an input or another output
 * (outputs.c), checked before any work, where the outputs are written (rank 0). */
static int check_outputs(const sim_options *o) {
  const swarf_cli_path outs[] = {{"--out", o->out},
                                 {"--mesh", o->mesh},
                                 {"--image", o->image},
                                 {"--report", o->verify.report_path},
                                 {"--html", o->html}};
  const int nouts = sizeof outs / sizeof outs[0];
  const swarf_cli_path ins[] = {{"PROGRAM", o->program},
                                {"--stock", o->stock.file},
                                {"--design", o->verify.design_path},
                                {"--tool-table", o->tool_table},
                                {"--tool-library", o->tool_library},
                                {"--offsets", o->verify.offsets}};
  swarf_cli_path fixtures[SWARF_SIM_MAX_FIXTURES];
  int nfix = 0;
  struct stat st;
  if (writer_rank != 0) return 0;
  for (size_t i = 0; i < sizeof outs / sizeof outs[0]; i++)
    if (swarf_cli_output_ok("simulate", outs[i].flag, outs[i].path)) return 2;
  if (o->out != NULL && stat(o->out, &st) == 0 && S_ISFIFO(st.st_mode)) {
    fprintf(stderr,
            "swarf simulate: --out: cannot write \"%s\": it is a FIFO, and a .vdb is written "
            "with seeks back to its header; write a file and copy it\n",
            o->out);
    return 2;
  }
  for (int i = 0; i < o->cfg.nfixtures; i++)
    if (o->cfg.fixtures[i].stl != NULL)
      fixtures[nfix++] = (swarf_cli_path){"--fixture", o->cfg.fixtures[i].stl};
  if (swarf_cli_outputs_distinct("simulate", outs, nouts, ins, 6) ||
      swarf_cli_outputs_distinct("simulate", outs, nouts, fixtures, nfix))
    return 2;
  return swarf_cli_outputs_outside("simulate", outs, nouts, "--subroutine-path",
                                   o->verify.subroutine_path, ".ngc");
}

static int parse_args(sim_options *o, int argc, char **argv) {
  int have_stock = 0, rc;
  memset(o, 0, sizeof *o);
  swarf_sim_config_init(&o->cfg);
  o->table_mm_per_unit = 1.0;
  o->cfg.collision_depths = 100; /* the warnings printed; the rest are counted */
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h"))
      return fputs(help, stdout), fputs("\nStock from files, placement and outputs:\n", stdout),
             fputs(swarf_cli_stock_help, stdout), fputs(swarf_verify_help, stdout),
             fputs(swarf_modbus_help, stdout), 1;
    if (argv[i][0] != '-' || argv[i][1] == '\0') {
      if (o->program) return usage_error("give one PROGRAM only");
      o->program = argv[i];
      continue;
    }
    have_stock |= !strcmp(argv[i], "--stock");
    if ((rc = parse_option(o, argc, argv, &i))) return rc;
  }
  if (!o->program) return usage_error("no PROGRAM given");
  if (!have_stock) return usage_error("--stock box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX is required");
  if ((rc = build_tools(o))) return rc;
  if (o->cfg.ntools == 0)
    return usage_error("--tool (or --tool-table, --tool-library) is required, e.g. --tool "
                       "T1=ball,D3.175");
  if (!o->out) return usage_error("--out FILE.vdb is required");
  if (swarf_cli_mesh_name("--mesh", o->mesh)) return 2;
  if (o->html != NULL && !swarf_html_available())
    return usage_error("--html: this swarf was built without three.js (libjs-three)");
  return check_outputs(o);
}

/* The voxel against the stock and the memory (the library's check, before
 * any other work: its message says what to give). */
static int check_size(const swarf_sim_config *cfg) {
  swarf_error err;
  swarf_error_init(&err);
  char flagged[sizeof err.message + 2];
  if (swarf_sim_config_check(cfg, 1, &err) == SWARF_OK) return 0;
  snprintf(flagged, sizeof flagged, "--%s", err.message); /* it starts with the setting's name */
  return usage_error(flagged);
}

/* The .vdb, mesh, picture and report: all or none (held unnamed,
 * published together once all are written; stock_output.h). */
/* The --html page in memory, before the outputs are written (its mesh is a
 * temporary file): 0, or the exit status after a message. */
static int render_page(sim_options *o, swarf_html *html, const swarf_stock *stock,
                       const swarf_sim_report *rep, char **page, size_t *len) {
  swarf_error err;
  char msg[1024], *report;
  swarf_html_page pg = {o->program,
                        stock,
                        o->verify.design,
                        o->cfg.tolerance > 0 ? o->cfg.tolerance : 0.5 * swarf_stock_voxel(stock),
                        &o->cfg,
                        rep,
                        NULL};
  swarf_error_init(&err);
  if (o->html == NULL) return 0;
  if ((report = swarf_verify_report_text(&o->verify, o->program, &o->cfg, rep, &err)) != NULL) {
    pg.report_json = report;
    swarf_html_render(html, &pg, page, len, &err);
    free(report);
  }
  if (*page != NULL) return 0;
  swarf_error_format(&err, msg, sizeof msg);
  fprintf(stderr, "swarf simulate: --html: %s\n", msg);
  return (int)swarf_status_classify(err.status);
}

static int write_outputs(sim_options *o, swarf_html *html, const swarf_stock *stock,
                         const swarf_sim_report *rep, size_t *ntri) {
  swarf_error err;
  char *page = NULL;
  size_t len = 0;
  int rc = render_page(o, html, stock, rep, &page, &len);
  if (rc != 0) return rc;
  swarf_error_init(&err);
  swarf_stock_outputs_begin();
  if (swarf_stock_write_vdb(stock, o->out, &err) != SWARF_OK) {
    char msg[1024];
    swarf_stock_outputs_abort();
    swarf_error_format(&err, msg, sizeof msg); /* FILE: what */
    fprintf(stderr, "swarf simulate: %s\n", msg);
    return (int)swarf_status_classify(err.status);
  }
  rc = swarf_cli_write_views("simulate", stock, o->mesh, o->image, o->verify.design,
                             o->verify.tolerance, o->stock.view, ntri);
  if (rc == 0) rc = swarf_verify_write_report(&o->verify, o->program, &o->cfg, rep);
  if (rc == 0 && page != NULL && swarf_stock_output_write(o->html, page, len, &err) != SWARF_OK) {
    char msg[1024];
    swarf_error_format(&err, msg, sizeof msg);
    fprintf(stderr, "swarf simulate: --html: %s\n", msg);
    rc = (int)swarf_status_classify(err.status);
  }
  free(page);
  if (rc != 0) {
    swarf_stock_outputs_abort();
    return rc;
  }
  if (swarf_stock_outputs_commit(&err) != SWARF_OK) {
    char msg[1024];
    swarf_error_format(&err, msg, sizeof msg);
    fprintf(stderr, "swarf simulate: %s\n", msg);
    return 1;
  }
  return 0;
}

static void print_alarm(const sim_options *o, const swarf_alarm *a) {
  static const char *part[] = {"cutter", "shank", "holder"};
  char deep[48] = "";
  if (isfinite(a->depth)) snprintf(deep, sizeof deep, " (%.1f mm deep)", a->depth);
  fprintf(stderr, "%s:%ld:%d: warning: ", o->program, a->line, a->column);
  switch (a->kind) {
  case SWARF_ALARM_RAPID:
    fprintf(stderr, "rapid move (G0) cuts into the material\n");
    break;
  case SWARF_ALARM_SHANK:
  case SWARF_ALARM_HOLDER:
    fprintf(stderr, "%s of T%d hits the material%s\n", part[a->kind == SWARF_ALARM_SHANK ? 1 : 2],
            a->tool, deep);
    break;
  case SWARF_ALARM_FIXTURE:
    fprintf(stderr, "T%d %s hits fixture %d%s\n", a->tool,
            part[a->part >= 0 && a->part <= 2 ? a->part : 0], a->index, deep);
    break;
  case SWARF_ALARM_NO_TOOL:
    fprintf(stderr, "feed move with an empty spindle (T0) runs into the material: load a tool "
                    "(T<n> M6) before cutting\n");
    break;
  default:
    fprintf(stderr, "alarm %d\n", (int)a->kind);
  }
}

/* Each alarm as a located warning, in program order: the first 100 of each
 * kind, then how many more. */
static void print_alarms(const sim_options *o, const alarm_list *l, const swarf_sim_report *r) {
  static const char *what[] = {"rapid moves cut into the material",
                               "shank collisions",
                               "holder collisions",
                               "fixture collisions",
                               "gouges",
                               "feed moves with an empty spindle"};
  long told[SWARF_ALARM_KINDS] = {0};
  for (long i = 0; i < l->n; i++) {
    const swarf_alarm *a = &l->a[i];
    if ((unsigned)a->kind >= SWARF_ALARM_KINDS || a->kind == SWARF_ALARM_GOUGE ||
        told[a->kind]++ >= 100)
      continue;
    print_alarm(o, a);
  }
  for (int k = 0; k < SWARF_ALARM_KINDS; k++) {
    if (k == SWARF_ALARM_GOUGE) continue;
    long shown = told[k] < 100 ? told[k] : 100;
    if (r->alarm_count[k] > shown)
      fprintf(stderr, "%s: warning: %ld more %s\n", o->program, r->alarm_count[k] - shown, what[k]);
  }
}

static void print_summary(const sim_options *o, const swarf_stock *stock, const swarf_sim_report *r,
                          double total_s, size_t ntri) {
  double removed = r->volume_before - r->volume_after;
  printf("swarf: %s\n", o->program);
  printf("  lines %ld, moves %ld (%ld rapid, %ld arcs), %ld cutting the stock, %ld tool changes\n",
         r->lines, r->moves, r->rapids, r->arcs, r->cutting_moves, r->tool_changes);
  printf("  path %.1f mm, machining time %.1f min at programmed feeds\n", r->path_mm,
         r->machining_s / 60.0);
  printf("  stock %.1f mm^3, removed %.1f mm^3 (%.1f%%), remaining %.1f mm^3\n", r->volume_before,
         removed, r->volume_before > 0 ? 100.0 * removed / r->volume_before : 0.0, r->volume_after);
  printf("  alarms %ld (%ld rapid moves cutting into material, %ld moves gouging the design, %ld "
         "collisions: %ld shank, %ld holder, %ld fixture)\n",
         r->alarms, r->alarm_count[SWARF_ALARM_RAPID], r->alarm_count[SWARF_ALARM_GOUGE],
         r->collisions, r->alarm_count[SWARF_ALARM_SHANK], r->alarm_count[SWARF_ALARM_HOLDER],
         r->alarm_count[SWARF_ALARM_FIXTURE]);
  if (r->alarm_count[SWARF_ALARM_NO_TOOL] > 0)
    printf("  feed moves into the material with an empty spindle (T0): %ld\n",
           r->alarm_count[SWARF_ALARM_NO_TOOL]);
  if (r->collision_s > 0) printf("  collision check %.2f s CPU\n", r->collision_s);
  printf("  simulation %.2f s (%.0f moves/s), total %.2f s\n", r->seconds,
         r->seconds > 0 ? r->moves / r->seconds : 0.0, total_s);
  printf("  grid: voxel %g mm, active voxels %llu\n", swarf_stock_voxel(stock),
         swarf_stock_active_voxels(stock));
  printf("  wrote %s", o->out);
  if (o->mesh) printf(", %s (%zu triangles)", o->mesh, ntri);
  if (o->image) printf(", %s", o->image);
  if (o->html) printf(", %s", o->html);
  printf("\n");
}

static int on_progress(void *user, const swarf_sim_progress *p) {
  sim_clients *c = user;
  if (c->bar != NULL) swarf_progress_update(c->bar, p->fraction, p->report->moves);
  return swarf_modbus_observe(c->modbus, p);
}

static void on_alarm(void *user, const swarf_alarm *a) {
  sim_clients *c = user;
  alarm_list *l = &c->alarms;
  swarf_verify_alarm(c->verify, a);
  if (l->n == l->cap) {
    long cap = l->cap ? 2 * l->cap : 64;
    swarf_alarm *p = cap <= MAX_KEPT_ALARMS ? realloc(l->a, sizeof *p * (size_t)cap) : NULL;
    if (p == NULL) {
      l->dropped++;
      return;
    }
    l->a = p;
    l->cap = cap;
  }
  l->a[l->n++] = *a;
}

static void on_move(void *user, const swarf_move *m) {
  swarf_html_add_move(((sim_clients *)user)->html, m);
}

static void on_line(void *user, const swarf_line_result *l) {
  swarf_verify_line(((sim_clients *)user)->verify, l);
}

static void on_note(void *user, long line, int column, const char *text) {
  swarf_verify_note(((sim_clients *)user)->verify, line, column, text);
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

/* Several processes: every rank must read the program (the driver opens it
 * inside the run, where a rank failing alone would leave the others
 * waiting): the driver's own message when it cannot. */
static int check_program(const char *path) {
  FILE *f = fopen(path, "rb");
  swarf_error e;
  char msg[1024];
  if (f != NULL) return fclose(f), 0;
  swarf_error_init(&e);
  swarf_error_at(&e, path, 0, 0, NULL);
  swarf_error_set(&e, SWARF_ERR_OPEN, "cannot open the program: %s", strerror(errno));
  swarf_error_format(&e, msg, sizeof msg);
  fprintf(stderr, "%s\n", msg);
  return (int)swarf_status_classify(SWARF_ERR_OPEN);
}

/* The run failed: bad input and a stop are every rank's (the same program
 * everywhere), reported once by rank 0; anything else may be this rank's
 * alone: all ranks end (MPI_Abort, status 1). Returns the exit status. */
static int run_failed(swarf_cli_mpi *mpi, const swarf_error *e, const swarf_modbus_service *mb) {
  const swarf_status_class c = swarf_status_classify(e->status);
  if (c != SWARF_CLASS_INPUT && e->status != SWARF_ERR_ABORTED) {
    char msg[1024];
    swarf_error_format(e, msg, sizeof msg);
    swarf_cli_mpi_abort(mpi, msg, 1);
  }
  return report_failure(e, mb);
}

/* Checks the outputs of rank 0 and prints what the run found: alarms,
 * outputs, summary, verification, --fail-on. Returns the exit status. */
static int finish_run(sim_options *o, sim_clients *clients, swarf_stock *stock,
                      swarf_sim_report *rep, const swarf_progress *pb) {
  size_t ntri = 0;
  print_alarms(o, &clients->alarms, rep);
  swarf_verify_warn(&o->verify, o->program, rep);
  int rc = write_outputs(o, clients->html, stock, rep, &ntri);
  if (rc == 0 && !o->quiet) {
    print_summary(o, stock, rep, swarf_progress_now() - pb->start, ntri);
    swarf_verify_summary(&o->verify, rep);
  }
  if (rc == 0) rc = swarf_verify_finish(&o->verify, rep);
  if (rc == 0 && o->fail_on_collision && rep->collisions > 0) {
    fprintf(stderr, "%s: %ld collisions (--fail-on collision): exit status 4\n", o->program,
            rep->collisions);
    rc = 4;
  }
  if (rc == 0 && o->fail_on_no_tool && rep->alarm_count[SWARF_ALARM_NO_TOOL] > 0) {
    fprintf(stderr, "%s: %ld feed moves with an empty spindle (--fail-on no-tool): exit status 4\n",
            o->program, rep->alarm_count[SWARF_ALARM_NO_TOOL]);
    rc = 4;
  }
  return rc;
}

/* Everything up to the run, on every rank in step: options, inputs, the
 * initial stock, the design, the Modbus service (rank 0's). Returns the
 * exit status, or -1 when --help was printed. */
static int prepare(sim_options *o, int argc, char **argv, swarf_cli_mpi *mpi, swarf_stock **initial,
                   swarf_modbus_service **mb) {
  static const char *const names[] = {"program",      "--stock file",   "--design",
                                      "--tool-table", "--tool-library", "--offsets"};
  const int slabs = mpi->comm.size > 1;
  int rc = parse_args(o, argc, argv);
  if (rc == 1) return -1;
  if (rc == 0 && o->cfg.threads > 0) /* all of the run's passes, not only the removal's */
    swarf_stock_limit_threads(o->cfg.threads);
  if (rc == 0 && o->stock.file == NULL) rc = check_size(&o->cfg);
  if (rc == 0 && slabs && o->balance) rc = usage_error("--balance: run it on one process");
  if (rc == 0 && slabs) rc = check_program(o->program);
  if ((rc = swarf_cli_mpi_agree(mpi, rc))) return rc;
  const char *const files[] = {o->program,    o->stock.file,   o->verify.design_path,
                               o->tool_table, o->tool_library, o->verify.offsets};
  if ((rc = swarf_cli_mpi_same_inputs(mpi, argc, argv, names, files, 6))) return rc;
  rc = swarf_cli_stock_make(&o->stock, &o->cfg, initial);
  if ((rc = swarf_cli_mpi_agree(mpi, rc))) return rc;
  o->verify.frame = *initial;
  o->verify.views = o->mesh != NULL || o->image != NULL || o->html != NULL;
  o->verify.lines_wanted = o->html != NULL;
  rc = swarf_verify_prepare(&o->verify, &o->cfg);
  if ((rc = swarf_cli_mpi_agree(mpi, rc))) return rc;
  if (mpi->comm.rank == 0) rc = start_modbus(o, mb); /* rank 0's only */
  return swarf_cli_mpi_agree(mpi, rc);
}

static int simulate(int argc, char **argv, swarf_cli_mpi *mpi) {
  sim_options o;
  swarf_sim_report rep;
  swarf_stock *stock = NULL, *initial = NULL;
  swarf_progress pb;
  swarf_modbus_service *mb = NULL;
  swarf_error err;
  const int rank = mpi->comm.rank;
  int ran = 0;
  sim_clients clients = {NULL, NULL, &o.verify, {NULL, 0, 0, 0}, NULL};
  memset(&rep, 0, sizeof rep);
  swarf_progress_init(&pb);
  int rc = prepare(&o, argc, argv, mpi, &initial, &mb);
  if (rc < 0) return 0; /* --help */
  if (rc != 0) goto done;
  if (rank != 0) o.quiet = 1;
  if (mpi->comm.size > 1) o.cfg.comm = &mpi->comm;
  clients.bar = o.quiet ? NULL : &pb;
  clients.modbus = mb;
  if (o.html != NULL && rank == 0 && (clients.html = swarf_html_new()) == NULL) {
    fputs("swarf simulate: out of memory\n", stderr);
    rc = 1;
    goto done;
  }
  if (clients.html != NULL) o.cfg.cb.move = on_move;
  o.cfg.cb.progress = on_progress;
  o.cfg.cb.alarm = on_alarm;
  o.cfg.cb.note = on_note;
  if (o.cfg.line_volumes) o.cfg.cb.line = on_line;
  o.cfg.cb.user = &clients;
  swarf_error_init(&err);
  const swarf_status st = swarf_cli_run(&o.cfg, o.program, initial, o.balance, &stock, &rep, &err);
  initial = NULL; /* the run's */
  ran = 1;
  swarf_progress_finish(&pb);
  if (st != SWARF_OK)
    rc = run_failed(mpi, &err, mb);
  else if (rank == 0) /* rank 0 prints and writes; another rank's stock is its slab */
    rc = finish_run(&o, &clients, stock, &rep, &pb);
done:
  swarf_html_free(clients.html);
  free(clients.alarms.a);
  swarf_modbus_finish(mb, rc == 4 ? 0 : rc, ran ? &rep : NULL); /* a gouge is the part's */
  swarf_stock_free(initial);
  swarf_stock_free(stock);
  swarf_verify_free(&o.verify);
  return rc;
}

int swarf_cli_simulate(int argc, char **argv) {
  swarf_cli_mpi mpi;
  int rc = swarf_cli_mpi_start(&mpi);
  if (rc != 0) return rc;
  writer_rank = mpi.comm.rank;
  return swarf_cli_mpi_end(&mpi, simulate(argc, argv, &mpi));
}
