/* SPDX-License-Identifier: MPL-2.0 */
/* cli_stock.c -- stocks from files, their placement, outputs by format and
 * `swarf compare` (cli_stock.h). */
#include "cli_stock.h"
#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

const char swarf_cli_stock_help[] =
    "  --stock stl:FILE a closed, consistently oriented triangle mesh (binary or\n"
    "                   ASCII STL, mm) made into a level set at --voxel\n"
    "  --stock vdb:FILE a grid swarf (or another tool) wrote: the level set named\n"
    "                   \"stock\" or the first float level set; its own voxel size,\n"
    "                   or resampled to --voxel when that is given and differs\n"
    "  --stock-transform tx=MM,ty=MM,tz=MM,rx=DEG,ry=DEG,rz=DEG   place the stock for\n"
    "                   this setup: rotate about the machine X axis, then Y, then Z\n"
    "                   (through the origin, right-hand rule), then translate\n"
    "  --mesh FILE      the surface by extension: .stl (binary), .obj, .ply (with\n"
    "                   --design: coloured by deviation, a \"deviation\" property)\n"
    "  --view NAME      the --image's view: iso (default), top, front, back, left,\n"
    "                   right, bottom\n"
    "  --html FILE.html one page that opens in a browser with no network: the part\n"
    "                   to turn (coloured by deviation with --design), the toolpath\n"
    "                   with a slider through its lines and the tool, a click on\n"
    "                   the part names the line that last cut there, the alarms\n"
    "                   linked to their lines, removal rate and feed per line\n"
    "                   (measures each line's volume, as --report does)\n";

static int fail(const char *flag, const char *what) {
  fprintf(stderr, "swarf: %s: %s\n", flag, what);
  return 2;
}

int swarf_cli_stock_option(swarf_cli_stock *c, const char *flag, const char *val, int *i) {
  swarf_error err;
  if (!strcmp(flag, "--voxel")) c->voxel_given = 1;
  if (strcmp(flag, "--stock") && strcmp(flag, "--stock-transform") && strcmp(flag, "--view"))
    return -1;
  if (val == NULL) return fail(flag, "needs a value");
  if (!strcmp(flag, "--stock")) {
    if (strncmp(val, "stl:", 4) && strncmp(val, "vdb:", 4)) return -1; /* box:, cylinder: */
    if (val[4] == '\0') return fail(flag, "give the file: stl:FILE or vdb:FILE");
    c->file = val + 4;
    c->is_vdb = val[0] == 'v';
  } else if (!strcmp(flag, "--view")) {
    if (swarf_stock_view_parse(val, &c->view, &err) != SWARF_OK) return fail(flag, err.message);
  } else {
    if (swarf_stock_placement_parse(val, &c->place, &err) != SWARF_OK)
      return fail(flag, err.message);
    c->place_set = 1;
  }
  (*i)++;
  return 0;
}

int swarf_cli_mesh_name(const char *flag, const char *path) {
  const char *dot = path ? strrchr(path, '.') : NULL, *slash = path ? strrchr(path, '/') : NULL;
  if (path == NULL) return 0;
  if (dot != NULL && (slash == NULL || dot > slash) &&
      (!strcasecmp(dot, ".stl") || !strcasecmp(dot, ".obj") || !strcasecmp(dot, ".ply")))
    return 0;
  fprintf(stderr, "swarf: %s: \"%s\": name the mesh .stl (binary STL), .obj or .ply\n", flag, path);
  return 2;
}

static int stock_error(const swarf_error *e) {
  char msg[1024];
  swarf_error_format(e, msg, sizeof msg);
  fprintf(stderr, "swarf simulate: --stock: %s\n", msg);
  return (int)swarf_status_classify(e->status);
}

/* The box or cylinder of cfg as a stock (to place it). */
static swarf_status shape_stock(const swarf_sim_config *cfg, swarf_stock **out, swarf_error *err) {
  const swarf_sim_stock_spec *sp = &cfg->stock;
  if (sp->kind == SWARF_SIM_STOCK_CYLINDER)
    return swarf_stock_new_cylinder(sp->axis, sp->radius, sp->lo[sp->axis], sp->hi[sp->axis],
                                    cfg->voxel, cfg->half_width, out, err);
  return swarf_stock_new_box(sp->lo, sp->hi, cfg->voxel, cfg->half_width, out, err);
}

