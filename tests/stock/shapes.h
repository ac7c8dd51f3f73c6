/* SPDX-License-Identifier: MPL-2.0 */
/* shapes.h -- analytic shapes for the stock tests and benchmark (header only).
 *
 * Exact signed distances (mm, < 0 inside) of an axis-aligned box, a ball and a
 * capsule (a ball swept along a segment), with the callback shape of
 * swarf_stock_sdf_fn, and helpers to compare two stocks voxel by voxel.
 */
#ifndef SWARF_TESTS_STOCK_SHAPES_H
#define SWARF_TESTS_STOCK_SHAPES_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stock.h"

typedef struct {
  double lo[3], hi[3];
} box_shape;

typedef struct {
  double a[3], b[3]; /* segment ends (a == b: a ball) */
  double r;
} capsule_shape;

static inline double box_sdf(const box_shape *b, const double p[3]) {
  double out2 = 0.0, in = -INFINITY;
  for (int k = 0; k < 3; k++) {
    double q = fmax(b->lo[k] - p[k], p[k] - b->hi[k]);
    if (q > 0.0) out2 += q * q;
    in = fmax(in, q);
  }
  return out2 > 0.0 ? sqrt(out2) : in;
}

static inline double capsule_dist(const capsule_shape *c, double x, double y, double z) {
  double ab[3], ap[3] = {x - c->a[0], y - c->a[1], z - c->a[2]}, t = 0.0, len2 = 0.0, d2 = 0.0;
  for (int k = 0; k < 3; k++) {
    ab[k] = c->b[k] - c->a[k];
    len2 += ab[k] * ab[k];
    t += ab[k] * ap[k];
  }
  t = len2 > 0.0 ? fmin(fmax(t / len2, 0.0), 1.0) : 0.0;
  for (int k = 0; k < 3; k++) {
    double d = ap[k] - t * ab[k];
    d2 += d * d;
  }
  return sqrt(d2) - c->r;
}

static inline double capsule_sdf_cb(const void *ctx, double x, double y, double z) {
  return capsule_dist((const capsule_shape *)ctx, x, y, z);
}

static inline void capsule_bounds(const capsule_shape *c, double lo[3], double hi[3]) {
  for (int k = 0; k < 3; k++) {
    lo[k] = fmin(c->a[k], c->b[k]) - c->r;
    hi[k] = fmax(c->a[k], c->b[k]) + c->r;
  }
}

static inline swarf_stock_cut capsule_cut(const capsule_shape *c) {
  swarf_stock_cut cut = {0};
  capsule_bounds(c, cut.lo, cut.hi);
  cut.sdf = capsule_sdf_cb;
  cut.ctx = c;
  return cut;
}

/* All active voxels of a stock: centres and values, in visiting order. */
typedef struct {
  double *xyz;
  float *value;
  size_t n, cap;
} voxel_list;

static inline void voxel_list_add(void *ctx, const double centre[3], float value) {
  voxel_list *l = (voxel_list *)ctx;
  if (l->n == l->cap) {
    l->cap = l->cap ? 2 * l->cap : 4096;
    l->xyz = (double *)realloc(l->xyz, 3 * l->cap * sizeof(double));
    l->value = (float *)realloc(l->value, l->cap * sizeof(float));
  }
  memcpy(l->xyz + 3 * l->n, centre, 3 * sizeof(double));
  l->value[l->n++] = value;
}

static inline void voxel_list_free(voxel_list *l) {
  free(l->xyz);
  free(l->value);
  memset(l, 0, sizeof *l);
}

/* Number of differences between the active voxels of a and b (positions and
 * bit-exact values); 0 means identical. */
static inline size_t stock_differences(const swarf_stock *a, const swarf_stock *b) {
  voxel_list la = {0}, lb = {0};
  size_t diff = 0;
  swarf_stock_visit_active(a, voxel_list_add, &la);
  swarf_stock_visit_active(b, voxel_list_add, &lb);
  if (la.n != lb.n) diff = la.n > lb.n ? la.n - lb.n : lb.n - la.n;
  for (size_t i = 0; i < la.n; i++) {
    double c[3];
    float v =
        (float)swarf_stock_voxel_value(b, la.xyz[3 * i], la.xyz[3 * i + 1], la.xyz[3 * i + 2], c);
    if (memcmp(&v, &la.value[i], sizeof v) != 0) diff++;
  }
  voxel_list_free(&la);
  voxel_list_free(&lb);
  return diff;
}

#endif
