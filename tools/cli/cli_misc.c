/* SPDX-License-Identifier: MPL-2.0 */
/* cli_misc.c -- `swarf parse`, `swarf info`, `swarf render` and `swarf help`.
 *
 * Small commands around the simulator: check and list a program's moves,
 * describe a stock grid, draw one.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_stock.h"
#include "gcode.h"
#include "stock.h"
#include "swarf_file.h"
#include "swarf_sim.h"

static const char parse_help[] =
    "usage: swarf parse PROGRAM [--quiet | --canon] [--tools TABLE] [--dialect NAME]\n"
    "                   [--block-delete] [--subroutine-path DIRS] [--work-limit N]\n"
    "                   [--start X,Y,Z]\n"
    "                   [--g54 X,Y,Z] [--offsets FILE] [--units mm|in]\n"
    "                   [--tool-table FILE [--tool-table-units mm|in]]\n"
    "\n"
    "Checks PROGRAM and lists its canonical moves, one per line:\n"
    "  LINE KIND X Y Z [centre CX CY CZ normal NX NY NZ angle DEG rise MM] F feed T tool\n"
    "in the machine frame (offsets applied), mm, mm/min and degrees (G20 programs\n"
    "converted). --quiet prints only the count. --canon prints the canonical calls as\n"
    "`rs274 -g` does instead (program coordinates, active unit), to compare line by\n"
    "line. --tools reads a LinuxCNC tool table (inches, as rs274 without an INI).\n"
    "  --dialect NAME   linuxcnc (default), fanuc, haas or grbl (tools/doc/\n"
    "                   dialects.md)\n"
    "  --block-delete   the block delete switch is on: `/` blocks are skipped (off:\n"
    "                   they run, as rs274 runs them)\n"
    "  --subroutine-path DIRS  where `o<name> call` finds <name>.ngc (':' between\n"
    "                   directories)\n"
    "  --work-limit N   the bound on the work of loops and calls: lines run, and\n"
    "                   moves and arc turns beyond one a line (default 5000000)\n"
    "The machine's setup, as swarf simulate takes it (then the moves are listed in\n"
    "the workpiece frame simulate cuts in: G54 as set up is its origin):\n"
    "  --start X,Y,Z    where the tool tip is when the program starts (workpiece mm;\n"
    "                   default the machine's 0,0,0)\n"
    "  --g54 X,Y,Z      G54's origin in machine coordinates (mm)\n"
    "  --offsets FILE   LinuxCNC's parameter file (its .var)\n"
    "  --units mm|in    the machine's length unit\n"
    "  --tool-table FILE  a LinuxCNC tool table: its tools and G43 lengths are the\n"
    "                   program's (without one, rs274's built-in T1-T3 lengths)\n"
    "  --tool-table-units mm|in  the table's unit (default mm)\n"
    "What was accepted without effect (a vendor M code, a grbl $ line, a probe move\n"
    "that found nothing) is told as FILE:LINE:COL: note: ... on stderr.\n"
    "Exit status 2 with FILE:LINE:COL: message on the first error.\n";

static const char info_help[] =
    "usage: swarf info FILE.vdb\n"
    "\n"
    "Describes a stock grid: voxel size, active voxels, enclosed volume, bounds, and\n"
    "whether it is a valid narrow-band level set (OpenVDB's checkLevelSet).\n";

static const char render_help[] =
    "usage: swarf render FILE.vdb --image FILE.png [--size WIDTHxHEIGHT] [--view NAME]\n"
    "                    [--design FILE.stl|FILE.vdb [--tolerance MM]]\n"
    "\n"
    "Draws the stock in FILE.vdb with OpenVDB's level-set ray tracer (default 1024x768).\n"
    "  --view NAME   iso (default: from the front left, above; perspective), or\n"
    "                orthographic top (X right, Y up), front (from -Y), back, left\n"
    "                (from -X), right, bottom\n"
    "  --design F    colour the surface by its signed distance to the design F (a\n"
    "                closed STL or a .vdb): green within the tolerance, yellow to red\n"
    "                outside it (excess), cyan to blue inside it (gouge), saturated at\n"
    "                4 tolerances; a legend with the scale in mm is drawn\n"
    "  --tolerance MM  default half the stock's voxel\n";

/* The workpiece frame the moves are listed in (identity without a setup). */
static swarf_sim_frame parse_frame = {{0, 0, 0}, 1, 0};

