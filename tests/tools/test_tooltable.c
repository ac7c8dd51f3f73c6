/* SPDX-License-Identifier: MPL-2.0 */
/* test_tooltable.c -- LinuxCNC tool tables (--tool-table) and tool
 * libraries (--tool-library) read into the simulation's tool table.
 *
 * Tables: every upstream LinuxCNC case that comes with a test.tbl
 * (../shared/conformance/linuxcnc/ * /test.tbl, inches as rs274 reads them)
 * is read with swarf_sim_config_load_tool_table; the diameters and lengths
 * it gives are handed to the interpreter and the case's program must then
 * produce rs274's own motion calls (cutter compensation uses the diameters,
 * G43 the lengths), and the values are also checked against the files'
 * text. Bad tables are refused with FILE:LINE and the reason.
 *
 * Libraries: tests/tools/tooltables/library.json read back field by field;
 * bad libraries refused at the line of the offending key.
 *
 * Usage: test_tooltable <conformance-dir> <this folder>.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../gcode/canon_compare.h"
#include "check.h"
#include "swarf_sim.h"

static const char *cases[] = {
    "cam-nisley",          "ccomp-mill-g90g91g92", "ccomp-mill-line-arc-entry",
    "ccomp-mill-zchanges", "g10-l1-l10",           "g10-l11",
    "g10-with-g92",        "machine-coord-params", "rotation-abs-pts"};

static const swarf_sim_tool *tool(const swarf_sim_config *cfg, int number) {
  for (int i = 0; i < cfg->ntools; i++)
    if (cfg->tools[i].number == number) return &cfg->tools[i];
  return NULL;
}

/* The case's program with the tools of cfg, against rs274's calls. */
static void run_case(const char *root, const char *dir, const swarf_sim_config *cfg) {
  char path[1024], exp_path[1024], why[200] = "";
  size_t len, elen;
  canon_text out = {0};
  canon_calls got, want;
  int messages = strcmp(dir, "rotation-abs-pts") == 0 || strcmp(dir, "machine-coord-params") == 0;
  const char *program = strcmp(dir, "cam-nisley") == 0 ? "cam.ngc" : "test.ngc";
  snprintf(path, sizeof path, "%s/linuxcnc/%s/%s", root, dir, program);
  snprintf(exp_path, sizeof exp_path, "%s/linuxcnc/%s/expected", root, dir);
  char *text = canon_slurp(path, &len), *expected = canon_slurp(exp_path, &elen);
  CHECK(text != NULL && expected != NULL, "%s: cannot read %s or %s", dir, path, exp_path);
  if (text == NULL || expected == NULL) return free(text), free(expected);
  swarf_gcode_parser *p = NULL;
  CHECK(swarf_gcode_parser_new(program, NULL, NULL, &p) == SWARF_OK, "parser");
  if (p == NULL) return free(text), free(expected);
  swarf_gcode_parser_set_canon(p, canon_collect, &out);
  swarf_gcode_parser_clear_tools(p);
  for (int i = 0; i < cfg->ntools; i++)
    swarf_gcode_parser_set_tool(p, cfg->tools[i].number, cfg->tools[i].length,
                                cfg->tools[i].cutter.diameter);
  swarf_status status = swarf_gcode_parser_feed(p, text, len);
  if (status == SWARF_OK) status = swarf_gcode_parser_finish(p);
  CHECK(status == SWARF_OK, "%s: rejected: %s", dir,
        swarf_gcode_parser_error(p) ? swarf_gcode_parser_error(p)->message : "?");
  swarf_gcode_parser_free(p);
  if (out.text == NULL) canon_collect("", &out);
  canon_extract(out.text, messages, &got);
  canon_extract(expected, messages, &want);
  CHECK(!canon_differ(&got, &want, 1.01e-4, why, sizeof why), "%s: %s", dir, why);
  printf("%-28s %zu %s calls match rs274 with the table read by swarf\n", dir, want.n,
         messages ? "MESSAGE" : "motion");
  free(got.v);
  free(want.v);
  free(out.text);
  free(text);
  free(expected);
}

