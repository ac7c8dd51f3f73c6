/* SPDX-License-Identifier: MPL-2.0 */
/* test_setup.c -- the machine's setup (gcode.h): start position, parameters
 * and LinuxCNC's parameter file, the machine's length unit, the first units
 * word. Expected machine positions are computed by hand from LinuxCNC's
 * motion controller formula (emccanon.cc: p += g92; rotate (x, y) by the
 * system's rotation; p += g5x; p += tool offset), not by the front end.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "collect.h"

static char dir[] = "/tmp/swarf_setup_XXXXXX";

static const char *write_file(const char *name, const char *text) {
  static char path[256];
  FILE *f;
  snprintf(path, sizeof path, "%s/%s", dir, name);
  f = fopen(path, "w");
  fputs(text, f);
  fclose(f);
  return path;
}

static collected *run_on(swarf_gcode_parser *p, const char *text, collected *c) {
  memset(c, 0, sizeof *c);
  collect_end(c, p, swarf_gcode_parser_feed(p, text, strlen(text)));
  return c;
}

static swarf_gcode_parser *new_parser(collected *c) {
  swarf_gcode_parser *p = NULL;
  swarf_gcode_parser_new("test.ngc", collect_move, c, &p);
  swarf_gcode_parser_set_fragment(p, 1, NULL); /* test texts need not end */
  return p;
}

static void check_point(const double *got, double x, double y, double z, const char *what) {
  char w[160];
  const double want[3] = {x, y, z};
  for (int k = 0; k < 3; k++) {
    snprintf(w, sizeof w, "%s, axis %c", what, "XYZ"[k]);
    CHECK_NEAR(got[k], want[k], 1e-9, w);
  }
}

/* The first move starts where the machine was put; G91 adds to the point. */
static void test_start(void) {
  static collected c;
  const double start[SWARF_NAXES] = {10, 20, 30, 0, 0, 0};
  swarf_gcode_parser *p = new_parser(&c);
  CHECK(swarf_gcode_parser_set_start(p, start, NULL) == SWARF_OK, "set_start");
  run_on(p, "G91 G0 X1\nG90 G1 Z5 F100\n", &c);
  CHECK(c.status == 0 && c.n == 2, "status %d, %d moves", c.status, c.n);
  check_point(c.moves[0].start, 10, 20, 30, "first move starts at the start");
  check_point(c.moves[0].end, 11, 20, 30, "G91 X1 from the start");
  check_point(c.moves[1].end, 11, 20, 5, "then G90 Z5");

  /* a start given after the offsets, or before: the same machine position */
  p = new_parser(&c);
  swarf_gcode_parser_set_start(p, start, NULL);
  swarf_gcode_parser_set_units(p, SWARF_GCODE_UNITS_MM, NULL);
  swarf_gcode_parser_set_param(p, 5221, 5, NULL);
  run_on(p, "G91 G0 X1\n", &c);
  check_point(c.moves[0].start, 10, 20, 30, "start before the G54 offset");
  check_point(c.moves[0].end, 11, 20, 30, "G91 X1 (G54 X5)");

  p = new_parser(&c);
  swarf_gcode_parser_set_start(p, start, NULL);
  CHECK(swarf_gcode_parser_feed(p, "G0 X1\n", 6) == 0, "feed");
  CHECK(swarf_gcode_parser_set_start(p, start, NULL) == SWARF_ERR_STATE, "set_start after feed");
  CHECK(swarf_gcode_parser_set_param(p, 5221, 1, NULL) == SWARF_ERR_STATE, "set_param after feed");
  swarf_gcode_parser_free(p);
}