int swarf_cli_stock_make(const swarf_cli_stock *c, swarf_sim_config *cfg, swarf_stock **out) {
  const swarf_stock_placement *p = c->place_set ? &c->place : NULL;
  swarf_error err;
  swarf_status st;
  *out = NULL;
  swarf_error_init(&err);
  if (c->file == NULL && !c->place_set) return 0;
  if (c->file != NULL && c->is_vdb)
    st = swarf_stock_read_vdb(c->file, p, c->voxel_given ? cfg->voxel : 0.0, cfg->half_width, out,
                              &err);
  else if (c->file != NULL)
    st = swarf_stock_read_stl(c->file, p, cfg->voxel, cfg->half_width, out, &err);
  else {
    swarf_stock *s = NULL;
    if (shape_stock(cfg, &s, &err) != SWARF_OK) return stock_error(&err);
    st = swarf_stock_place(s, p, out, &err);
    swarf_stock_free(s);
  }
  if (st != SWARF_OK) {
    if (err.status == SWARF_ERR_ARG && c->place_set) {
      char msg[1024];
      swarf_error_format(&err, msg, sizeof msg);
      fprintf(stderr, "swarf simulate: --stock-transform: %s\n", msg);
      return 2;
    }
    return stock_error(&err);
  }
  cfg->voxel = swarf_stock_voxel(*out);
  return 0;
}

/* The work balance of 2..upto processes, from the run's tally. */
static void print_balance(const swarf_sim *sim, int upto) {
  static const int ranks[] = {2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 256, 512, 1024};
  double ratio, visited;
  for (size_t i = 0; i < sizeof ranks / sizeof ranks[0] && ranks[i] <= upto; i++)
    if (swarf_sim_balance(sim, ranks[i], &ratio, &visited) == SWARF_OK)
      printf("balance: %4d ranks: busiest/mean %.3f (%.4g voxels visited in all)\n", ranks[i],
             ratio, visited);
}

swarf_status swarf_cli_run(const swarf_sim_config *cfg, const char *program, swarf_stock *stock,
                           int balance, swarf_stock **out, swarf_sim_report *rep,
                           swarf_error *err) {
  swarf_sim *sim = NULL;
  swarf_status st;
  *out = NULL;
  memset(rep, 0, sizeof *rep);
  st = stock != NULL ? swarf_sim_new_with_stock(cfg, program, stock, &sim, err)
                     : swarf_sim_new(cfg, program, &sim, err);
  if (st != SWARF_OK) return st;
  st = swarf_sim_feed_file(sim, program);
  if (st == SWARF_OK) st = swarf_sim_finish(sim);
  *rep = *swarf_sim_get_report(sim);
  if (st == SWARF_OK && balance >= 2) print_balance(sim, balance);
  if (st == SWARF_OK)
    *out = swarf_sim_take_stock(sim);
  else if (err != NULL)
    *err = *swarf_sim_error(sim);
  swarf_sim_free(sim);
  return st;
}

int swarf_cli_write_views(const char *cmd, const swarf_stock *s, const char *mesh,
                          const char *image, const swarf_stock *design, double tolerance,
                          swarf_stock_view view, size_t *ntri) {
  swarf_stock_output o;
  swarf_error err;
  swarf_status st = SWARF_OK;
  char msg[1024];
  memset(&o, 0, sizeof o);
  o.view = view;
  o.design = design;
  o.tolerance = tolerance;
  if (mesh != NULL) st = swarf_stock_write_mesh(s, mesh, &o, ntri, &err);
  if (st == SWARF_OK && image != NULL) st = swarf_stock_write_image(s, image, &o, &err);
  if (st == SWARF_OK) return 0;
  swarf_error_format(&err, msg, sizeof msg);
  fprintf(stderr, "swarf %s: %s\n", cmd, msg);
  return (int)swarf_status_classify(st);
}

/* ---- swarf compare ---------------------------------------------------------- */

static const char compare_help[] =
    "usage: swarf compare A.vdb B.vdb|B.stl [--tolerance MM] [--fail-on gouge]\n"
    "                     [--image FILE.png [--view NAME]] [--mesh FILE.ply]\n"
    "\n"
    "The deviation of the stock A from B: another result (.vdb) or the design\n"
    "(.stl, a closed mesh), as `swarf simulate --design` reports it: gouge (B's\n"
    "inside deeper than the tolerance where A has no material), excess (A's\n"
    "material farther than the tolerance outside B), their volumes, the deepest\n"
    "gouge and the largest excess and where they are. An STL design's depths are\n"
    "exact at any distance (its triangles are kept); a .vdb's are measured up to\n"
    "its band, \"or more\" beyond.\n"
    "\n"
    "  --tolerance MM   deviations within it are none (default: half A's voxel)\n"
    "  --fail-on gouge  exit status 4 when there is a gouge\n"
    "  --image, --mesh  A's surface coloured by its signed deviation from B\n"
    "  --view NAME      iso (default), top, front, back, left, right, bottom\n"
    "\n"
    "Prints key=value lines (mm, mm^3). Exit status 0, 2 on bad input (files that\n"
    "are not level sets or closed meshes, B not overlapping A), 1 internal, 4 above.\n";

typedef struct {
  const char *a, *b, *image, *mesh;
  double tolerance;
  int fail_on_gouge;
  swarf_stock_view view;
} compare_options;