static void tables(const char *root) {
  char probe[1024];
  snprintf(probe, sizeof probe, "%s/linuxcnc/INDEX.md", root);
  if (access(probe, R_OK) != 0) { /* a clone without ../shared beside it */
    printf("SKIPPED (part): LinuxCNC's tables are not here (%s): they live in ../shared\n", probe);
    return;
  }
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char path[1024];
    swarf_sim_config cfg;
    swarf_error err;
    swarf_sim_config_init(&cfg);
    snprintf(path, sizeof path, "%s/linuxcnc/%s/test.tbl", root, cases[i]);
    CHECK(swarf_sim_config_load_tool_table(&cfg, path, 25.4, &err) == SWARF_OK, "%s: %s:%ld: %s",
          cases[i], err.file, err.line, err.message);
    if (strncmp(cases[i], "cam", 3) == 0 || strncmp(cases[i], "ccomp", 5) == 0) {
      /* T1 P1 Z0.5 D0.0625, T2 Z0.7 D0.125, T3 Z0.5 D0.25, T4 Z0.7 D1.0, T32 Z0.5 D0.0 (inches) */
      static const double z[5] = {0.5, 0.7, 0.5, 0.7, 0.5}, d[5] = {0.0625, 0.125, 0.25, 1.0, 0};
      static const int n[5] = {1, 2, 3, 4, 32};
      CHECK(cfg.ntools == 5, "%s: 5 tools, got %d", cases[i], cfg.ntools);
      for (int k = 0; k < 5; k++) {
        const swarf_sim_tool *t = tool(&cfg, n[k]);
        CHECK(t != NULL, "%s: T%d read", cases[i], n[k]);
        if (t == NULL) continue;
        CHECK_NEAR(t->length, z[k] * 25.4, 1e-12, "Z in mm");
        CHECK_NEAR(t->cutter.diameter, d[k] * 25.4, 1e-12, "D in mm");
        CHECK(d[k] == 0 || (t->cutter.shape == SWARF_CUTTER_FLAT && t->cutter.length > 0),
              "a table tool is a flat end mill");
      }
    } else {
      CHECK(cfg.ntools == 1 && tool(&cfg, 1) != NULL && tool(&cfg, 1)->length == 0 &&
                tool(&cfg, 1)->cutter.diameter == 0,
            "%s: T1 with Z0 and no diameter", cases[i]);
    }
    run_case(root, cases[i], &cfg);
  }
}

/* A table of one text must be refused at `line` with `words` in the reason. */
static void bad_table(const char *text, long line, const char *words) {
  char path[] = "/tmp/swarf_tbl_XXXXXX";
  int fd = mkstemp(path);
  FILE *f = fdopen(fd, "w");
  fputs(text, f);
  fclose(f);
  swarf_sim_config cfg;
  swarf_error err;
  swarf_sim_config_init(&cfg);
  swarf_status s = swarf_sim_config_load_tool_table(&cfg, path, 1.0, &err);
  char shown[800];
  swarf_error_format(&err, shown, sizeof shown);
  CHECK(s == SWARF_ERR_TOOL && err.line == line && strcmp(err.file, path) == 0 &&
            strstr(err.message, words) != NULL,
        "refused at line %ld with \"%s\": got %s (%s)", line, words, shown, swarf_status_name(s));
  printf("bad table refused: %s\n", shown);
  remove(path);
}

static void bad_tables(void) {
  bad_table("T1 P1 D6 Z+30\nT2 P2 D6 K3\n", 2, "unknown word \"K3\"");
  bad_table("; header\nT1 P1 D6 Z+3x0\n", 2, "bad number in \"Z+3x0\"");
  bad_table("T1 P1 D6\n\nT1 P2 D3\n", 3, "T1 is already in the table (line 1)");
  bad_table("P1 D6 Z3 ;no tool\n", 1, "no T word");
  bad_table("T1000 P1 D6\n", 1, "tool numbers run from 0 to 999");
  bad_table("T-1 P1 D6\n", 1, "tool numbers run from 0 to 999");
  bad_table("T1.5 P1 D6\n", 1, "whole numbers");
  bad_table("T1 P1 D-6\n", 1, "negative");
  bad_table("T1 P1 D6 X0.5 Z10\n", 1, "only Z offsets");
  bad_table("T1 P1 D6 Znan\n", 1, "bad number");
  /* accepted: comments, blank lines, tabs, lower case, lathe fields, no final newline, and
   * T0 (LinuxCNC's empty spindle: rs274 reads the line) */
  char path[] = "/tmp/swarf_tbl_XXXXXX";
  FILE *f = fdopen(mkstemp(path), "w");
  fputs(";T9 is a comment\nT0 P0 Z0 D0 ;empty spindle\n t7\tp3 d0.25 z-1.5 i95 j155 q2 ;a ; b\nT8 "
        "P4 D3",
        f);
  fclose(f);
  swarf_sim_config cfg;
  swarf_error err;
  swarf_sim_config_init(&cfg);
  CHECK(swarf_sim_config_load_tool_table(&cfg, path, 25.4, &err) == SWARF_OK, "good table: %s",
        err.message);
  CHECK(cfg.ntools == 2 && tool(&cfg, 7) && tool(&cfg, 8) && !tool(&cfg, 9), "T7 and T8 only");
  if (tool(&cfg, 7)) CHECK_NEAR(tool(&cfg, 7)->length, -1.5 * 25.4, 1e-12, "T7 Z");
  if (tool(&cfg, 8)) CHECK_NEAR(tool(&cfg, 8)->cutter.diameter, 3 * 25.4, 1e-12, "T8 D");
  remove(path);
  CHECK(swarf_sim_config_load_tool_table(&cfg, "/nonexistent/t.tbl", 1, &err) == SWARF_ERR_OPEN,
        "a missing table is refused");
}

