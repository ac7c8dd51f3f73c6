/* SPDX-License-Identifier: MPL-2.0 */
/* test_slab_build.c -- a box or cylinder stock built in one part of its
 * index space (swarf_stock_new_box_slab, swarf_stock_new_cylinder_slab)
 * against the whole build.
 *
 * Truth: the whole build (swarf_stock_new_box / _cylinder), itself checked
 * against the analytic distance in test_box.c. Each part must hold exactly
 * (float equality) the whole build's value at every voxel of its blocks and
 * the same active voxels; the parts of a partition, loaded into a whole
 * build cropped to the first part (as the processes' parts are gathered),
 * must give the whole build back: the same active voxels and values, the
 * same volume. A region without blocks builds nothing but has the whole
 * stock's index box.
 */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "stock.h"

static const double voxel = 0.1;
static const int hw = 3;

typedef struct {
  const swarf_stock *whole;
  int lo[3], hi[3]; /* block origins of the region */
  long n, outside, differ;
} visit_ctx;

static void index_of(const double c[3], int ijk[3]) {
  for (int k = 0; k < 3; k++)
    ijk[k] = (int)lround(c[k] / voxel);
}

static int in_blocks(const visit_ctx *v, const int ijk[3]) {
  for (int k = 0; k < 3; k++)
    if ((ijk[k] & ~7) < v->lo[k] || (ijk[k] & ~7) > v->hi[k]) return 0;
  return 1;
}

static void visit(void *user, const double c[3], float value) {
  visit_ctx *v = user;
  int ijk[3];
  index_of(c, ijk);
  v->n++;
  if (v->lo[0] <= v->hi[0] && !in_blocks(v, ijk)) v->outside++;
  if ((float)swarf_stock_voxel_value(v->whole, c[0], c[1], c[2], NULL) != value) v->differ++;
}

/* Values at every voxel of the index box (stride 2) whose block is in the region. */
static long differ_in(const swarf_stock *a, const swarf_stock *w, const visit_ctx *v) {
  int lo[3], hi[3];
  long bad = 0;
  swarf_stock_index_box(w, lo, hi);
  for (int i = lo[0]; i <= hi[0]; i += 2)
    for (int j = lo[1]; j <= hi[1]; j += 2)
      for (int k = lo[2]; k <= hi[2]; k += 2) {
        const int ijk[3] = {i, j, k};
        if (v != NULL && !in_blocks(v, ijk)) continue;
        bad += swarf_stock_voxel_value(a, i * voxel, j * voxel, k * voxel, NULL) !=
               swarf_stock_voxel_value(w, i * voxel, j * voxel, k * voxel, NULL);
      }
  return bad;
}

typedef swarf_status (*part_fn)(const int rlo[3], const int rhi[3], swarf_stock **out);

static const double box_lo[3] = {-3.03, -1.21, -2.0}, box_hi[3] = {27.17, 18.93, 3.55};
static swarf_status box_slab(const int rlo[3], const int rhi[3], swarf_stock **out) {
  return rlo == NULL ? swarf_stock_new_box(box_lo, box_hi, voxel, hw, out, NULL)
                     : swarf_stock_new_box_slab(box_lo, box_hi, voxel, hw, rlo, rhi, out, NULL);
}
static swarf_status cyl_slab(const int rlo[3], const int rhi[3], swarf_stock **out) {
  return rlo == NULL
             ? swarf_stock_new_cylinder(2, 13.3, -1.0, 4.2, voxel, hw, out, NULL)
             : swarf_stock_new_cylinder_slab(2, 13.3, -1.0, 4.2, voxel, hw, rlo, rhi, out, NULL);
}

/* Four parts: x cut at cx, y at cy (block-aligned), as tools/sim/mpi/slab.c cuts. */
static void region(int r, int cx, int cy, int lo[3], int hi[3]) {
  for (int k = 0; k < 3; k++)
    lo[k] = -(1 << 30), hi[k] = 1 << 30;
  if (r & 1)
    lo[0] = cx;
  else
    hi[0] = cx - 1;
  if (r & 2)
    lo[1] = cy;
  else
    hi[1] = cy - 1;
}

