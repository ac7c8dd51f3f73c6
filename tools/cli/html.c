/* SPDX-License-Identifier: MPL-2.0 */
/* html.c -- `swarf simulate --html` (html.h): the moves collected, the mesh,
 * the data and the page written into memory. */
#define _GNU_SOURCE
#include "html.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <jansson.h>

#include "stock_output.h"

/* Assets, NUL-terminated (html_assets.c: embedded at build time). */
extern const char swarf_html_page_text[], swarf_html_three[], swarf_html_orbit[],
    swarf_html_viewer[];
extern const int swarf_html_built;

#define MESH_TRIANGLES 500000.0 /* the page's mesh at most about this many */
#define ARC_STEP 0.17           /* radians between the points drawn of an arc (~10 degrees) */

struct swarf_html {
  double *p; /* 6 a point: line, kind (0 rapid, 1 feed), x, y, z, feed */
  size_t n, cap;
  int oom;
};

int swarf_html_available(void) {
  return swarf_html_built;
}

swarf_html *swarf_html_new(void) {
  return swarf_html_built ? calloc(1, sizeof(swarf_html)) : NULL;
}

void swarf_html_free(swarf_html *h) {
  if (h != NULL) free(h->p);
  free(h);
}

static void point(swarf_html *h, long line, int feed, const double x[3], double f) {
  if (h->n == h->cap) {
    size_t cap = h->cap ? 2 * h->cap : 4096;
    double *p = realloc(h->p, cap * 6 * sizeof *p);
    if (p == NULL) {
      h->oom = 1;
      return;
    }
    h->p = p, h->cap = cap;
  }
  double *q = h->p + 6 * h->n++;
  q[0] = (double)line, q[1] = feed, q[2] = x[0], q[3] = x[1], q[4] = x[2], q[5] = f;
}

/* Rodrigues: v turned by t about the unit axis k. */
static void turn(const double k[3], double t, const double v[3], double out[3]) {
  const double c = cos(t), s = sin(t), kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
  const double x[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2],
                       k[0] * v[1] - k[1] * v[0]};
  for (int i = 0; i < 3; i++)
    out[i] = v[i] * c + x[i] * s + k[i] * kv * (1 - c);
}

void swarf_html_add_move(swarf_html *h, const swarf_move *m) {
  const int feed = m->kind != SWARF_MOVE_RAPID;
  if (h == NULL || h->oom || m->kind > SWARF_MOVE_ARC) return;
  if (h->n == 0) point(h, m->line, 0, m->start, 0.0);
  if (m->kind == SWARF_MOVE_ARC) {
    const int steps = (int)fmin(ceil(m->angle / ARC_STEP), 3600.0);
    const double r[3] = {m->start[0] - m->center[0], m->start[1] - m->center[1],
                         m->start[2] - m->center[2]};
    for (int j = 1; j < steps; j++) {
      const double t = m->angle * j / steps;
      double q[3];
      turn(m->normal, t, r, q);
      for (int k = 0; k < 3; k++)
        q[k] += m->center[k] + m->rise * (t / m->angle) * m->normal[k];
      point(h, m->line, 1, q, m->feed);
    }
  }
  point(h, m->line, feed, m->end, m->feed);
}

/* ---- the mesh ------------------------------------------------------------- */

/* The stock coarsened so that its mesh stays under MESH_TRIANGLES (about 10
 * triangles a surface voxel, marching tetrahedra: 236,596 for 24,207 on a
 * box with a slot; the band is 2 half-widths deep), written as a
 * PLY into a temporary file and read back. */