/* ---- Libraries ------------------------------------------------------------ */

static void good_library(const char *here) {
  char path[1024];
  swarf_sim_config cfg;
  swarf_error err;
  swarf_sim_config_init(&cfg);
  snprintf(path, sizeof path, "%s/tooltables/library.json", here);
  /* a table first: the library keeps its lengths unless it gives one */
  FILE *f = fopen("/tmp/swarf_lib_table.tbl", "w");
  fputs("T1 P1 D3 Z+40\nT2 P2 D6 Z+50\nT5 P5 D10 Z+60\n", f);
  fclose(f);
  CHECK(swarf_sim_config_load_tool_table(&cfg, "/tmp/swarf_lib_table.tbl", 1, &err) == SWARF_OK,
        "table: %s", err.message);
  remove("/tmp/swarf_lib_table.tbl");
  CHECK(swarf_sim_config_load_tool_library(&cfg, path, &err) == SWARF_OK, "%s:%ld: %s", err.file,
        err.line, err.message);
  const swarf_sim_tool *t1 = tool(&cfg, 1), *t2 = tool(&cfg, 2), *t3 = tool(&cfg, 3),
                       *t5 = tool(&cfg, 5);
  CHECK(cfg.ntools == 4 && t1 && t2 && t3 && t5, "T1 T2 T3 T5, got %d tools", cfg.ntools);
  if (!t1 || !t2 || !t3 || !t5) return;
  CHECK(t1->cutter.shape == SWARF_CUTTER_FLAT && t1->cutter.diameter == 6 &&
            t1->cutter.length == 12 && t1->stickout == 30 && t1->shank == 6 && t1->length == 85.5,
        "T1: flat D6, flutes 12, stick-out 30, shank 6, its own length 85.5");
  CHECK(t1->nholder == 2 && t1->holder[0].d0 == 20 && t1->holder[0].d1 == 20 &&
            t1->holder[0].height == 40 && t1->holder[1].d0 == 20 && t1->holder[1].d1 == 32 &&
            t1->holder[1].height == 10,
        "T1: holder 20x40 then a cone 20-32 x 10");
  CHECK(t2->cutter.shape == SWARF_CUTTER_BALL && t2->cutter.diameter == 3.175 &&
            t2->cutter.length == 12.7 && t2->stickout == 20 && t2->shank == 0 && t2->length == 50 &&
            t2->nholder == 1 && t2->holder[0].d0 == 16 && t2->holder[0].height == 30,
        "T2: ball, flutes in the spec, the table's length kept, holder from a string");
  CHECK(t3->cutter.shape == SWARF_CUTTER_BULL && t3->cutter.corner_radius == 1 &&
            t3->stickout == 0 && t3->nholder == 0 && t3->length == 0,
        "T3: a bull nose without an assembly");
  CHECK(t5->cutter.diameter == 10 && t5->length == 60 && t5->stickout == 0,
        "T5: only in the table, unchanged");
}

/* A library of one text must be refused at `line` with `words` in the reason. */
static void bad_library(const char *text, long line, const char *words) {
  char path[] = "/tmp/swarf_lib_XXXXXX";
  FILE *f = fdopen(mkstemp(path), "w");
  fputs(text, f);
  fclose(f);
  swarf_sim_config cfg;
  swarf_error err;
  char shown[800];
  swarf_sim_config_init(&cfg);
  swarf_status s = swarf_sim_config_load_tool_library(&cfg, path, &err);
  swarf_error_format(&err, shown, sizeof shown);
  CHECK(s != SWARF_OK && err.line == line && strstr(err.message, words) != NULL,
        "refused at line %ld with \"%s\": got %s", line, words, shown);
  printf("bad library refused: %s\n", shown);
  remove(path);
}