/* With --tool-table the moves are listed where simulate cuts: at the tip of
 * the tool in the spindle, its length below the controlled point (one tool
 * is loaded from the start, as simulate loads it). */
static struct {
  int n, number[SWARF_SIM_MAX_TOOLS];
  double length[SWARF_SIM_MAX_TOOLS], spindle;
} parse_tips;

static void tips_from(const swarf_sim_config *cfg) {
  parse_tips.n = cfg->ntools;
  for (int i = 0; i < cfg->ntools; i++)
    parse_tips.number[i] = cfg->tools[i].number, parse_tips.length[i] = cfg->tools[i].length;
  parse_tips.spindle = cfg->ntools == 1 ? cfg->tools[0].length : 0.0;
}

static void tips_change(int tool) {
  parse_tips.spindle = 0.0;
  for (int i = 0; i < parse_tips.n; i++)
    if (parse_tips.number[i] == tool) parse_tips.spindle = parse_tips.length[i];
}

static int print_move(const swarf_move *m, void *user) {
  static const char *kinds[] = {"RAPID", "LINE", "ARC", "DWELL", "TOOL"};
  const swarf_sim_frame *f = &parse_frame;
  swarf_move tip;
  long *count = user;
  double end[3], c[3];
  (*count)++;
  if (m->kind == SWARF_MOVE_TOOL_CHANGE) tips_change(m->tool);
  if (count[1]) return 0;
  tip = *m;
  tip.end[2] -= parse_tips.spindle, tip.center[2] -= parse_tips.spindle;
  m = &tip;
  swarf_sim_frame_point(f, m->end, end);
  printf("%ld %s %.4f %.4f %.4f", m->line, kinds[m->kind], end[0], end[1], end[2]);
  if (m->kind == SWARF_MOVE_ARC) {
    swarf_sim_frame_point(f, m->center, c);
    printf(" centre %.4f %.4f %.4f normal %g %g %g angle %.4f rise %.4f", c[0], c[1], c[2],
           f->cos_rot * m->normal[0] + f->sin_rot * m->normal[1],
           -f->sin_rot * m->normal[0] + f->cos_rot * m->normal[1], m->normal[2],
           m->angle * 57.29577951308232, m->rise);
  }
  if (m->kind == SWARF_MOVE_DWELL) printf(" dwell %.4f", m->dwell);
  printf(" F %.4f T %d\n", m->feed, m->tool);
  return 0;
}

static void print_canon(const char *call, void *user) {
  (void)user;
  puts(call);
}

static int count_move(const swarf_move *m, void *user) {
  (void)m;
  (*(long *)user)++;
  return 0;
}

typedef struct {
  const char *program, *tools, *dialect, *subpath, *offsets, *units, *tool_table;
  int canon, quiet, block_delete, start_set, g54_set;
  long work_limit;
  double start[3], g54[3], table_mm_per_unit;
} parse_options;

/* The machine's setup (--start, --g54, --offsets, --units) by the code
 * swarf simulate uses, when any is given; the listing's frame from it. */
static int machine_setup(swarf_gcode_parser *p, const parse_options *o, swarf_error *err) {
  swarf_sim_config *cfg;
  swarf_status rc;
  if (!o->start_set && !o->g54_set && o->offsets == NULL && o->units == NULL &&
      o->tool_table == NULL)
    return SWARF_OK;
  if ((cfg = swarf_sim_config_new()) == NULL) return SWARF_ERR_MEMORY;
  if (o->tool_table != NULL && (rc = swarf_sim_config_load_tool_table(
                                    cfg, o->tool_table, o->table_mm_per_unit, err)) != SWARF_OK)
    return swarf_sim_config_free(cfg), rc;
  tips_from(cfg);
  cfg->units =
      o->units != NULL && !strcmp(o->units, "in") ? SWARF_GCODE_UNITS_INCH : SWARF_GCODE_UNITS_MM;
  cfg->offsets_file = o->offsets;
  cfg->g54_set = o->g54_set;
  memcpy(cfg->g54, o->g54, sizeof cfg->g54);
  rc = swarf_sim_setup_parser(cfg, p, o->start_set ? o->start : NULL, &parse_frame, err);
  swarf_sim_config_free(cfg);
  return rc;
}

/* "X,Y,Z" (mm, as simulate reads it); 0, or 2 after a message. */
static int read_point(const char *flag, const char *val, double out[3]) {
  if (swarf_cli_read_point(val, out) == 0) return 0;
  fprintf(stderr, "swarf parse: %s: give X,Y,Z in mm, e.g. 0,0,25 (got \"%s\")\n", flag, val);
  return 2;
}