static void check_shape(const char *what, part_fn make, int cx, int cy) {
  swarf_stock *w = NULL, *m = NULL, *p[4] = {NULL};
  int wlo[3], whi[3], plo[3], phi[3];
  unsigned long long active = 0;
  CHECK(make(NULL, NULL, &w) == SWARF_OK && make(NULL, NULL, &m) == SWARF_OK, "%s: whole", what);
  if (w == NULL || m == NULL) return;
  swarf_stock_index_box(w, wlo, whi);
  for (int r = 0; r < 4; r++) {
    int lo[3], hi[3];
    visit_ctx v = {w, {0}, {0}, 0, 0, 0};
    region(r, cx, cy, lo, hi);
    for (int k = 0; k < 3; k++)
      v.lo[k] = (int)(((long)lo[k] + 7) & ~7L), v.hi[k] = hi[k] & ~7;
    CHECK(make(lo, hi, &p[r]) == SWARF_OK, "%s: part %d built", what, r);
    if (p[r] == NULL) continue;
    swarf_stock_index_box(p[r], plo, phi);
    CHECK(memcmp(plo, wlo, sizeof plo) == 0 && memcmp(phi, whi, sizeof phi) == 0,
          "%s: part %d has the whole index box", what, r);
    swarf_stock_visit_active(p[r], visit, &v);
    CHECK(v.n > 1000 && v.outside == 0 && v.differ == 0,
          "%s: part %d: %ld active voxels, %ld outside its blocks, %ld differ from the whole's",
          what, r, v.n, v.outside, v.differ);
    CHECK(differ_in(p[r], w, &v) == 0, "%s: part %d: every voxel of its blocks is the whole's",
          what, r);
    active += swarf_stock_active_voxels(p[r]);
  }
  CHECK(active == swarf_stock_active_voxels(w), "%s: parts' active voxels %llu, whole %llu", what,
        active, swarf_stock_active_voxels(w));
  /* the gathering: m cropped to part 0, the other parts loaded into it */
  int lo[3], hi[3];
  region(0, cx, cy, lo, hi);
  CHECK(swarf_stock_set_region(m, lo, hi, NULL) == SWARF_OK &&
            swarf_stock_slab_crop(m, NULL) == SWARF_OK,
        "%s: crop", what);
  for (int r = 1; r < 4; r++) {
    void *buf = NULL;
    size_t n = 0;
    CHECK(p[r] != NULL && swarf_stock_slab_save(p[r], &buf, &n, NULL) == SWARF_OK &&
              swarf_stock_slab_load(m, buf, n, NULL) == SWARF_OK,
          "%s: part %d gathered", what, r);
    free(buf);
  }
  swarf_stock_set_region(m, NULL, NULL, NULL);
  visit_ctx v = {w, {1}, {0}, 0, 0, 0};
  swarf_stock_visit_active(m, visit, &v);
  CHECK(swarf_stock_active_voxels(m) == swarf_stock_active_voxels(w) && v.differ == 0,
        "%s: gathered: %llu active voxels (whole %llu), %ld differ", what,
        swarf_stock_active_voxels(m), swarf_stock_active_voxels(w), v.differ);
  CHECK(differ_in(m, w, NULL) == 0, "%s: gathered: every voxel is the whole's", what);
  CHECK(swarf_stock_volume(m) == swarf_stock_volume(w), "%s: gathered volume %.9g, whole %.9g",
        what, swarf_stock_volume(m), swarf_stock_volume(w));
  CHECK(swarf_stock_check(p[3], NULL) == SWARF_OK && swarf_stock_check(m, NULL) == SWARF_OK,
        "%s: part and gathered stock are valid level sets", what);
  for (int r = 0; r < 4; r++)
    swarf_stock_free(p[r]);
  swarf_stock_free(w);
  swarf_stock_free(m);
}

int main(void) {
  check_shape("box", box_slab, 72, 40);   /* inside the first level-1 node */
  check_shape("box", box_slab, 136, 128); /* beyond it, on its edge */
  check_shape("cylinder", cyl_slab, -64, 16);
  /* a region without blocks: a shell */
  const int none_lo[3] = {8, 8, 8}, none_hi[3] = {0, 0, 0};
  int a[3], b[3], c[3], d[3];
  swarf_stock *w = NULL, *s = NULL;
  CHECK(box_slab(NULL, NULL, &w) == SWARF_OK && box_slab(none_lo, none_hi, &s) == SWARF_OK,
        "shell built");
  if (w != NULL && s != NULL) {
    swarf_stock_index_box(w, a, b);
    swarf_stock_index_box(s, c, d);
    CHECK(swarf_stock_active_voxels(s) == 0 && memcmp(a, c, sizeof a) == 0 &&
              memcmp(b, d, sizeof b) == 0,
          "shell: no voxel, the whole index box");
  }
  swarf_stock_free(w);
  swarf_stock_free(s);
  CHECK(swarf_stock_new_box_slab(box_lo, box_hi, voxel, hw, NULL, none_hi, &s, NULL) ==
                SWARF_ERR_ARG &&
            s == NULL,
        "a NULL region is refused");
  return check_done();
}
