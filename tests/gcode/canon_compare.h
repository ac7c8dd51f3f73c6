/* SPDX-License-Identifier: MPL-2.0 */
/* canon_compare.h -- helpers of the gcode tests (header only): collect the
 * canonical calls swarf prints (its canon listener) and compare the motion
 * calls (STRAIGHT_TRAVERSE, STRAIGHT_FEED, ARC_FEED, DWELL, STRAIGHT_PROBE,
 * NURBS_FEED) or the MESSAGE
 * numbers of two canon texts in rs274's format, numerically, in order.
 * The texts are owned by the caller; canon_calls owns its array.
 */
#ifndef SWARF_TESTS_GCODE_CANON_COMPARE_H
#define SWARF_TESTS_GCODE_CANON_COMPARE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gcode.h"

typedef struct {
  char *text;
  size_t len, cap;
} canon_text;

static inline void canon_collect(const char *call, void *user) {
  canon_text *t = user;
  size_t n = strlen(call);
  if (t->len + n + 2 > t->cap) {
    t->cap = (t->len + n + 2) * 2;
    t->text = realloc(t->text, t->cap);
  }
  memcpy(t->text + t->len, call, n);
  t->len += n;
  t->text[t->len++] = '\n';
  t->text[t->len] = '\0';
}

typedef struct {
  int kind; /* index into the names below; 4: MESSAGE */
  double v[9];
  int nv;
  long text_line;
} canon_call1;

typedef struct {
  canon_call1 *v;
  size_t n, cap;
} canon_calls;

/* `needle` within the first n bytes of s, or NULL. */
static inline const char *canon_find(const char *s, size_t n, const char *needle) {
  size_t k = strlen(needle);
  for (size_t i = 0; i + k <= n; i++)
    if (s[i] == needle[0] && memcmp(s + i, needle, k) == 0) return s + i;
  return NULL;
}

/* The calls of `text` (motions, or only MESSAGE numbers when `messages`). */
static inline void canon_extract(const char *text, int messages, canon_calls *out) {
  /* kinds 0-3 and 5-6 (4 is MESSAGE): G38.x prints STRAIGHT_PROBE, G5 and
   * G5.1 NURBS_FEED(4, ...) / (3, ...) (only the order is compared). */
  static const char *names[] = {"STRAIGHT_TRAVERSE(", "STRAIGHT_FEED(", "ARC_FEED(", "DWELL(", NULL,
                                "STRAIGHT_PROBE(",    "NURBS_FEED("};
  long line = 0;
  memset(out, 0, sizeof *out);
  for (const char *s = text; s && *s; s = strchr(s, '\n'), s = s ? s + 1 : NULL) {
    canon_call1 c = {-1, {0}, 0, ++line};
    const char *open = NULL, *p;
    const char *eol = strchr(s, '\n');
    size_t n = eol ? (size_t)(eol - s) : strlen(s);
    if (messages) {
      p = canon_find(s, n, "MESSAGE(\"");
      if (p == NULL) continue;
      c.kind = 4;
      for (p += 9; p < s + n && c.nv < 9; p++) {
        char *end;
        if (!(*p == '-' || (*p >= '0' && *p <= '9'))) continue;
        c.v[c.nv] = strtod(p, &end);
        if (end > p && memchr(p, '.', (size_t)(end - p))) c.nv++;
        p = end - 1;
      }
    } else {
      for (int k = 0; k < 7 && open == NULL; k++) {
        if (names[k] == NULL) continue;
        p = canon_find(s, n, names[k]);
        if (p != NULL) c.kind = k, open = p + strlen(names[k]);
      }
      if (open == NULL) continue;
      for (p = open; c.nv < 9;) {
        char *end;
        c.v[c.nv] = strtod(p, &end);
        if (end == p) break;
        c.nv++;
        p = end;
        while (*p == ' ' || *p == ',')
          p++;
      }
    }
    if (out->n == out->cap) {
      out->cap = out->cap ? 2 * out->cap : 1024;
      out->v = realloc(out->v, out->cap * sizeof *out->v);
    }
    out->v[out->n++] = c;
  }
}

/* 0 if equal within `tol`; else 1 and a description in `why`. */
static inline int canon_differ(const canon_calls *a, const canon_calls *b, double tol, char *why,
                               size_t cap) {
  size_t n = a->n < b->n ? a->n : b->n;
  for (size_t i = 0; i < n; i++) {
    const canon_call1 *x = &a->v[i], *y = &b->v[i];
    int same = x->kind == y->kind && x->nv == y->nv;
    for (int k = 0; same && k < x->nv; k++)
      same = fabs(x->v[k] - y->v[k]) <= tol;
    if (!same) {
      snprintf(why, cap, "call %zu differs (swarf canon line %ld, expected line %ld)", i + 1,
               x->text_line, y->text_line);
      return 1;
    }
  }
  if (a->n != b->n) {
    snprintf(why, cap, "%zu calls, expected %zu", a->n, b->n);
    return 1;
  }
  return 0;
}

/* Runs `text` through a parser with the canon listener; `tools` may be NULL. */
static inline int canon_run(const char *name, const char *text, size_t len, const char *tools,
                            canon_text *out, swarf_error *err) {
  swarf_gcode_parser *p = NULL;
  swarf_gcode_parser_new(name, NULL, NULL, &p);
  int status = SWARF_OK;
  memset(out, 0, sizeof *out);
  memset(err, 0, sizeof *err);
  swarf_gcode_parser_set_canon(p, canon_collect, out);
  if (tools != NULL) status = swarf_gcode_parser_load_tools(p, tools, err);
  if (status == SWARF_OK) status = swarf_gcode_parser_feed(p, text, len);
  if (status == SWARF_OK) status = swarf_gcode_parser_finish(p);
  if (status != SWARF_OK && swarf_gcode_parser_error(p) != NULL)
    *err = *swarf_gcode_parser_error(p);
  swarf_gcode_parser_free(p);
  if (out->text == NULL) canon_collect("", out);
  return status;
}

/* The whole file, NUL-terminated, or NULL. */
static inline char *canon_slurp(const char *path, size_t *len) {
  FILE *in = fopen(path, "rb");
  char *buf;
  long n;
  if (in == NULL) return NULL;
  fseek(in, 0, SEEK_END);
  n = ftell(in);
  fseek(in, 0, SEEK_SET);
  buf = malloc((size_t)n + 1);
  if (buf != NULL && fread(buf, 1, (size_t)n, in) != (size_t)n) {
    free(buf);
    buf = NULL;
  }
  fclose(in);
  if (buf != NULL) buf[n] = '\0', *len = (size_t)n;
  return buf;
}

#endif