/* A parameter file: G54 origin, G55, a rotation, G28 home, #5220. */
static void test_param_file(void) {
  static collected c;
  swarf_error err;
  double o[SWARF_NAXES], rot;
  const char *path = write_file("ok.var", "31\t2.500000\n"
                                          "5161\t0.000000\n5162\t0.000000\n5163\t-10.000000\n"
                                          "\n"
                                          "5221\t10.000000\n5222 -5.0\n  5223   -50 \r\n"
                                          "5241\t100.000000\n5250\t90.000000\n");
  swarf_gcode_parser *p = new_parser(&c);
  swarf_gcode_parser_set_units(p, SWARF_GCODE_UNITS_MM, NULL);
  CHECK(swarf_gcode_parser_load_params(p, path, &err) == SWARF_OK, "load: %s", err.message);
  swarf_gcode_parser_work_system(p, 1, o, &rot);
  check_point(o, 10, -5, -50, "G54 origin read back");
  swarf_gcode_parser_work_system(p, 2, o, &rot);
  CHECK_NEAR(rot, 90, 0, "G55 rotation");
  CHECK(swarf_gcode_parser_work_system(p, 10, o, &rot) == SWARF_ERR_ARG, "system 10");
  run_on(p,
         "G0 X1 Y2 Z3\n"      /* G54: + (10, -5, -50) */
         "G53 G0 Z-3\n"       /* machine Z -3, X Y unchanged */
         "G0 Z#31\n"          /* a user parameter from the file */
         "G28\n"              /* to machine Z -10 via where it is */
         "G55 G0 X1 Y2 Z0\n", /* rotated 90: (1, 2) -> (-2, 1), + (100, 0, 0) */
         &c);
  CHECK(c.status == 0 && c.n == 6, "status %d (%s), %d moves", c.status, c.error.message, c.n);
  check_point(c.moves[0].end, 11, -3, -47, "G0 X1 Y2 Z3 in G54");
  check_point(c.moves[1].end, 11, -3, -3, "G53 G0 Z-3 goes to machine Z-3");
  check_point(c.moves[2].end, 11, -3, -47.5, "G0 Z#31 (2.5 in G54)");
  check_point(c.moves[4].end, 0, 0, -10, "G28 home from #5161-#5163");
  check_point(c.moves[5].end, 98, 1, 0, "G55 rotated 90 degrees");

  /* #5220 selects the work system in force; #5210 restores the G92 offset */
  path = write_file("g55.var", "5211 1\n5212 2\n5213 3\n5210 1\n5220 2\n5241 100\n");
  p = new_parser(&c);
  swarf_gcode_parser_set_units(p, SWARF_GCODE_UNITS_MM, NULL);
  CHECK(swarf_gcode_parser_load_params(p, path, &err) == SWARF_OK, "load: %s", err.message);
  run_on(p, "G0 X0 Y0 Z0\n", &c);
  check_point(c.moves[0].end, 101, 2, 3, "#5220 = 2 (G55) and G92 from #5211-#5213");

  /* In an inch machine, the file holds inches */
  path = write_file("inch.var", "5221 1\n5223 -2\n");
  p = new_parser(&c);
  swarf_gcode_parser_set_units(p, SWARF_GCODE_UNITS_INCH, NULL);
  CHECK(swarf_gcode_parser_load_params(p, path, &err) == SWARF_OK, "load: %s", err.message);
  run_on(p, "G0 X1 Z0\n", &c);
  check_point(c.moves[0].end, 50.8, 0, -50.8, "inch machine: X1 Z0 in, G54 X1 Z-2 in");
  p = new_parser(&c);
  CHECK(swarf_gcode_parser_set_units(p, 0, NULL) == SWARF_ERR_ARG, "unit 0");
  swarf_gcode_parser_free(p);
}

