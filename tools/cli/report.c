/* SPDX-License-Identifier: MPL-2.0 */
/* report.c -- the JSON report of a run (see report.h).
 *
 * Entries are kept per (line, tool) in an array with an open-addressing
 * index, so a line that runs many times (a loop, a subroutine) stays one
 * entry. The document is built with jansson at the end and written by the
 * stock module's output rules (stock_output.h), with the run's other
 * outputs: all or none.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <jansson.h>

#include "report.h"
#include "stock_output.h"

#ifndef SWARF_VERSION
#define SWARF_VERSION "unknown"
#endif

struct swarf_report {
  swarf_report_line *lines;
  size_t n, cap;
  size_t *slot; /* index + 1 into lines, 0 empty; size nslot (a power of two) */
  size_t nslot;
  swarf_alarm *alarms;
  size_t nalarms, alarm_cap;
  swarf_alarm *told, *gouges; /* swarf_report_alarms and _gouges */
  size_t ntold, ngouges;
  int oom;
  int sorted;
};

swarf_report *swarf_report_new(void) {
  return calloc(1, sizeof(swarf_report));
}

void swarf_report_free(swarf_report *r) {
  if (r == NULL) return;
  free(r->lines);
  free(r->slot);
  free(r->alarms);
  free(r->told);
  free(r->gouges);
  free(r);
}

static size_t hash(long line, int tool, size_t nslot) {
  unsigned long long h = (unsigned long long)line * 0x9E3779B97F4A7C15ull ^ (unsigned)tool;
  h ^= h >> 29;
  return (size_t)(h & (nslot - 1));
}

/* Rebuilds the index for nslot slots; 0 or -1 out of memory. */
static int reindex(swarf_report *r, size_t nslot) {
  size_t *slot = calloc(nslot, sizeof *slot);
  if (slot == NULL) return -1;
  free(r->slot);
  r->slot = slot;
  r->nslot = nslot;
  for (size_t i = 0; i < r->n; i++) {
    size_t h = hash(r->lines[i].line, r->lines[i].tool, nslot);
    while (slot[h] != 0)
      h = (h + 1) & (nslot - 1);
    slot[h] = i + 1;
  }
  return 0;
}

/* The entry of (line, tool), a new zero one if none; NULL out of memory. */
static swarf_report_line *entry(swarf_report *r, long line, int tool) {
  size_t h;
  if (2 * (r->n + 1) > r->nslot && reindex(r, r->nslot ? 2 * r->nslot : 1024) != 0) return NULL;
  for (h = hash(line, tool, r->nslot); r->slot[h] != 0; h = (h + 1) & (r->nslot - 1)) {
    swarf_report_line *e = &r->lines[r->slot[h] - 1];
    if (e->line == line && e->tool == tool) return e;
  }
  if (r->n == r->cap) {
    size_t cap = r->cap ? 2 * r->cap : 1024;
    swarf_report_line *grown = realloc(r->lines, cap * sizeof *grown);
    if (grown == NULL) return NULL;
    r->lines = grown;
    r->cap = cap;
  }
  r->slot[h] = r->n + 1;
  memset(&r->lines[r->n], 0, sizeof r->lines[r->n]);
  r->lines[r->n].line = line;
  r->lines[r->n].tool = tool;
  r->sorted = 0;
  return &r->lines[r->n++];
}

void swarf_report_add_line(swarf_report *r, const swarf_line_result *l) {
  swarf_report_line *e = entry(r, l->line, l->tool);
  if (e == NULL) {
    r->oom = 1;
    return;
  }
  e->moves += l->moves;
  e->time_s += l->time_s;
  e->path_mm += l->path_mm;
  e->removed_mm3 += l->removed; /* NaN stays NaN: not measured */
}

void swarf_report_add_alarm(swarf_report *r, const swarf_alarm *a) {
  if (r->nalarms == r->alarm_cap) {
    size_t cap = r->alarm_cap ? 2 * r->alarm_cap : 64;
    swarf_alarm *grown = realloc(r->alarms, cap * sizeof *grown);
    if (grown == NULL) {
      r->oom = 1;
      return;
    }
    r->alarms = grown;
    r->alarm_cap = cap;
  }
  r->alarms[r->nalarms++] = *a;
}

/* Gouge indices by line, then by arrival. */
static const swarf_alarm *sort_base;
static int gouge_order(const void *a, const void *b) {
  const size_t i = *(const size_t *)a, j = *(const size_t *)b;
  if (sort_base[i].line != sort_base[j].line) return sort_base[i].line < sort_base[j].line ? -1 : 1;
  return (i > j) - (i < j);
}

