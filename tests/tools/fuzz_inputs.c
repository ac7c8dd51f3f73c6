/* fuzz_inputs.c -- the fuzz entry of the small readers of user input.
 *
 * The first byte picks the reader, the rest is its input:
 *   0 tool table, both readers: `swarf parse --tools` (gcode/tools.c, inches)
 *     and `--tool-table` (tools/sim/tooltable.c), from a memfd (a regular file)
 *   1 tool library JSON (tools/sim/library.c), from a memfd
 *   2 --tool spec  3 --stock spec  4 --machine spec  5 --holder spec
 *   6 --fixture spec
 * Invariants (a breach aborts): a reader returns OK or an input status
 * (exit 2 class) with a message; a table error names a line within the
 * input; what a reader accepts is finite (lengths, diameters, boxes), tool
 * diameters are >= 0 and boxes have lo < hi (an STL fixture's bounds come
 * later, from the mesh).
 * Built with libFuzzer under clang (tools_inputs_fuzz), and linked into a
 * plain smoke driver (tests/gcode/fuzz_smoke.c) everywhere.
 */
#define _GNU_SOURCE
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "gcode.h"
#include "swarf_sim.h"

static void fail(const char *why, const swarf_error *e) {
  fprintf(stderr, "fuzz_inputs: %s (%s)\n", why, e ? e->message : "");
  abort();
}

static void check_status(swarf_status s, const swarf_error *e) {
  if (s == SWARF_OK) return;
  if (swarf_status_classify(s) != SWARF_CLASS_INPUT)
    fail("a reader failed as an internal error", e);
  if (e->message[0] == '\0') fail("an error without a message", e);
}

/* The input as a regular file: /proc/self/fd/N of a memfd. */
static int as_file(const uint8_t *data, size_t size, char path[64]) {
  int fd = memfd_create("fuzz", MFD_CLOEXEC);
  if (fd < 0) return -1;
  if (size > 0 && write(fd, data, size) != (ssize_t)size) {
    close(fd);
    return -1;
  }
  snprintf(path, 64, "/proc/self/fd/%d", fd);
  return fd;
}

static void check_tools(const swarf_sim_config *cfg, const swarf_error *e) {
  for (int i = 0; i < cfg->ntools; i++) {
    const swarf_sim_tool *t = &cfg->tools[i];
    if (!isfinite(t->length) || !isfinite(t->cutter.diameter) || t->cutter.diameter < 0)
      fail("a tool with a non-finite or negative value", e);
  }
}

static void tool_table(const uint8_t *data, size_t size) {
  char path[64];
  long lines = 1;
  swarf_error e;
  swarf_gcode_parser *p = NULL;
  swarf_sim_config cfg;
  swarf_status s;
  int fd = as_file(data, size, path);
  if (fd < 0) return;
  for (size_t i = 0; i < size; i++)
    lines += data[i] == '\n';
  swarf_error_init(&e);
  if (swarf_gcode_parser_new("fuzz", NULL, NULL, &p) != SWARF_OK) fail("out of memory", NULL);
  s = swarf_gcode_parser_load_tools(p, path, &e);
  check_status(s, &e);
  if (s != SWARF_OK && (e.line < 0 || e.line > lines)) fail("parse --tools: error line", &e);
  swarf_gcode_parser_free(p);
  swarf_sim_config_init(&cfg);
  swarf_error_init(&e);
  s = swarf_sim_config_load_tool_table(&cfg, path, 1.0, &e);
  check_status(s, &e);
  if (s != SWARF_OK && (e.line < 0 || e.line > lines)) fail("--tool-table: error line", &e);
  if (s == SWARF_OK) check_tools(&cfg, &e);
  close(fd);
}

static void tool_library(const uint8_t *data, size_t size) {
  char path[64];
  swarf_error e;
  swarf_sim_config cfg;
  swarf_status s;
  int fd = as_file(data, size, path);
  if (fd < 0) return;
  swarf_sim_config_init(&cfg);
  swarf_error_init(&e);
  s = swarf_sim_config_load_tool_library(&cfg, path, &e);
  check_status(s, &e);
  if (s == SWARF_OK) check_tools(&cfg, &e);
  close(fd);
}

static void spec(int which, const char *text) {
  swarf_error e;
  swarf_sim_tool t;
  swarf_sim_stock_spec st;
  swarf_machine m;
  swarf_sim_fixture fx;
  swarf_status s = SWARF_OK;
  swarf_error_init(&e);
  switch (which) {
  case 2:
    if ((s = swarf_sim_parse_tool(text, &t, &e)) == SWARF_OK &&
        (!isfinite(t.cutter.diameter) || t.cutter.diameter < 0 || !isfinite(t.stickout)))
      fail("--tool accepted a bad value", &e);
    break;
  case 3:
    if ((s = swarf_sim_parse_stock(text, &st, &e)) == SWARF_OK)
      for (int k = 0; k < 3; k++)
        if (!isfinite(st.lo[k]) || !isfinite(st.hi[k]) || !(st.lo[k] < st.hi[k]))
          fail("--stock accepted a bad box", &e);
    break;
  case 4:
    s = swarf_machine_parse(&m, text, &e);
    break;
  case 5:
    s = swarf_sim_parse_holder(text, &t, &e);
    break;
  default:
    if ((s = swarf_sim_parse_fixture(text, &fx, &e)) == SWARF_OK && fx.stl == NULL) /* a box */
      for (int k = 0; k < 3; k++)
        if (!isfinite(fx.lo[k]) || !isfinite(fx.hi[k]) || !(fx.lo[k] < fx.hi[k]))
          fail("--fixture accepted a bad box", &e);
  }
  check_status(s, &e);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  int which;
  char *text;
  if (size == 0) return 0;
  which = data[0] % 7;
  data++, size--;
  if (which == 0) return tool_table(data, size), 0;
  if (which == 1) return tool_library(data, size), 0;
  text = malloc(size + 1);
  if (text == NULL) return 0;
  memcpy(text, data, size);
  text[size] = '\0';
  spec(which, text);
  free(text);
  return 0;
}