/* 2 with a message unless the folder of `path` (may be NULL) is writable. */
static int folder_ok(const char *flag, const char *path) {
  return swarf_cli_output_ok("compare", flag, path); /* outputs.c */
}

static int compare_args(compare_options *o, int argc, char **argv) {
  swarf_error err;
  memset(o, 0, sizeof *o);
  for (int i = 1; i < argc; i++) {
    const char *f = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    char *end;
    if (!strcmp(f, "--help") || !strcmp(f, "-h")) return fputs(compare_help, stdout), 1;
    if (f[0] != '-') {
      if (o->b != NULL) return fail("compare", "give two files: A.vdb and B.vdb or B.stl");
      *(o->a ? &o->b : &o->a) = f;
      continue;
    }
    if (v == NULL) return fail(f, "needs a value");
    i++;
    if (!strcmp(f, "--tolerance")) {
      errno = 0;
      o->tolerance = strtod(v, &end);
      if (end == v || *end || errno || !isfinite(o->tolerance) || o->tolerance <= 0)
        return fail(f, "give a number of mm > 0");
    } else if (!strcmp(f, "--fail-on")) {
      if (strcmp(v, "gouge")) return fail(f, "the one condition is \"gouge\"");
      o->fail_on_gouge = 1;
    } else if (!strcmp(f, "--image"))
      o->image = v;
    else if (!strcmp(f, "--mesh"))
      o->mesh = v;
    else if (!strcmp(f, "--view")) {
      if (swarf_stock_view_parse(v, &o->view, &err) != SWARF_OK) return fail(f, err.message);
    } else {
      fprintf(stderr, "swarf compare: unknown option \"%s\"\n%s", f, compare_help);
      return 2;
    }
  }
  if (o->b == NULL) return fputs(compare_help, stderr), 2;
  if (swarf_cli_mesh_name("--mesh", o->mesh)) return 2;
  if (folder_ok("--mesh", o->mesh) || folder_ok("--image", o->image)) return 2;
  const swarf_cli_path outs[] = {{"--mesh", o->mesh}, {"--image", o->image}};
  const swarf_cli_path ins[] = {{"A", o->a}, {"B", o->b}};
  return swarf_cli_outputs_distinct("compare", outs, 2, ins, 2);
}

static void print_point(const char *key, const double p[3]) {
  if (isfinite(p[0]))
    printf("%s=%.4f,%.4f,%.4f\n", key, p[0], p[1], p[2]);
  else
    printf("%s=none\n", key);
}

static void print_deviation(const compare_options *o, const swarf_stock_deviation *d) {
  printf("compare=%s\nagainst=%s\n", o->a, o->b);
  printf("tolerance_mm=%.4f\nreach_mm=%.4f\n", d->tolerance, d->reach);
  printf("stock_mm3=%.4f\ndesign_mm3=%.4f\n", d->stock_volume, d->design_volume);
  printf("gouge_mm3=%.4f\ngouge_depth_mm=%.4f%s\n", d->gouge_volume, d->gouge_depth,
         d->gouge_clamped ? " (or more)" : "");
  print_point("gouge_at", d->gouge_at);
  printf("excess_mm3=%.4f\nexcess_mm=%.4f%s\n", d->excess_volume, d->excess_height,
         d->excess_clamped ? " (or more)" : "");
  print_point("excess_at", d->excess_at);
}

static int read_error(const char *which, const swarf_error *e) {
  char msg[1024];
  swarf_error_format(e, msg, sizeof msg);
  fprintf(stderr, "swarf compare: %s: %s\n", which, msg);
  return (int)swarf_status_classify(e->status);
}

int swarf_cli_compare(int argc, char **argv) {
  compare_options o;
  swarf_stock *a = NULL, *b = NULL;
  swarf_stock_deviation d;
  swarf_error err;
  int rc = compare_args(&o, argc, argv);
  if (rc == 1) return 0;
  if (rc) return rc;
  if (swarf_stock_read_vdb(o.a, NULL, 0.0, 0, &a, &err) != SWARF_OK) return read_error("A", &err);
  const int band = swarf_stock_design_band(a, swarf_stock_voxel(a), o.tolerance,
                                           o.image != NULL || o.mesh != NULL);
  if (swarf_stock_read_design_band(o.b, swarf_stock_voxel(a), band, &b, &err) != SWARF_OK) {
    swarf_stock_free(a);
    return read_error("B", &err);
  }
  if (swarf_stock_compare(a, b, NULL, o.tolerance, &d, &err) != SWARF_OK)
    rc = read_error("B", &err);
  if (rc == 0) {
    rc = swarf_cli_write_views("compare", a, o.mesh, o.image, b, d.tolerance, o.view, NULL);
    if (rc == 0) print_deviation(&o, &d);
    if (rc == 0 && o.fail_on_gouge && (d.gouge_depth > 0 || d.gouge_volume > 0)) rc = 4;
  }
  swarf_stock_free(a);
  swarf_stock_free(b);
  return rc;
}