static void print_note(long line, int column, const char *note, void *user) {
  fprintf(stderr, "%s:%ld:%d: note: %s\n", (const char *)user, line, column, note);
}

/* The reading options on a new parser. */
static int parse_setup(swarf_gcode_parser *p, const parse_options *o, swarf_error *err) {
  swarf_gcode_dialect d = SWARF_GCODE_DIALECT_LINUXCNC;
  int rc = SWARF_OK;
  if (o->canon) swarf_gcode_parser_set_canon(p, print_canon, NULL);
  swarf_gcode_parser_set_notes(p, print_note, (void *)o->program);
  if (o->dialect != NULL) swarf_gcode_dialect_from_name(o->dialect, &d);
  rc = swarf_gcode_parser_set_dialect(p, d, err);
  if (rc == SWARF_OK) rc = swarf_gcode_parser_set_block_delete(p, o->block_delete, err);
  if (rc == SWARF_OK && o->work_limit != 0)
    rc = swarf_gcode_parser_set_work_limit(p, o->work_limit, err);
  if (rc == SWARF_OK && o->subpath != NULL)
    rc = swarf_gcode_parser_set_subroutine_path(p, o->subpath, err);
  if (rc == SWARF_OK && o->tools != NULL) rc = swarf_gcode_parser_load_tools(p, o->tools, err);
  if (rc == SWARF_OK) rc = machine_setup(p, o, err);
  return rc;
}

/* Streams the program through a parser set up as the options say. */
static int parse_stream(const parse_options *o, long *count, swarf_error *err) {
  char chunk[65536];
  size_t got;
  int rc = SWARF_OK;
  swarf_gcode_parser *p;
  FILE *in;
  memset(err, 0, sizeof *err);
  in = swarf_file_open_input(o->program, "program", 0, err); /* regular files only */
  if (in == NULL) {
    char why[sizeof err->message];
    snprintf(why, sizeof why, "%s", err->message);
    snprintf(err->message, sizeof err->message, "cannot open file: %.480s", why);
    return err->status;
  }
  if (swarf_gcode_parser_new(o->program, o->canon ? count_move : print_move, count, &p) != SWARF_OK)
    return fclose(in), SWARF_ERR_MEMORY;
  rc = parse_setup(p, o, err);
  while (rc == SWARF_OK && !swarf_gcode_parser_ended(p) &&
         (got = fread(chunk, 1, sizeof chunk, in)) > 0)
    rc = swarf_gcode_parser_feed(p, chunk, got);
  if (rc == SWARF_OK && ferror(in)) {
    snprintf(err->message, sizeof err->message, "cannot read file");
    rc = SWARF_ERR_OPEN;
  }
  if (rc == SWARF_OK) rc = swarf_gcode_parser_finish(p);
  if (rc != SWARF_OK && swarf_gcode_parser_error(p) != NULL) *err = *swarf_gcode_parser_error(p);
  swarf_gcode_parser_free(p);
  fclose(in);
  return rc;
}