/* keep[i]: 1 if alarm i is told; a line's first gouge takes its deepest depth and place. */
static int merge_gouges(swarf_report *r, char *keep, swarf_alarm *merged) {
  size_t *g = malloc((r->nalarms ? r->nalarms : 1) * sizeof *g), ng = 0;
  if (g == NULL) return -1;
  for (size_t i = 0; i < r->nalarms; i++) {
    merged[i] = r->alarms[i];
    keep[i] = 1;
    if (r->alarms[i].kind == SWARF_ALARM_GOUGE) g[ng++] = i;
  }
  sort_base = r->alarms;
  qsort(g, ng, sizeof *g, gouge_order);
  for (size_t a = 0, b; a < ng; a = b) {
    swarf_alarm *first = &merged[g[a]];
    for (b = a + 1; b < ng && r->alarms[g[b]].line == first->line; b++) {
      const swarf_alarm *x = &r->alarms[g[b]];
      keep[g[b]] = 0;
      if (x->depth > first->depth) {
        first->depth = x->depth;
        memcpy(first->at, x->at, sizeof first->at);
      }
    }
  }
  free(g);
  return 0;
}

const swarf_alarm *swarf_report_alarms(swarf_report *r, size_t *n) {
  swarf_alarm *merged = malloc((r->nalarms ? r->nalarms : 1) * sizeof *merged);
  char *keep = malloc(r->nalarms ? r->nalarms : 1);
  size_t k = 0;
  if (merged == NULL || keep == NULL || merge_gouges(r, keep, merged) != 0) {
    free(merged);
    free(keep);
    r->oom = 1;
    *n = 0;
    return NULL;
  }
  for (size_t i = 0; i < r->nalarms; i++)
    if (keep[i]) merged[k++] = merged[i];
  free(keep);
  free(r->told);
  r->told = merged;
  r->ntold = *n = k;
  return merged;
}

static int gouge_by_line(const void *a, const void *b) {
  const swarf_alarm *x = a, *y = b;
  return (x->line > y->line) - (x->line < y->line);
}

const swarf_alarm *swarf_report_gouges(swarf_report *r, size_t *n) {
  size_t nt, k = 0;
  const swarf_alarm *t = swarf_report_alarms(r, &nt);
  swarf_alarm *g = malloc((nt ? nt : 1) * sizeof *g);
  *n = 0;
  if (g == NULL) return r->oom = 1, NULL;
  for (size_t i = 0; i < nt; i++)
    if (t[i].kind == SWARF_ALARM_GOUGE) g[k++] = t[i];
  qsort(g, k, sizeof *g, gouge_by_line); /* one a line: no ties */
  free(r->gouges);
  r->gouges = g;
  r->ngouges = *n = k;
  return g;
}

static int by_line(const void *a, const void *b) {
  const swarf_report_line *x = a, *y = b;
  if (x->line != y->line) return x->line < y->line ? -1 : 1;
  return (x->tool > y->tool) - (x->tool < y->tool);
}

const swarf_report_line *swarf_report_lines(swarf_report *r, size_t *n) {
  if (!r->sorted && r->n > 0) {
    qsort(r->lines, r->n, sizeof *r->lines, by_line);
    if (reindex(r, r->nslot) != 0) r->oom = 1;
    r->sorted = 1;
  }
  *n = r->n;
  return r->lines;
}

long swarf_report_peak_mrr(swarf_report *r, double *mm3_per_min, int *tool) {
  size_t n;
  const swarf_report_line *l = swarf_report_lines(r, &n);
  long best = 0;
  double rate = 0;
  for (size_t i = 0; i < n; i++) {
    double v = l[i].time_s > 0 && l[i].removed_mm3 > 0 ? l[i].removed_mm3 / l[i].time_s * 60 : 0;
    if (v > rate) rate = v, best = l[i].line, *tool = l[i].tool;
  }
  *mm3_per_min = rate;
  return best;
}

/* ---- the document ------------------------------------------------------ */

/* A number, or null when it is not finite (JSON has no NaN). */
static json_t *num(double v) {
  return isfinite(v) ? json_real(v) : json_null();
}

static json_t *point(const double p[3]) {
  if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) return json_null();
  return json_pack("[fff]", p[0], p[1], p[2]);
}

static const char *alarm_kind(swarf_alarm_kind k) {
  static const char *names[] = {"rapid", "shank", "holder", "fixture", "gouge", "no_tool"};
  return (unsigned)k < SWARF_ALARM_KINDS ? names[k] : "unknown";
}