static swarf_status mesh_bytes(const swarf_html_page *pg, char **out, size_t *len,
                               swarf_error *err) {
  const swarf_stock *s = pg->stock;
  swarf_stock *coarse = NULL;
  const double surface = (double)swarf_stock_active_voxels(s) / (2.0 * swarf_stock_half_width(s));
  swarf_stock_output o;
  swarf_status st = SWARF_OK;
  const char *dir = getenv("TMPDIR");
  char buf[4096];
  int fd;
  if (dir == NULL || dir[0] == '\0' || strlen(dir) > 4000) dir = "/tmp";
  snprintf(buf, sizeof buf, "%s/swarf-html-XXXXXX.ply", dir); /* mkstemps fills the X's */
  if (10.0 * surface > MESH_TRIANGLES) {
    const double v = swarf_stock_voxel(s) * sqrt(10.0 * surface / MESH_TRIANGLES);
    if ((st = swarf_stock_resample(s, v, 3, &coarse, err)) != SWARF_OK) return st;
    s = coarse;
  }
  if ((fd = mkstemps(buf, 4)) < 0) {
    swarf_stock_free(coarse);
    return swarf_error_set(err, SWARF_ERR_IO, "--html: no temporary file for the mesh in %s", dir);
  }
  close(fd);
  memset(&o, 0, sizeof o);
  o.design = pg->design;
  o.tolerance = pg->tolerance;
  st = swarf_stock_write_mesh(s, buf, &o, NULL, err);
  swarf_stock_free(coarse);
  if (st == SWARF_OK) {
    FILE *f = fopen(buf, "rb");
    long n = -1;
    if (f != NULL && fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 &&
        fseek(f, 0, SEEK_SET) == 0 && (*out = malloc((size_t)n + 1)) != NULL &&
        fread(*out, 1, (size_t)n, f) == (size_t)n)
      *len = (size_t)n;
    else
      st = swarf_error_set(err, SWARF_ERR_IO, "--html: cannot read back the mesh");
    if (f != NULL) fclose(f);
  }
  unlink(buf);
  return st;
}