int swarf_cli_parse(int argc, char **argv) {
  long count[2] = {0, 0};
  parse_options o = {0};
  swarf_error err;
  int rc;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) return fputs(parse_help, stdout), 0;
    if (!strcmp(a, "--quiet"))
      count[1] = 1;
    else if (!strcmp(a, "--canon"))
      o.canon = 1;
    else if (!strcmp(a, "--block-delete"))
      o.block_delete = 1;
    else if (!strcmp(a, "--tools") && i + 1 < argc)
      o.tools = argv[++i];
    else if (!strcmp(a, "--subroutine-path") && i + 1 < argc)
      o.subpath = argv[++i];
    else if (!strcmp(a, "--offsets") && i + 1 < argc)
      o.offsets = argv[++i];
    else if (!strcmp(a, "--work-limit") && i + 1 < argc) {
      char *end;
      o.work_limit = strtol(argv[++i], &end, 10);
      if (*end || end == argv[i] || o.work_limit < 1 || o.work_limit > SWARF_GCODE_WORK_LIMIT_MAX) {
        fprintf(stderr,
                "swarf parse: --work-limit: give a count from 1 to 1000000000 (got \"%s\")\n",
                argv[i]);
        return 2;
      }
    } else if (!strcmp(a, "--tool-table") && i + 1 < argc)
      o.tool_table = argv[++i];
    else if (!strcmp(a, "--tool-table-units") && i + 1 < argc) {
      const char *u = argv[++i];
      if (strcmp(u, "mm") && strcmp(u, "in")) {
        fprintf(stderr, "swarf parse: --tool-table-units: give mm or in (got \"%s\")\n", u);
        return 2;
      }
      o.table_mm_per_unit = u[0] == 'i' ? 25.4 : 1.0;
    } else if (!strcmp(a, "--start") && i + 1 < argc) {
      if (read_point(a, argv[++i], o.start)) return 2;
      o.start_set = 1;
    } else if (!strcmp(a, "--g54") && i + 1 < argc) {
      if (read_point(a, argv[++i], o.g54)) return 2;
      o.g54_set = 1;
    } else if (!strcmp(a, "--units") && i + 1 < argc) {
      o.units = argv[++i];
      if (strcmp(o.units, "mm") && strcmp(o.units, "in")) {
        fprintf(stderr, "swarf parse: --units: give mm or in (got \"%s\")\n", o.units);
        return 2;
      }
    } else if (!strcmp(a, "--dialect") && i + 1 < argc) {
      o.dialect = argv[++i];
      if (swarf_gcode_dialect_from_name(o.dialect, NULL) != 0) {
        fprintf(stderr, "swarf parse: --dialect: give linuxcnc, fanuc, haas or grbl (got \"%s\")\n",
                o.dialect);
        return 2;
      }
    } else if (a[0] == '-' || o.program) {
      fprintf(stderr, "swarf parse: unexpected \"%s\"\n%s", a, parse_help);
      return 2;
    } else
      o.program = a;
  }
  if (o.program == NULL) return fputs(parse_help, stderr), 2;
  if (o.table_mm_per_unit == 0) o.table_mm_per_unit = 1.0;
  if (o.tools != NULL && o.tool_table != NULL) {
    fprintf(stderr, "swarf parse: give --tools (rs274's table, with --canon) or --tool-table "
                    "(simulate's), not both\n");
    return 2;
  }
  if (o.tools != NULL && !o.canon) {
    fprintf(stderr, "swarf parse: --tools needs --canon\n");
    return 2;
  }
  fflush(stdout);
  rc = parse_stream(&o, count, &err);
  if (rc != SWARF_OK) {
    char msg[1024];
    swarf_error_format(&err, msg, sizeof msg); /* FILE:LINE:COL, or TABLE:LINE for tables */
    fprintf(stderr, "%s\n", msg);
    return swarf_status_classify(rc) == SWARF_CLASS_INPUT ? 2 : 1;
  }
  fprintf(count[1] ? stdout : stderr, "%s: %ld moves\n", o.program, count[0]);
  return 0;
}

static swarf_stock *open_grid(const char *cmd, const char *path) {
  swarf_error err;
  swarf_stock *s = NULL;
  char msg[1024];
  if (swarf_stock_read(path, &s, &err) != SWARF_OK) {
    swarf_error_format(&err, msg, sizeof msg); /* FILE: what */
    fprintf(stderr, "swarf %s: %s\n", cmd, msg);
  }
  return s;
}