static json_t *lines_json(swarf_report *r) {
  size_t n;
  const swarf_report_line *l = swarf_report_lines(r, &n);
  json_t *a = json_array();
  for (size_t i = 0; i < n; i++)
    json_array_append_new(a, json_pack("{sI sI sI so so so}", "line", (json_int_t)l[i].line, "tool",
                                       (json_int_t)l[i].tool, "moves", (json_int_t)l[i].moves,
                                       "removed_mm3", num(l[i].removed_mm3), "time_s",
                                       num(l[i].time_s), "path_mm", num(l[i].path_mm)));
  return a;
}

/* Per tool, in order of first use (the lines are sorted by line). */
static json_t *tools_json(swarf_report *r) {
  size_t n, nt = 0;
  const swarf_report_line *l = swarf_report_lines(r, &n);
  swarf_report_line *t = calloc(n ? n : 1, sizeof *t);
  json_t *a = json_array();
  if (t == NULL) return r->oom = 1, a;
  for (size_t i = 0; i < n; i++) {
    size_t k = 0;
    while (k < nt && t[k].tool != l[i].tool)
      k++;
    if (k == nt) t[nt++].tool = l[i].tool;
    t[k].moves += l[i].moves;
    t[k].time_s += l[i].time_s;
    t[k].path_mm += l[i].path_mm;
    t[k].removed_mm3 += l[i].removed_mm3;
  }
  for (size_t k = 0; k < nt; k++)
    json_array_append_new(a, json_pack("{sI sI so so so}", "tool", (json_int_t)t[k].tool, "moves",
                                       (json_int_t)t[k].moves, "removed_mm3", num(t[k].removed_mm3),
                                       "time_s", num(t[k].time_s), "path_mm", num(t[k].path_mm)));
  free(t);
  return a;
}

static json_t *alarms_json(swarf_report *r) {
  json_t *a = json_array();
  size_t n;
  const swarf_alarm *told = swarf_report_alarms(r, &n);
  for (size_t i = 0; i < n; i++) {
    const swarf_alarm *al = &told[i];
    json_t *o = json_pack("{ss sI si si so so}", "kind", alarm_kind(al->kind), "line",
                          (json_int_t)al->line, "column", al->column, "tool", al->tool, "depth_mm",
                          num(al->depth), "at", point(al->at));
    if (al->kind == SWARF_ALARM_FIXTURE) json_object_set_new(o, "fixture", json_integer(al->index));
    json_array_append_new(a, o);
  }
  return a;
}

static json_t *design_json(const swarf_stock_deviation *d) {
  return json_pack("{so so so so so so so so so so so so}", "tolerance_mm", num(d->tolerance),
                   "reach_mm", num(d->reach), "design_mm3", num(d->design_volume), "gouge_mm3",
                   num(d->gouge_volume), "gouge_depth_mm", num(d->gouge_depth), "gouge_at",
                   point(d->gouge_at), "gouge_clamped", json_boolean(d->gouge_clamped),
                   "excess_mm3", num(d->excess_volume), "excess_mm", num(d->excess_height),
                   "excess_at", point(d->excess_at), "excess_clamped",
                   json_boolean(d->excess_clamped), "missing_mm3", num(d->missing_volume));
}

static json_t *summary_json(swarf_report *r, const swarf_sim_report *f) {
  static const char *kinds[] = {"rapid", "shank", "holder", "fixture", "gouge", "no_tool"};
  json_t *s, *counts = json_object();
  double rate = 0;
  int tool = 0;
  long peak = swarf_report_peak_mrr(r, &rate, &tool);
  for (int k = 0; k < SWARF_ALARM_KINDS; k++)
    json_object_set_new(counts, kinds[k], json_integer(f->alarm_count[k]));
  s = json_pack("{sI sI sI sI sI sI so so so so so so so sI so}", "lines", (json_int_t)f->lines,
                "moves", (json_int_t)f->moves, "cutting_moves", (json_int_t)f->cutting_moves,
                "rapids", (json_int_t)f->rapids, "arcs", (json_int_t)f->arcs, "tool_changes",
                (json_int_t)f->tool_changes, "path_mm", num(f->path_mm), "machining_s",
                num(f->machining_s), "volume_before_mm3", num(f->volume_before), "volume_after_mm3",
                num(f->volume_after), "removed_mm3", num(f->volume_before - f->volume_after),
                "simulation_s", num(f->seconds), "start",
                json_pack("{so sb}", "at", point(f->start), "default", f->start_default), "alarms",
                (json_int_t)f->alarms, "alarm_counts", counts);
  json_object_set_new(s, "peak_mrr",
                      peak > 0 ? json_pack("{sI si sf}", "line", (json_int_t)peak, "tool", tool,
                                           "mm3_per_min", rate)
                               : json_null());
  json_object_set_new(s, "units_line",
                      f->units_line > 0 ? json_integer(f->units_line) : json_null());
  json_object_set_new(s, "units_warning_line",
                      f->units_missing_line > 0 ? json_integer(f->units_missing_line)
                                                : json_null());
  json_object_set_new(s, "design", f->has_deviation ? design_json(&f->deviation) : json_null());
  return s;
}