static void bad_libraries(void) {
  bad_library("{\"tools\": [\n  {\"number\": 1, \"cutter\": \"flat,D6\"},\n  {\"number\": 2,\n"
              "   \"cutter\": \"flat,D6\" \"stickout\": 3}\n]}\n",
              4, "not valid JSON");
  bad_library("{\"tools\": [\n  {\"number\": 1, \"cutter\": \"flat,D6\"},\n  {\"number\": 2,\n"
              "   \"cutter\": \"flat,D6\",\n   \"stikout\": 30}\n]}\n",
              5, "unknown key \"stikout\"");
  bad_library("{\"tools\": [\n  {\"number\": 1,\n   \"cutter\": \"flat,D6\",\n"
              "   \"stickout\": -3}\n]}\n",
              4, "\"stickout\" must be > 0");
  bad_library("{\"tools\": [\n  {\"number\": 1, \"cutter\": \"flat,D6\"},\n"
              "  {\"number\": 2, \"cutter\": \"flat,D6\",\n   \"holder\": [{\"diameter\": 20, "
              "\"height\": 40}]}\n]}\n",
              3, "holder but no stick-out");
  bad_library("{\"tools\": [\n  {\"number\": 4,\n   \"cutter\": \"vbit,D6\"}\n]}\n", 3,
              "\"cutter\"");
  bad_library("{\"tools\": [\n  {\"number\": 4, \"cutter\": \"flat,D6\"},\n"
              "  {\"number\": 4, \"cutter\": \"ball,D6\"}\n]}\n",
              3, "T4 is already in the library (line 2)");
  bad_library("{\"tools\": [\n  {\"cutter\": \"flat,D6\"}\n]}\n", 2, "\"number\"");
  bad_library("{\"tools\": [\n  {\"number\": 1, \"cutter\": \"flat,D6\", \"stickout\": 30,\n"
              "   \"holder\": [{\"diameter\": [20], \"height\": 40}]}\n]}\n",
              3, "holder piece");
  bad_library("[1, 2]\n", 1, "{\"tools\"");
}

/* ---- G43 with the table's lengths ------------------------------------------ */

/* Removed volume of a plunge of T1 (flat D6, table length 50) from Z5 to Z-3
 * at (10, 10) under `g43`. The tip follows the machine: G43 H1 puts it where
 * the program says (a hole 3 deep: 27 pi mm^3); G43 H2 (T2 is 45 long) 5 mm
 * lower (8 deep: 72 pi); G49 (no offset) 50 mm lower: the first traverse,
 * from the start position (0,0,0, the tip's), dives through the stock to
 * Z-45 and the plunge stays under it (the stock is 20 deep). */
static double plunge_volume(const char *g43) {
  char program[256], path[] = "/tmp/swarf_g43_XXXXXX";
  FILE *f = fdopen(mkstemp(path), "w");
  fputs("T1 P1 D6 Z+50\nT2 P2 D6 Z+45\n", f);
  fclose(f);
  swarf_sim_config cfg;
  swarf_error err;
  swarf_sim_config_init(&cfg);
  cfg.voxel = 0.1;
  CHECK(swarf_sim_parse_stock("box:0,0,-20,20,20,0", &cfg.stock, &err) == SWARF_OK, "stock");
  CHECK(swarf_sim_config_load_tool_table(&cfg, path, 1.0, &err) == SWARF_OK, "%s", err.message);
  remove(path);
  snprintf(program, sizeof program, "T1 M6\n%s\nG0 X10 Y10 Z5\nG1 Z-3 F100\nG1 Z5\nM2\n", g43);
  swarf_stock *out = NULL;
  swarf_sim_report rep;
  CHECK(swarf_sim_run_text(&cfg, "g43.ngc", program, strlen(program), &out, &rep, &err) == SWARF_OK,
        "%s: %s", g43, err.message);
  swarf_stock_free(out);
  return rep.volume_before - rep.volume_after;
}

static void g43_lengths(void) {
  const double pi = 3.14159265358979;
  double h1 = plunge_volume("G43 H1"), h2 = plunge_volume("G43 H2"), none = plunge_volume("G49");
  printf("G43 H1: removed %.3f mm^3 (27 pi = %.3f); G43 H2: %.3f (72 pi = %.3f); G49: %.3f\n", h1,
         27 * pi, h2, 72 * pi, none);
  CHECK(fabs(h1 - 27 * pi) < 0.02 * 27 * pi, "G43 H1: the tip lands where the program says");
  CHECK(fabs(h2 - 72 * pi) < 0.02 * 72 * pi, "G43 H2 on T1: 5 mm lower, as on the machine");
  CHECK(none > 5 * h2, "G49: the gauge line at the program's Z, the tip 50 mm lower");
}

int main(int argc, char **argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: %s <conformance-dir> <tests/tools>\n", argv[0]);
    return 2;
  }
  tables(argv[1]);
  bad_tables();
  good_library(argv[2]);
  bad_libraries();
  g43_lengths();
  return check_done();
}