int swarf_cli_info(int argc, char **argv) {
  double lo[3], hi[3];
  swarf_error err;
  swarf_stock *s;
  if (argc != 2 || argv[1][0] == '-') {
    fputs(info_help, argc == 2 && !strcmp(argv[1], "--help") ? stdout : stderr);
    return argc == 2 && !strcmp(argv[1], "--help") ? 0 : 2;
  }
  if ((s = open_grid("info", argv[1])) == NULL) return 2;
  swarf_stock_bounds(s, lo, hi);
  printf("file %s\ngrid stock (level set)\nvoxel %g mm\nband %d voxels\n", argv[1],
         swarf_stock_voxel(s), swarf_stock_half_width(s));
  printf("active_voxels %llu\nvolume %.3f mm^3\n", swarf_stock_active_voxels(s),
         swarf_stock_volume(s));
  printf("bounds %.3f %.3f %.3f %.3f %.3f %.3f mm\n", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  if (swarf_stock_check(s, &err) == SWARF_OK)
    printf("level_set valid\n");
  else
    printf("level_set INVALID: %s\n", err.message);
  swarf_stock_free(s);
  return 0;
}

typedef struct {
  const char *in, *out, *design;
  int w, h;
  double tolerance;
  swarf_stock_view view;
} render_options;

static int render_args(render_options *o, int argc, char **argv) {
  swarf_error err;
  memset(o, 0, sizeof *o);
  o->w = 1024, o->h = 768;
  for (int i = 1; i < argc; i++) {
    const char *f = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    char *end;
    if (!strcmp(f, "--help")) return fputs(render_help, stdout), 1;
    if (f[0] != '-' && !o->in) {
      o->in = f;
      continue;
    }
    if (v == NULL || f[0] != '-')
      return fprintf(stderr, "swarf render: unexpected \"%s\"\n%s", f, render_help), 2;
    i++;
    if (!strcmp(f, "--image"))
      o->out = v;
    else if (!strcmp(f, "--design"))
      o->design = v;
    else if (!strcmp(f, "--size")) {
      if (sscanf(v, "%dx%d", &o->w, &o->h) != 2 || o->w < 16 || o->h < 16 || o->w > 8192 ||
          o->h > 8192)
        return fprintf(stderr, "swarf render: --size WIDTHxHEIGHT, 16 to 8192\n"), 2;
    } else if (!strcmp(f, "--view")) {
      if (swarf_stock_view_parse(v, &o->view, &err) != SWARF_OK)
        return fprintf(stderr, "swarf render: --view: %s\n", err.message), 2;
    } else if (!strcmp(f, "--tolerance")) {
      errno = 0;
      o->tolerance = strtod(v, &end);
      if (end == v || *end || errno || !(o->tolerance > 0) || o->tolerance > 1e6)
        return fprintf(stderr, "swarf render: --tolerance: give a number of mm > 0\n"), 2;
    } else
      return fprintf(stderr, "swarf render: unexpected \"%s\"\n%s", f, render_help), 2;
  }
  if (!o->in || !o->out) return fputs(render_help, stderr), 2;
  if (o->tolerance > 0 && !o->design)
    return fprintf(stderr, "swarf render: --tolerance needs --design\n"), 2;
  {
    const swarf_cli_path outs[] = {{"--image", o->out}};
    const swarf_cli_path ins[] = {{"FILE.vdb", o->in}, {"--design", o->design}};
    if (swarf_cli_output_ok("render", "--image", o->out) ||
        swarf_cli_outputs_distinct("render", outs, 1, ins, 2))
      return 2;
  }
  return 0;
}

int swarf_cli_render(int argc, char **argv) {
  render_options o;
  swarf_stock *s, *design = NULL;
  swarf_stock_output opt;
  swarf_error err;
  char msg[1024];
  int rc = render_args(&o, argc, argv);
  if (rc) return rc == 1 ? 0 : rc;
  if ((s = open_grid("render", o.in)) == NULL) return 2;
  if (o.design &&
      swarf_stock_read_design_band(o.design, swarf_stock_voxel(s),
                                   swarf_stock_design_band(s, swarf_stock_voxel(s), o.tolerance, 1),
                                   &design, &err) != SWARF_OK) {
    swarf_error_format(&err, msg, sizeof msg);
    fprintf(stderr, "swarf render: --design: %s\n", msg);
    swarf_stock_free(s);
    return (int)swarf_status_classify(err.status);
  }
  memset(&opt, 0, sizeof opt);
  opt.width = o.w, opt.height = o.h, opt.view = o.view, opt.design = design,
  opt.tolerance = o.tolerance;
  rc = 0;
  if (swarf_stock_write_image(s, o.out, &opt, &err) != SWARF_OK) {
    swarf_error_format(&err, msg, sizeof msg);
    fprintf(stderr, "swarf render: %s\n", msg);
    rc = (int)swarf_status_classify(err.status);
  }
  swarf_stock_free(design);
  swarf_stock_free(s);
  return rc;
}

int swarf_cli_help(const char *command) {
  char *argv[] = {(char *)command, "--help", NULL};
  if (!strcmp(command, "simulate")) return swarf_cli_simulate(2, argv);
  if (!strcmp(command, "parse")) return fputs(parse_help, stdout), 0;
  if (!strcmp(command, "info")) return fputs(info_help, stdout), 0;
  if (!strcmp(command, "render")) return fputs(render_help, stdout), 0;
  if (!strcmp(command, "compare")) return swarf_cli_compare(2, argv);
  if (!strcmp(command, "envelope")) return swarf_cli_envelope(2, argv);
  fprintf(stderr, "swarf help: unknown command \"%s\"\n", command);
  return 2;
}