/* A file name or spec as a JSON string. JSON holds UTF-8 only, and a name
 * is bytes: one that is not UTF-8 (a Latin-1 "caf\xe9.ngc") is read as
 * Latin-1, each byte its code point, so the report says "café" instead of
 * failing (jansson refuses invalid UTF-8, which read as out of memory). */
static json_t *name_string(const char *s) {
  json_t *j = json_string(s);
  if (j != NULL) return j;
  size_t n = strlen(s), k = 0;
  char *u = malloc(2 * n + 1);
  if (u == NULL) return NULL;
  for (const unsigned char *p = (const unsigned char *)s; *p; p++)
    if (*p < 0x80) {
      u[k++] = (char)*p;
    } else {
      u[k++] = (char)(0xc0 | (*p >> 6));
      u[k++] = (char)(0x80 | (*p & 0x3f));
    }
  u[k] = '\0';
  j = json_string(u);
  free(u);
  return j;
}

static json_t *str_or_null(const char *s) {
  return s != NULL ? name_string(s) : json_null();
}

static json_t *inputs_json(const swarf_report_inputs *in) {
  json_t *tools = json_array();
  for (int i = 0; i < in->ntools; i++)
    json_array_append_new(tools, name_string(in->tools[i]));
  return json_pack(
      "{so so so so so so so so so so so ss}", "program", str_or_null(in->program), "stock",
      str_or_null(in->stock), "tools", tools, "voxel", num(in->voxel), "machine",
      str_or_null(in->machine ? in->machine : "xyz"), "offsets", str_or_null(in->offsets), "g54",
      in->g54 ? point(in->g54) : json_null(), "start", in->start ? point(in->start) : json_null(),
      "units", str_or_null(in->units), "design", str_or_null(in->design), "tolerance",
      in->design && in->tolerance > 0 ? num(in->tolerance) : json_null(), "version", SWARF_VERSION);
}

/* Writes doc to path by the stock module's output rules (stock_output.h):
 * an unnamed file in the same folder, synced, named at the end, or held
 * with the run's other outputs until their commit (all or none). */
static swarf_status write_atomic(const json_t *doc, const char *path, swarf_error *err) {
  char *text = json_dumps(doc, JSON_INDENT(1) | JSON_REAL_PRECISION(12));
  swarf_status s;
  size_t n;
  if (text == NULL) return swarf_error_set(err, SWARF_ERR_MEMORY, "out of memory in the report");
  n = strlen(text);
  text[n] = '\n'; /* json_dumps leaves room for its NUL: the file ends with a newline */
  s = swarf_stock_output_write(path, text, n + 1, err);
  free(text);
  if (s != SWARF_OK) {
    char why[sizeof err->message];
    snprintf(why, sizeof why, "%s", err->message);
    swarf_error_at(err, path, 0, 0, "--report");
    return swarf_error_set(err, s, "cannot write the report: %s", why);
  }
  return SWARF_OK;
}

/* The document, or NULL (out of memory: err says so). */
static json_t *document(swarf_report *r, const swarf_sim_report *final,
                        const swarf_report_inputs *in, swarf_error *err) {
  json_t *doc = NULL;
  if (!r->oom)
    doc = json_pack("{si so so so so so}", "swarf_report", 1, "summary", summary_json(r, final),
                    "lines", lines_json(r), "tools", tools_json(r), "alarms", alarms_json(r),
                    "inputs", inputs_json(in));
  if (doc == NULL || r->oom) {
    json_decref(doc);
    swarf_error_set(err, SWARF_ERR_MEMORY, "out of memory in the report");
    return NULL;
  }
  return doc;
}

swarf_status swarf_report_write(swarf_report *r, const swarf_sim_report *final,
                                const swarf_report_inputs *in, const char *path, swarf_error *err) {
  json_t *doc = document(r, final, in, err);
  swarf_status s;
  if (doc == NULL) return SWARF_ERR_MEMORY;
  s = write_atomic(doc, path, err);
  json_decref(doc);
  return s;
}

char *swarf_report_text(swarf_report *r, const swarf_sim_report *final,
                        const swarf_report_inputs *in, swarf_error *err) {
  json_t *doc = document(r, final, in, err);
  char *text = doc != NULL ? json_dumps(doc, JSON_COMPACT | JSON_REAL_PRECISION(10)) : NULL;
  if (doc != NULL && text == NULL)
    swarf_error_set(err, SWARF_ERR_MEMORY, "out of memory in the report");
  json_decref(doc);
  return text;
}