static void base64(FILE *f, const unsigned char *b, size_t n) {
  static const char a[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (size_t i = 0; i < n; i += 3) {
    const unsigned v = (unsigned)b[i] << 16 | (i + 1 < n ? (unsigned)b[i + 1] << 8 : 0) |
                       (i + 2 < n ? b[i + 2] : 0);
    char q[4] = {a[v >> 18 & 63], a[v >> 12 & 63], i + 1 < n ? a[v >> 6 & 63] : '=',
                 i + 2 < n ? a[v & 63] : '='};
    fwrite(q, 1, 4, f);
    if (i % 57 == 54) fputc('\n', f);
  }
}

/* ---- the data -------------------------------------------------------------- */

/* Text inside <script>: "</" would end it. */
static void script_text(FILE *f, const char *s) {
  for (; *s; s++) {
    if (s[0] == '<' && s[1] == '/')
      fputs("<\\", f);
    else
      fputc(*s, f);
  }
}

static void html_text(FILE *f, const char *s) {
  for (; *s; s++)
    if (*s == '<')
      fputs("&lt;", f);
    else if (*s == '>')
      fputs("&gt;", f);
    else if (*s == '&')
      fputs("&amp;", f);
    else if (*s == '"')
      fputs("&quot;", f);
    else
      fputc(*s, f);
}

static json_t *tools_json(const swarf_sim_config *cfg) {
  json_t *a = json_array();
  for (int i = 0; a != NULL && i < cfg->ntools; i++) {
    const swarf_sim_tool *t = &cfg->tools[i];
    json_t *h = json_array();
    for (int k = 0; h != NULL && k < t->nholder; k++)
      json_array_append_new(
          h, json_pack("[fff]", t->holder[k].d0, t->holder[k].d1, t->holder[k].height));
    json_array_append_new(
        a, json_pack("{si sf sf sf sf so}", "number", t->number, "diameter", t->cutter.diameter,
                     "length", t->cutter.length, "stickout", t->stickout, "shank",
                     t->shank > 0 ? t->shank : t->cutter.diameter, "holder", h ? h : json_null()));
  }
  return a;
}

static void data_json(FILE *f, const swarf_html *h, const swarf_html_page *pg) {
  json_t *head = json_pack(
      "{ss sf so so}", "program", pg->program, "voxel", swarf_stock_voxel(pg->stock), "tolerance",
      pg->design ? json_real(pg->tolerance) : json_null(), "tools", tools_json(pg->cfg));
  char *text = head ? json_dumps(head, JSON_COMPACT) : NULL;
  size_t n = text ? strlen(text) : 0;
  if (n > 1)
    fwrite(text, 1, n - 1, f), fputc(',', f); /* the object, still open */
  else
    fputc('{', f);
  free(text);
  json_decref(head);
  fputs("\"report\":", f);
  script_text(f, pg->report_json);
  fputs(",\"path\":[", f);
  for (size_t i = 0; i < h->n; i++) {
    const double *q = h->p + 6 * i;
    fprintf(f, "%s%ld,%d,%.4f,%.4f,%.4f,%.1f", i ? "," : "", (long)q[0], (int)q[1], q[2], q[3],
            q[4], q[5]);
  }
  fputs("]}", f);
}

static void summary(FILE *f, const swarf_html_page *pg) {
  const swarf_sim_report *r = pg->report;
  long alarms = 0;
  for (int k = 0; k < SWARF_ALARM_KINDS; k++)
    alarms += r->alarm_count[k];
  fprintf(f, "moves %ld (%ld rapid, %ld arcs)\nremoved %.1f mm&#179; of %.1f\n", r->moves,
          r->rapids, r->arcs, r->volume_before - r->volume_after, r->volume_before);
  fprintf(f, "machining time %.1f min, path %.0f mm\nalarms %ld\nvoxel %g mm", r->machining_s / 60,
          r->path_mm, alarms, swarf_stock_voxel(pg->stock));
}

static void legend(FILE *f, const swarf_html_page *pg) {
  const double t = pg->tolerance;
  if (pg->design == NULL) return;
  fprintf(f,
          "<h2>Deviation from the design (mm)</h2><div class=\"bar\" id=\"legend\"></div>"
          "<div class=\"scale\"><span style=\"left:0\">%.3g gouge</span>"
          "<span style=\"left:37.5%%\">%.3g</span><span style=\"left:50%%\">0</span>"
          "<span style=\"left:62.5%%\">%.3g</span><span style=\"left:100%%\">%.3g "
          "excess</span></div>",
          -4 * t, -t, t, 4 * t);
}

/* The page template's text from `from` up to the marker `@NAME@`; returns
 * the marker's name (in *name, up to 15 characters) and where text resumes. */
static const char *copy_to_marker(FILE *f, const char *from, char name[16]) {
  const char *at = strchr(from, '@'), *end;
  while (at != NULL && ((end = strchr(at + 1, '@')) == NULL || end - at - 1 > 15 || end == at + 1))
    at = strchr(at + 1, '@');
  if (at == NULL) {
    fputs(from, f);
    name[0] = '\0';
    return NULL;
  }
  fwrite(from, 1, (size_t)(at - from), f);
  memcpy(name, at + 1, (size_t)(end - at - 1));
  name[end - at - 1] = '\0';
  return end + 1;
}

swarf_status swarf_html_render(swarf_html *h, const swarf_html_page *pg, char **text, size_t *len,
                               swarf_error *err) {
  char *mesh = NULL, name[16];
  size_t nmesh = 0;
  swarf_status st;
  FILE *f;
  *text = NULL, *len = 0;
  if (h->oom) return swarf_error_set(err, SWARF_ERR_MEMORY, "--html: out of memory for the path");
  if ((st = mesh_bytes(pg, &mesh, &nmesh, err)) != SWARF_OK) return st;
  if ((f = open_memstream(text, len)) == NULL)
    return free(mesh), swarf_error_set(err, SWARF_ERR_MEMORY, "--html: out of memory");
  for (const char *at = swarf_html_page_text; at != NULL;) {
    at = copy_to_marker(f, at, name);
    if (!strcmp(name, "TITLE"))
      html_text(f, strrchr(pg->program, '/') ? strrchr(pg->program, '/') + 1 : pg->program);
    else if (!strcmp(name, "SUMMARY"))
      summary(f, pg);
    else if (!strcmp(name, "LEGEND"))
      legend(f, pg);
    else if (!strcmp(name, "THREE"))
      fputs(swarf_html_three, f);
    else if (!strcmp(name, "ORBIT"))
      fputs(swarf_html_orbit, f);
    else if (!strcmp(name, "VIEWER"))
      fputs(swarf_html_viewer, f);
    else if (!strcmp(name, "DATA"))
      data_json(f, h, pg);
    else if (!strcmp(name, "MESH"))
      base64(f, (const unsigned char *)mesh, nmesh);
  }
  free(mesh);
  if (fclose(f) != 0 || *text == NULL) {
    free(*text), *text = NULL;
    return swarf_error_set(err, SWARF_ERR_MEMORY, "--html: out of memory");
  }
  return SWARF_OK;
}
