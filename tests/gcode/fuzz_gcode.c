/* SPDX-License-Identifier: MPL-2.0 */
/* fuzz_gcode.c -- the fuzz entry of the G-code front end.
 *
 * LLVMFuzzerTestOneInput runs the input through a parser twice: whole, and
 * in pieces whose sizes come from the input's first byte. Both runs must
 * agree exactly (same moves, same status, same error place), and every move
 * must be sane: finite numbers, a unit normal and a sweep in (0, 2 pi 10^4]
 * for arcs, a feed above 0 on every arc and feed line, lines within the
 * input (loops and calls run lines again, so lines need not grow), columns
 * from 1. Any breach aborts.
 * Built with libFuzzer under clang, and linked into fuzz_smoke (a plain
 * driver) everywhere.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gcode.h"

#define FUZZ_WORK_LIMIT 100000L

typedef struct {
  uint64_t hash;
  long moves;
  long lines; /* lines in the input: a move's line is 1..lines */
} fuzz_run;

static void fail(const char *why) {
  fprintf(stderr, "fuzz_gcode: %s\n", why);
  abort();
}

static uint64_t mix(uint64_t h, const void *p, size_t n) {
  const unsigned char *b = p;
  for (size_t i = 0; i < n; i++)
    h = (h ^ b[i]) * 1099511628211ull;
  return h;
}

static void check_finite(const double *v, int n) {
  for (int i = 0; i < n; i++)
    if (!isfinite(v[i])) fail("a move has a non-finite number");
}

static void check_move(const swarf_move *mv, fuzz_run *r) {
  check_finite(mv->start, SWARF_NAXES);
  check_finite(mv->end, SWARF_NAXES);
  check_finite(mv->center, 3);
  check_finite(&mv->angle, 1);
  check_finite(&mv->rise, 1);
  if (mv->line > r->lines || mv->line < 1 || mv->column < 1) fail("bad line or column");
  if (mv->kind == SWARF_MOVE_LINE && !(mv->feed > 0)) fail("feed line without feed");
  if (mv->feed < 0 || !isfinite(mv->feed) || !isfinite(mv->spindle)) fail("bad feed or spindle");
  if (mv->kind == SWARF_MOVE_ARC) {
    double n2 = mv->normal[0] * mv->normal[0] + mv->normal[1] * mv->normal[1] +
                mv->normal[2] * mv->normal[2];
    if (fabs(n2 - 1) > 1e-12) fail("arc normal not unit");
    if (!(mv->angle > 0 && mv->angle <= 2 * 3.14159265358979 * 10001)) fail("arc sweep");
    if (mv->feed <= 0) fail("arc without feed");
  }
}

static int on_move(const swarf_move *mv, void *user) {
  fuzz_run *r = user;
  check_move(mv, r);
  r->moves++;
  r->hash = mix(r->hash, &mv->kind, sizeof mv->kind);
  r->hash = mix(r->hash, mv->end, sizeof mv->end);
  r->hash = mix(r->hash, mv->center, sizeof mv->center);
  r->hash = mix(r->hash, &mv->angle, sizeof mv->angle);
  r->hash = mix(r->hash, &mv->line, sizeof mv->line);
  r->hash = mix(r->hash, &mv->column, sizeof mv->column);
  return 0;
}

/* The dialect an input asks for on its first line: ";fanuc", ";haas" or
 * ";grbl" (a comment in every dialect), else LinuxCNC. */
static swarf_gcode_dialect dialect_of(const uint8_t *data, size_t size) {
  static const char *names[] = {";fanuc", ";haas", ";grbl"};
  for (int i = 0; i < 3; i++) {
    size_t n = strlen(names[i]);
    if (size >= n && memcmp(data, names[i], n) == 0) return (swarf_gcode_dialect)(i + 1);
  }
  return SWARF_GCODE_DIALECT_LINUXCNC;
}

/* Runs `data` in pieces of 1..max_piece bytes (0: whole); returns the status
 * and fills the run and the error place. */
static int run(const uint8_t *data, size_t size, unsigned max_piece, uint32_t seed, fuzz_run *r,
               long *err_line, int *err_col) {
  swarf_gcode_parser *p = NULL;
  swarf_gcode_parser_new("fuzz", on_move, r, &p);
  int status = SWARF_OK;
  size_t at = 0;
  memset(r, 0, sizeof *r);
  r->hash = 14695981039346656037ull;
  r->lines = 1;
  for (size_t i = 0; i < size; i++)
    r->lines += data[i] == '\n';
  if (p == NULL) fail("out of memory");
  status = swarf_gcode_parser_set_dialect(p, dialect_of(data, size), NULL);
  /* A loop that runs to the default bound takes 20-80 s under ASan: past
   * libFuzzer's -timeout. The bound's code is the same at 100,000. */
  if (status == SWARF_OK) status = swarf_gcode_parser_set_work_limit(p, FUZZ_WORK_LIMIT, NULL);
  while (at < size && status == SWARF_OK) {
    size_t piece = size - at;
    if (max_piece) {
      seed = seed * 1103515245u + 12345u;
      piece = 1 + (seed >> 16) % max_piece;
      if (piece > size - at) piece = size - at;
    }
    status = swarf_gcode_parser_feed(p, (const char *)data + at, piece);
    at += piece;
  }
  if (status == SWARF_OK) status = swarf_gcode_parser_finish(p);
  *err_line = swarf_gcode_parser_error(p) ? swarf_gcode_parser_error(p)->line : -1;
  *err_col = swarf_gcode_parser_error(p) ? swarf_gcode_parser_error(p)->column : -1;
  if ((status == SWARF_OK) != (swarf_gcode_parser_error(p) == NULL)) fail("error record");
  swarf_gcode_parser_free(p);
  return status;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fuzz_run whole, split;
  long line_w, line_s;
  int col_w, col_s, status_w, status_s;
  unsigned max_piece = size ? 1u + data[0] % 64u : 1u;
  status_w = run(data, size, 0, 0, &whole, &line_w, &col_w);
  status_s = run(data, size, max_piece, size ? data[size - 1] : 0, &split, &line_s, &col_s);
  if (status_w != status_s || line_w != line_s || col_w != col_s)
    fail("whole and split runs end differently");
  if (whole.moves != split.moves || whole.hash != split.hash)
    fail("whole and split runs emit different moves");
  return 0;
}
