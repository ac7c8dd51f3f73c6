/* SPDX-License-Identifier: MPL-2.0 */
/* test_sim_setup.c -- the driver's machine setup (swarf_sim_config: start,
 * offsets file, g54, units) and the workpiece frame (G54's, rotation
 * included).
 *
 * - the default start: X0 Y0, SWARF_SIM_CLEARANCE above a box stock; above
 *   the bounding sphere about the pivot on a rotary machine;
 * - G54 rotated by 90 degrees (#5230 from a parameter file): a program in
 *   G54 cuts where it says in the workpiece frame, and a G53 plunge at
 *   machine (10, 0) lands at workpiece (0, -10) = Rz(-90) (10, 0): the grid
 *   has no material there and material at (10, 0);
 * - an inch machine: --g54 is still mm (divided into the file's unit), and
 *   a program without G20/G21 runs in inches; the first move before any
 *   units word and the first units word are in the report.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gcode.h"
#include "swarf_sim.h"

static void config(swarf_sim_config *cfg, const char *stock) {
  swarf_error err;
  swarf_sim_tool t;
  swarf_sim_config_init(cfg);
  cfg->fragment = 1; /* the test texts need not end (one case checks the rule) */
  cfg->voxel = 0.25;
  CHECK(swarf_sim_parse_stock(stock, &cfg->stock, &err) == SWARF_OK, "%s", err.message);
  CHECK(swarf_sim_parse_tool("T1=flat,D4,L12", &t, &err) == SWARF_OK, "%s", err.message);
  swarf_sim_config_add_tool(cfg, &t, &err);
}

static swarf_stock *run(const swarf_sim_config *cfg, const char *text, swarf_sim_report *rep) {
  swarf_stock *out = NULL;
  swarf_error err;
  swarf_status st = swarf_sim_run_text(cfg, "t.ngc", text, strlen(text), &out, rep, &err);
  CHECK(st == SWARF_OK, "run: %s", err.message);
  return out;
}

static int material(const swarf_stock *s, double x, double y, double z) {
  return swarf_stock_sample(s, x, y, z) < 0;
}

static void test_default_start(void) {
  swarf_sim_config cfg;
  swarf_sim_report rep;
  swarf_error err;
  config(&cfg, "box:-20,-20,-10,20,20,3");
  swarf_stock_free(run(&cfg, "G0 Z20\n", &rep));
  CHECK(rep.start_default == 1, "default start");
  CHECK_NEAR(rep.start[0], 0, 0, "start X");
  CHECK_NEAR(rep.start[1], 0, 0, "start Y");
  CHECK_NEAR(rep.start[2], 3 + SWARF_SIM_CLEARANCE, 1e-12, "start Z: top + clearance");
  /* a bar about X on a 4th axis: any turn of the table stays below the start */
  config(&cfg, "cylinder:x,5,-4,4");
  CHECK(swarf_machine_parse(&cfg.machine, "xyza", &err) == SWARF_OK, "xyza");
  swarf_stock_free(run(&cfg, "G0 Z20\n", &rep));
  CHECK_NEAR(rep.start[2], sqrt(16 + 25 + 25) + SWARF_SIM_CLEARANCE, 1e-12,
             "rotary: above the bounding sphere (corner 4,5,5)");
  config(&cfg, "box:-20,-20,-10,20,20,3");
  cfg.start_set = 1;
  cfg.start[0] = 1, cfg.start[1] = 2, cfg.start[2] = 30;
  swarf_stock_free(run(&cfg, "G91 G0 X1\n", &rep));
  CHECK(rep.start_default == 0 && rep.start[2] == 30, "cfg.start");
  CHECK_NEAR(rep.path_mm, 1, 1e-12, "G91 X1 from the start");
}

static void test_rotated_g54(void) {
  static const char path[] = "test_sim_setup.var";
  swarf_sim_config cfg;
  swarf_sim_report rep;
  swarf_stock *s;
  FILE *f = fopen(path, "w");
  fputs("5230 90.0\n", f); /* G54's XY rotation, degrees */
  fclose(f);
  config(&cfg, "box:-20,-20,-10,20,20,0");
  cfg.offsets_file = path;
  s = run(&cfg, "G53 G0 X10 Y0 Z5\nG53 G1 Z-2 F100\nG53 G0 Z5\nG0 X-10 Y10\nG1 Z-2\nG0 Z5\n", &rep);
  if (s != NULL) {
    CHECK(!material(s, 0, -10, -1), "G53 at machine (10, 0): hole at workpiece (0, -10)");
    CHECK(material(s, 10, 0, -1), "no hole at workpiece (10, 0)");
    CHECK(!material(s, -10, 10, -1), "G54 (-10, 10): hole at workpiece (-10, 10)");
    CHECK(material(s, 10, -10, -1) && material(s, 10, 10, -1), "nowhere else");
  }
  swarf_stock_free(s);
  remove(path);
}

static void test_inch_machine(void) {
  swarf_sim_config cfg;
  swarf_sim_report rep;
  swarf_stock *s;
  config(&cfg, "box:-20,-20,-10,20,20,0");
  cfg.units = SWARF_GCODE_UNITS_INCH;
  cfg.g54_set = 1;
  cfg.g54[2] = -50.8; /* mm: 2 in */
  s = run(&cfg, "G53 G0 Z-1\nG0 X0.2 Y0.2\nG1 Z-0.04 F4\nG0 Z1\nG21\nG0 X5\n", &rep);
  if (s != NULL) {
    CHECK(!material(s, 5.08, 5.08, -0.5), "inch program: hole at (0.2, 0.2) in");
    CHECK(material(s, 0, 0, -0.5), "G53 Z-1 in: 1 in below machine 0 = 1 in above the part");
  }
  CHECK(rep.units_missing_line == 1 && rep.units_missing_column == 5,
        "first move before a units word: %ld:%d", rep.units_missing_line, rep.units_missing_column);
  CHECK(rep.units_line == 5, "first units word on line 5: %ld", rep.units_line);
  swarf_stock_free(s);
  /* a bad parameter file: new fails with its place */
  {
    swarf_sim *sim = NULL;
    swarf_error err;
    FILE *f = fopen("test_sim_setup_bad.var", "w");
    fputs("5221 1\n5222 1 2\n", f);
    fclose(f);
    config(&cfg, "box:-20,-20,-10,20,20,0");
    cfg.offsets_file = "test_sim_setup_bad.var";
    CHECK(swarf_sim_new(&cfg, "t.ngc", &sim, &err) == SWARF_ERR_FORMAT && sim == NULL,
          "bad offsets file: status %d", err.status);
    CHECK(err.line == 2 && !strcmp(err.file, "test_sim_setup_bad.var"), "at %s:%ld", err.file,
          err.line);
    remove("test_sim_setup_bad.var");
  }
}

int main(void) {
  test_default_start();
  test_rotated_g54();
  test_inch_machine();
  return check_done();
}
