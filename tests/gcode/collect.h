/* SPDX-License-Identifier: MPL-2.0 */
/* collect.h -- helpers of the gcode tests (header only): run a program held
 * in a string through a parser, keep its moves and its error, and evaluate
 * an arc move independently of the front end (Rodrigues' rotation).
 */
#ifndef SWARF_TESTS_GCODE_COLLECT_H
#define SWARF_TESTS_GCODE_COLLECT_H

#include <math.h>
#include <string.h>

#include "gcode.h"

#define COLLECT_MAX 512

typedef struct {
  swarf_move moves[COLLECT_MAX];
  int n;
  int status;
  swarf_error error; /* valid when status != 0 */
  long lines;
  int ended;
} collected;

static inline int collect_move(const swarf_move *mv, void *user) {
  collected *c = user;
  if (c->n < COLLECT_MAX) c->moves[c->n++] = *mv;
  return 0;
}

static inline void collect_end(collected *c, swarf_gcode_parser *p, int status) {
  if (status == SWARF_OK) status = swarf_gcode_parser_finish(p);
  c->status = status;
  if (swarf_gcode_parser_error(p) != NULL) c->error = *swarf_gcode_parser_error(p);
  c->lines = swarf_gcode_parser_lines(p);
  c->ended = swarf_gcode_parser_ended(p);
  swarf_gcode_parser_free(p);
}

/* The whole text in one feed. */
static inline collected *run_text(const char *text, collected *c) {
  swarf_gcode_parser *p = NULL;
  swarf_gcode_parser_new("test.ngc", collect_move, c, &p);
  swarf_gcode_parser_set_fragment(p, 1, NULL); /* test texts need not end */
  memset(c, 0, sizeof *c);
  collect_end(c, p, swarf_gcode_parser_feed(p, text, strlen(text)));
  return c;
}

/* The text in pieces of `piece` bytes. */
static inline collected *run_pieces(const char *text, size_t len, size_t piece, collected *c) {
  swarf_gcode_parser *p = NULL;
  swarf_gcode_parser_new("test.ngc", collect_move, c, &p);
  swarf_gcode_parser_set_fragment(p, 1, NULL); /* test texts need not end */
  int status = SWARF_OK;
  memset(c, 0, sizeof *c);
  for (size_t i = 0; i < len && status == SWARF_OK; i += piece)
    status = swarf_gcode_parser_feed(p, text + i, len - i < piece ? len - i : piece);
  collect_end(c, p, status);
  return c;
}

/* p(a) = center + Rot(normal, a angle)(start - center) + a rise normal. */
static inline void arc_point(const swarf_move *mv, double a, double out[3]) {
  double v[3], n[3], c, s, dot, cross[3];
  for (int i = 0; i < 3; i++)
    v[i] = mv->start[i] - mv->center[i], n[i] = mv->normal[i];
  c = cos(a * mv->angle);
  s = sin(a * mv->angle);
  dot = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
  cross[0] = n[1] * v[2] - n[2] * v[1];
  cross[1] = n[2] * v[0] - n[0] * v[2];
  cross[2] = n[0] * v[1] - n[1] * v[0];
  for (int i = 0; i < 3; i++)
    out[i] = mv->center[i] + v[i] * c + cross[i] * s + n[i] * dot * (1 - c) + a * mv->rise * n[i];
}

#endif
