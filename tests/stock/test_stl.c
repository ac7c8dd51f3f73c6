/* SPDX-License-Identifier: MPL-2.0 */
/* test_stl.c -- binary STL of the zero isosurface: closed, outward, right volume.
 *
 * Truth: a closed oriented surface has every undirected edge in exactly two
 * triangles, once in each direction; its enclosed volume by the divergence
 * theorem, sum of a . (b x c) / 6 over triangles, equals the box volume (1 %
 * tolerance: the mesh is the voxel-sampled surface) or, for a stock with a
 * ball removed, the stock's own volume (1 %). Outward normals: the stored
 * normal agrees with the vertex order and the level set increases along it
 * (sampled one voxel on each side of the triangle's centroid).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "shapes.h"

typedef struct {
  float n[3], v[3][3];
} tri;

static tri *read_stl(const char *path, uint32_t *count) {
  FILE *f = fopen(path, "rb");
  unsigned char head[84];
  tri *t = NULL;
  *count = 0;
  if (!f) return NULL;
  if (fread(head, 1, 84, f) == 84) {
    *count = head[80] | head[81] << 8 | head[82] << 16 | (uint32_t)head[83] << 24;
    t = calloc(*count ? *count : 1, sizeof *t);
    for (uint32_t i = 0; t && i < *count; i++) {
      unsigned char rec[50];
      if (fread(rec, 1, 50, f) != 50) {
        free(t);
        t = NULL;
        break;
      }
      memcpy(t[i].n, rec, 12); /* little-endian host */
      memcpy(t[i].v, rec + 12, 36);
    }
    if (t && fgetc(f) != EOF) CHECK(0, "%s: bytes after the last triangle", path);
  }
  fclose(f);
  return t;
}

/* Directed edges as vertex-position pairs, sorted to count matches. */
typedef struct {
  float a[3], b[3];
} edge;

static int edge_cmp(const void *x, const void *y) {
  return memcmp(x, y, sizeof(edge));
}

static void check_closed(const tri *t, uint32_t n, const char *what) {
  edge *e = malloc(3 * (size_t)n * sizeof *e), key;
  long unmatched = 0, repeated = 0;
  memset(e, 0, 3 * (size_t)n * sizeof *e);
  for (uint32_t i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) {
      memcpy(e[3 * i + k].a, t[i].v[k], 12);
      memcpy(e[3 * i + k].b, t[i].v[(k + 1) % 3], 12);
    }
  qsort(e, 3 * (size_t)n, sizeof *e, edge_cmp);
  for (size_t i = 0; i < 3 * (size_t)n; i++) {
    if (i + 1 < 3 * (size_t)n && edge_cmp(&e[i], &e[i + 1]) == 0) repeated++;
    memset(&key, 0, sizeof key);
    memcpy(key.a, e[i].b, 12);
    memcpy(key.b, e[i].a, 12);
    if (!bsearch(&key, e, 3 * (size_t)n, sizeof *e, edge_cmp)) unmatched++;
  }
  printf("%s: %u triangles, %ld edges without a reversed twin, %ld repeated\n", what, n, unmatched,
         repeated);
  CHECK(unmatched == 0, "%s: closed (every edge has a reversed twin): %ld open", what, unmatched);
  CHECK(repeated == 0, "%s: every directed edge once (oriented, manifold): %ld", what, repeated);
  free(e);
}

static double signed_volume(const tri *t, uint32_t n) {
  double v = 0.0;
  for (uint32_t i = 0; i < n; i++) {
    const float *a = t[i].v[0], *b = t[i].v[1], *c = t[i].v[2];
    v += a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) -
         a[1] * ((double)b[0] * c[2] - (double)b[2] * c[0]) +
         a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
  }
  return v / 6.0;
}

static void check_normals(const swarf_stock *s, const tri *t, uint32_t n, const char *what) {
  long bad_stored = 0, inward = 0;
  const double h = swarf_stock_voxel(s);
  for (uint32_t i = 0; i < n; i++) {
    double u[3], w[3], m[3], c[3], len;
    for (int k = 0; k < 3; k++) {
      u[k] = t[i].v[1][k] - t[i].v[0][k];
      w[k] = t[i].v[2][k] - t[i].v[0][k];
      c[k] = (t[i].v[0][k] + t[i].v[1][k] + t[i].v[2][k]) / 3.0;
    }
    m[0] = u[1] * w[2] - u[2] * w[1];
    m[1] = u[2] * w[0] - u[0] * w[2];
    m[2] = u[0] * w[1] - u[1] * w[0];
    len = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    if (len == 0.0) continue;
    double dot = (m[0] * t[i].n[0] + m[1] * t[i].n[1] + m[2] * t[i].n[2]) / len;
    if (dot < 0.999) bad_stored++;
    double out =
        swarf_stock_sample(s, c[0] + h * m[0] / len, c[1] + h * m[1] / len, c[2] + h * m[2] / len);
    double in =
        swarf_stock_sample(s, c[0] - h * m[0] / len, c[1] - h * m[1] / len, c[2] - h * m[2] / len);
    if (!(out > in)) inward++;
  }
  CHECK(bad_stored == 0, "%s: %ld stored normals disagree with the vertex order", what, bad_stored);
  CHECK(inward == 0, "%s: %ld triangles face into the material", what, inward);
}

static void mesh_case(const swarf_stock *s, const char *path, double want, const char *what) {
  swarf_error err = {0};
  size_t ntri = 0;
  uint32_t n;
  CHECK(swarf_stock_write_stl(s, path, &ntri, &err) == 0, "%s: write: %s", what, err.message);
  tri *t = read_stl(path, &n);
  CHECK(t != NULL && n == ntri && n > 0, "%s: read back %u triangles (%zu written)", what, n, ntri);
  if (!t) return;
  check_closed(t, n, what);
  double v = signed_volume(t, n);
  printf("%s: mesh volume %.4f mm^3 vs %.4f (%+.3f%%)\n", what, v, want, 100.0 * (v - want) / want);
  CHECK_NEAR(v, want, 0.01 * want, what);
  check_normals(s, t, n, what);
  free(t);
}

int main(void) {
  swarf_error err = {0};
  const box_shape box = {{-1.0, 0.5, -3.0}, {5.0, 4.5, 0.0}};
  swarf_stock *s = NULL;
  swarf_stock_new_box(box.lo, box.hi, 0.1, 3, &s, &err);
  CHECK(s != NULL, "new_box: %s", err.message);
  if (!s) return check_done();
  mesh_case(s, "stock_stl_box.stl", 6.0 * 4.0 * 3.0, "box");
  capsule_shape ball = {{2.0, 2.5, 0.0}, {2.0, 2.5, 0.0}, 1.5};
  swarf_stock_cut cut = capsule_cut(&ball);
  CHECK(swarf_stock_remove_batch(s, &cut, 1, &err) == 0, "remove: %s", err.message);
  mesh_case(s, "stock_stl_pocket.stl", swarf_stock_volume(s), "box with a ball pocket");
  CHECK(swarf_stock_write_stl(s, "stock_stl_no_dir/x.stl", NULL, &err) == SWARF_ERR_IO,
        "missing directory refused: %s", err.message);
  CHECK(swarf_stock_write_stl(NULL, "x.stl", NULL, &err) == SWARF_ERR_ARG, "NULL stock");
  swarf_stock_free(s);
  return check_done();
}
