/* SPDX-License-Identifier: MPL-2.0 */
/* fuzz_inputs.c -- the fuzz entry of the small readers of user input.
 *
 * The first byte picks the reader, the rest is its input:
 *   0 tool table, both readers: `swarf parse --tools` (gcode/tools.c, inches)
 *     and `--tool-table` (tools/sim/readers/tooltable.c), from a memfd (a regular file)
 *   1 tool library JSON (tools/sim/readers/library.c), from a memfd
 *   2 --tool spec  3 --stock spec  4 --machine spec  5 --holder spec
 *   6 --fixture spec
 *   7 --modbus spec, 8 --modbus-push spec (tools/modbus/modbus_spec.c)
 *   9 --offsets: LinuxCNC's parameter file (gcode/params_file.c), from a
 *     memfd, into a parser then run on a probe program that uses every
 *     offset (G54-G59.3, G28, G30, G92, G43)
 *   10 --stock-transform (a placement), 11 --view (stock.h)
 * Invariants (a breach aborts): a reader returns OK or an input status
 * (exit 2 class) with a message; a table error names a line within the
 * input; what a reader accepts is finite (lengths, diameters, boxes), tool
 * diameters are >= 0 and boxes have lo < hi (an STL fixture's bounds come
 * later, from the mesh); an endpoint accepted has every field in its range;
 * a parameter file accepted gives finite moves or a G-code error, one
 * refused leaves the parser as it was (the probe's moves equal a fresh
 * parser's).
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
#include "modbus_private.h"
#include "stock.h"
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
  swarf_stock_placement pl;
  swarf_stock_view view;
  swarf_status s = SWARF_OK;
  swarf_error_init(&e);
  switch (which) {
  case 10:
    if ((s = swarf_stock_placement_parse(text, &pl, &e)) == SWARF_OK)
      for (int k = 0; k < 3; k++)
        if (!isfinite(pl.t[k]) || !isfinite(pl.r[k]))
          fail("--stock-transform accepted a bad value", &e);
    break;
  case 11:
    s = swarf_stock_view_parse(text, &view, &e);
    break;
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

/* 7, 8: an endpoint of --modbus (server) or --modbus-push. */
static void modbus_spec(int push, const char *text) {
  swarf_mb_endpoint e;
  swarf_error err;
  char *end;
  long port;
  swarf_error_init(&err);
  if (swarf_mb_endpoint_parse(text, push, &e, &err) != SWARF_OK) {
    if (err.message[0] == '\0' || err.status != SWARF_ERR_ARG)
      fail("--modbus: a refusal without a message or not SWARF_ERR_ARG", NULL);
    return;
  }
  if (e.unit < 1 || e.unit > 247) fail("--modbus: unit out of 1..247", NULL);
  if (e.kind == SWARF_MB_TCP) {
    port = strtol(e.port, &end, 10);
    if (memchr(e.host, '\0', sizeof e.host) == NULL || e.host[0] == '\0' || *end != '\0' ||
        end == e.port || port < 0 || port > 65535 || (push && port == 0))
      fail("--modbus: a bad host or port accepted", NULL);
  } else if (push || memchr(e.device, '\0', sizeof e.device) == NULL || e.device[0] == '\0' ||
             e.baud < 50 || e.baud > 4000000 || e.data_bits < 5 || e.data_bits > 8 ||
             e.stop_bits < 1 || e.stop_bits > 2 || !strchr("NEO", e.parity) || e.parity == 0) {
    fail("--modbus: a bad serial endpoint accepted", NULL);
  }
  if (push && (e.address < 0 || e.address > 65536 - SWARF_MB_NREGS ||
               !(e.interval >= 0.05 && e.interval <= 3600)))
    fail("--modbus-push: address or interval out of range", NULL);
}

/* The probe program run after a parameter file: every work system, the
 * homes, G92 and a tool length offset, in both units. */
static const char probe[] = "G0 X1 Y2 Z3\nG55 G0 X0\nG56 X0\nG57 X0\nG58 X0\nG59 X0\n"
                            "G59.1 X0\nG59.2 X0\nG59.3 X0\nG54 X0\nG28\nG30\nG92 X0 Y0\n"
                            "G1 X1 F100\nG92.1\nG20 G0 X1\nG43.1 Z1\nG0 Z0\nG91 X-1\nM2\n";

typedef struct {
  uint64_t hash;
  long moves;
} probe_run;

static int on_probe_move(const swarf_move *mv, void *user) {
  probe_run *r = user;
  for (int k = 0; k < SWARF_NAXES; k++)
    if (!isfinite(mv->start[k]) || !isfinite(mv->end[k]))
      fail("--offsets: a move with a non-finite coordinate", NULL);
  for (size_t i = 0; i < sizeof mv->end; i++)
    r->hash = (r->hash ^ ((const uint8_t *)mv->end)[i]) * 1099511628211ull;
  r->moves++;
  return 0;
}

/* Runs the probe in `p` (which it frees): the status, the moves' hash. */
static swarf_status run_probe(swarf_gcode_parser *p, probe_run *r) {
  swarf_status s = swarf_gcode_parser_feed(p, probe, sizeof probe - 1);
  if (s == SWARF_OK) s = swarf_gcode_parser_finish(p);
  if (s != SWARF_OK && swarf_status_classify(s) != SWARF_CLASS_INPUT)
    fail("--offsets: the probe failed as an internal error", swarf_gcode_parser_error(p));
  swarf_gcode_parser_free(p);
  return s;
}

static void offsets_file(const uint8_t *data, size_t size) {
  char path[64];
  long lines = 1;
  swarf_error e;
  swarf_gcode_parser *p = NULL, *fresh = NULL;
  probe_run got = {14695981039346656037ull, 0}, want = got;
  swarf_status s;
  int fd = as_file(data, size, path);
  if (fd < 0) return;
  for (size_t i = 0; i < size; i++)
    lines += data[i] == '\n';
  swarf_error_init(&e);
  if (swarf_gcode_parser_new("probe", on_probe_move, &got, &p) != SWARF_OK ||
      swarf_gcode_parser_new("probe", on_probe_move, &want, &fresh) != SWARF_OK)
    fail("out of memory", NULL);
  s = swarf_gcode_parser_load_params(p, path, &e);
  close(fd);
  check_status(s, &e);
  if (s != SWARF_OK && (e.line < 1 || e.line > lines || e.column < 1))
    fail("--offsets: error place", &e);
  if (run_probe(p, &got) != SWARF_OK && s != SWARF_OK) fail("--offsets: the probe failed", NULL);
  if (s == SWARF_OK) {
    swarf_gcode_parser_free(fresh);
    return;
  }
  run_probe(fresh, &want);
  if (got.moves != want.moves || got.hash != want.hash)
    fail("--offsets: a refused file changed the parser", &e);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  int which;
  char *text;
  if (size == 0) return 0;
  which = data[0] % 12;
  data++, size--;
  if (which == 0) return tool_table(data, size), 0;
  if (which == 1) return tool_library(data, size), 0;
  if (which == 9) return offsets_file(data, size), 0;
  text = malloc(size + 1);
  if (text == NULL) return 0;
  memcpy(text, data, size);
  text[size] = '\0';
  if (which == 7 || which == 8)
    modbus_spec(which == 8, text);
  else
    spec(which, text);
  free(text);
  return 0;
}