/* Each bad file: FORMAT (or OPEN) at the right line, and the parser unchanged. */
static void test_bad_files(void) {
  static const struct {
    const char *text;
    long line;
    int code; /* SWARF_GCODE_E_* */
  } bad[] = {
      {"5221 10\n5222 x\n", 2, SWARF_GCODE_E_PARAMS_LINE},
      {"5221\n", 1, SWARF_GCODE_E_PARAMS_LINE},
      {"5221 10 20\n", 1, SWARF_GCODE_E_PARAMS_LINE},
      {"5221 10.0 ; G54 X\n", 1, SWARF_GCODE_E_PARAMS_LINE},
      {"5221 nan\n", 1, SWARF_GCODE_E_PARAMS_LINE},
      {"5221 0x10\n", 1, SWARF_GCODE_E_PARAMS_LINE},
      {"-5221 10\n", 1, SWARF_GCODE_E_PARAMS_LINE},
      {"5221 10\n\n5221 11\n", 3, SWARF_GCODE_E_PARAMS_TWICE},
      {"5602 1\n", 1, SWARF_GCODE_E_PARAM_NOT_FOUND},
      {"0 1\n", 1, SWARF_GCODE_E_PARAM_NOT_FOUND},
      {"5420 1\n", 1, SWARF_GCODE_E_PARAM_COMPUTED},
      {"5220 12\n", 1, SWARF_GCODE_E_SYSTEM_PARAM_VALUE},
      {"5210 2\n", 1, SWARF_GCODE_E_G92_PARAM_VALUE},
      {"5221 1e300\n", 1, SWARF_GCODE_E_PARAM_VALUE},
  };
  static collected c;
  swarf_error err;
  double o[SWARF_NAXES];
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    const char *path = write_file("bad.var", bad[i].text);
    swarf_gcode_parser *p = new_parser(&c);
    swarf_status s;
    swarf_gcode_parser_set_units(p, SWARF_GCODE_UNITS_MM, NULL);
    swarf_error_init(&err);
    s = swarf_gcode_parser_load_params(p, path, &err);
    CHECK(s == SWARF_ERR_FORMAT, "case %zu: status %d", i, s);
    CHECK(err.line == bad[i].line && strcmp(err.file, path) == 0, "case %zu: at %s:%ld", i,
          err.file, err.line);
    CHECK(err.code == bad[i].code, "case %zu: %s (%s)", i, swarf_gcode_error_name(err.code),
          err.message);
    swarf_gcode_parser_work_system(p, 1, o, NULL);
    check_point(o, 0, 0, 0, "a failed load changes nothing");
    run_on(p, "G0 X1\n", &c);
    check_point(c.moves[0].end, 1, 0, 0, "a failed load changes nothing (move)");
  }
  {
    swarf_gcode_parser *p = new_parser(&c);
    CHECK(swarf_gcode_parser_load_params(p, "/nonexistent/x.var", &err) == SWARF_ERR_OPEN,
          "missing file");
    swarf_gcode_parser_free(p);
  }
}

/* The machine's unit: programs without G20/G21 run in it; the first units
 * word's line is kept. */
static void test_units(void) {
  static collected c;
  swarf_gcode_parser *p = new_parser(&c);
  swarf_gcode_parser_set_units(p, SWARF_GCODE_UNITS_INCH, NULL);
  run_on(p, "G0 X1\n", &c);
  check_point(c.moves[0].end, 25.4, 0, 0, "inch machine, no units word");

  p = new_parser(&c);
  swarf_gcode_parser_set_units(p, SWARF_GCODE_UNITS_INCH, NULL);
  CHECK(swarf_gcode_parser_feed(p, "G0 X1\n(x)\nG21\nG0 X1\nG20\n", 22) == 0, "feed");
  CHECK(swarf_gcode_parser_units_line(p) == 3, "first units word on line 3, got %ld",
        swarf_gcode_parser_units_line(p));
  swarf_gcode_parser_free(p);

  p = new_parser(&c);
  CHECK(swarf_gcode_parser_feed(p, "G0 X1\n", 6) == 0, "feed");
  CHECK(swarf_gcode_parser_units_line(p) == 0, "no units word");
  swarf_gcode_parser_free(p);

  /* Without set_units, offset parameters stay in inches (rs274 without an INI) */
  p = new_parser(&c);
  swarf_gcode_parser_set_param(p, 5221, 1, NULL);
  run_on(p, "G0 X0\n", &c);
  check_point(c.moves[0].end, 25.4, 0, 0, "default: #5221 in inches");
  p = new_parser(&c);
  swarf_gcode_parser_set_param(p, 5221, 1, NULL);
  CHECK(swarf_gcode_parser_set_units(p, SWARF_GCODE_UNITS_MM, NULL) == SWARF_ERR_STATE,
        "unit after a parameter");
  swarf_gcode_parser_free(p);
}

int main(void) {
  if (mkdtemp(dir) == NULL) return 1;
  test_start();
  test_param_file();
  test_bad_files();
  test_units();
  {
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0) return 1;
  }
  return check_done();
}
