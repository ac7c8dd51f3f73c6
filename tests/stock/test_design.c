/* SPDX-License-Identifier: MPL-2.0 */
/* test_design.c -- comparison with a design, gouges per move, measured removal.
 *
 * Stock: the box [0.05,9.95]^2 x [-4.95,0.05] at 0.1 mm (faces between voxel
 * centres, where the voxel estimate of a box is exact, edges included). Design
 * (an STL box read with swarf_stock_read_design): the same box down to z = -1.45
 * (its sides and bottom on the stock's). Tolerance t = 0.05 mm (half a voxel).
 *  - excess: the 1.5 mm layer above the design, less t: 9.9^2 (1.5 - t) mm^3;
 *    the largest, 1.5 mm, beyond the design's band (0.3 mm): measured on its
 *    triangles, exactly, also with a tolerance of 0.5 mm; a 0.32 mm layer: its
 *    volume and height exactly;
 *  - a gouge 1 mm deep (beyond the band): 1.0 in the query, the batch and
 *    the comparison;
 *  - a ball plunged 0.3 mm below the design's top on a voxel column: the per-move
 *    query says 0.3 before the cut (0 after), the measured batch says the same,
 *    the comparison gives the gouge there, 0.3 deep, and the cap's volume;
 *  - moves that stay within the tolerance: no gouge;
 *  - measured batch: per-cut volumes add up to the volume change exactly (to
 *    rounding), an identical second cut removes nothing, the grid is bit for bit
 *    swarf_stock_remove_batch's (also with cleared blocks);
 *  - with the initial stock: a design wider than the stock gives `missing`
 *    (analytic), not gouge;
 *  - gouges only (no volumes): per cut the full measurement's gouges, bit for
 *    bit, on random capsules, with the design on the stock's lattice and off it;
 *  - a design elsewhere: SWARF_ERR_ARG;
 *  - a design's band read back from a .vdb with its STL's triangles
 *    (swarf_stock_design_surface, as the design cache does), or with those
 *    saved in search order (swarf_stock_design_surface_save and _cached):
 *    the deviation beyond the band is the STL design's, field for field; a
 *    damaged saved file is removed and the STL read; the triangles are read
 *    at the first query, and an STL changed before it fails it with
 *    SWARF_ERR_IO (never a silent mix of two designs).
 */
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "shapes.h"
#include "stl_box.h"

static const double V = 0.1, T = 0.05;

static swarf_stock *stock_box(void) {
  const double lo[3] = {0.05, 0.05, -4.95}, hi[3] = {9.95, 9.95, 0.05};
  swarf_stock *s = test_box_(lo, hi, V, 3);
  CHECK(s != NULL, "box");
  return s;
}

static swarf_stock *design_box(const double lo[3], const double hi[3]) {
  swarf_stock *d = NULL;
  swarf_error err;
  CHECK(stl_box_write("design_box.stl", lo, hi, 0, STL_GOOD) == 0, "write");
  CHECK(swarf_stock_read_design("design_box.stl", V, &d, &err) == SWARF_OK, "design: %s",
        err.message);
  return d;
}

static swarf_stock *copy(const swarf_stock *s) {
  static const swarf_stock_placement same = {{0, 0, 0}, {0, 0, 0}};
  swarf_stock *c = NULL;
  swarf_error err;
  CHECK(swarf_stock_place(s, &same, &c, &err) == SWARF_OK, "copy: %s", err.message);
  return c;
}

/* A ball of radius 1.5 whose bottom is at (x, y, zb). */
static capsule_shape ball(double x, double y, double zb) {
  capsule_shape c = {{x, y, zb + 1.5}, {x, y, zb + 1.5}, 1.5};
  return c;
}

static void test_excess(const swarf_stock *s, const swarf_stock *d) {
  swarf_stock_deviation dev;
  swarf_error err;
  CHECK(swarf_stock_compare(s, d, NULL, T, &dev, &err) == SWARF_OK, "%s", err.message);
  const double layer = 9.9 * 9.9 * (1.5 - T);
  printf("excess %.4f mm^3 (analytic %.4f), largest %.3f (reach %.3f, clamped %d), gouge %.4f\n",
         dev.excess_volume, layer, dev.excess_height, dev.reach, dev.excess_clamped,
         dev.gouge_volume);
  CHECK_NEAR(dev.excess_volume, layer, 1e-6 * layer,
             "excess volume, a 1.5 mm layer less the tolerance");
  /* A design read from a mesh keeps its triangles: deviations beyond its
   * band (SWARF_STOCK_DESIGN_BAND voxels, 0.2 mm) are measured against them exactly. */
  CHECK(isinf(dev.reach), "reach: unlimited for a mesh design (%g)", dev.reach);
  CHECK_NEAR(dev.excess_height, 1.5, 1e-4, "largest excess 1.5 mm, beyond the band, exact");
  CHECK(dev.excess_clamped == 0, "not flagged as clamped");
  CHECK(dev.gouge_volume < 1e-9 && dev.gouge_depth == 0, "no gouge: %.3g", dev.gouge_volume);
  CHECK_NEAR(dev.design_volume, 9.9 * 9.9 * 3.5, 1e-6 * 343, "design volume");
  CHECK_NEAR(dev.stock_volume, 9.9 * 9.9 * 5, 1e-6 * 490, "stock volume");
  CHECK(fabs(dev.tolerance - T) < 1e-12, "tolerance kept");
  /* A tolerance of 0.5 mm, beyond the band: volumes still exact (the design's
   * values past its band are measured on its triangles). */
  CHECK(swarf_stock_compare(s, d, NULL, 0.5, &dev, &err) == SWARF_OK, "%s", err.message);
  printf("tolerance 0.5: excess %.4f mm^3 (analytic %.4f), largest %.4f\n", dev.excess_volume,
         9.9 * 9.9 * 1.0, dev.excess_height);
  CHECK_NEAR(dev.excess_volume, 9.9 * 9.9 * 1.0, 1e-6 * 98, "excess beyond a 0.5 mm tolerance");
  CHECK_NEAR(dev.excess_height, 1.5, 1e-4, "largest excess with a wide tolerance");
}

static void test_excess_layer(void) {
  /* A 0.32 mm layer (off the voxel lattice): its height is measured exactly. */
  swarf_stock *s = stock_box();
  const double lo[3] = {0.05, 0.05, -4.95}, hi[3] = {9.95, 9.95, 0.05 - 0.32};
  swarf_stock *d = design_box(lo, hi);
  swarf_stock_deviation dev;
  swarf_error err;
  CHECK(swarf_stock_compare(s, d, NULL, 0, &dev, &err) == SWARF_OK, "%s", err.message);
  const double layer = 9.9 * 9.9 * (0.32 - T);
  printf("0.32 mm layer: excess %.4f mm^3 (%.4f), largest %.4f at %.2f %.2f %.2f\n",
         dev.excess_volume, layer, dev.excess_height, dev.excess_at[0], dev.excess_at[1],
         dev.excess_at[2]);
  CHECK_NEAR(dev.tolerance, T, 1e-12, "default tolerance: half a voxel");
  CHECK_NEAR(dev.excess_volume, layer, 1e-5 * layer, "layer volume");
  CHECK_NEAR(dev.excess_height, 0.32, 1e-4, "largest excess of a flat layer");
  CHECK(dev.excess_clamped == 0, "not clamped");
  CHECK(dev.excess_at[2] > -0.28 && dev.excess_at[2] < 0.06, "in the layer: z %.3f",
        dev.excess_at[2]);
  swarf_stock_free(d);
  swarf_stock_free(s);
}

static void test_gouge(swarf_stock *s, const swarf_stock *d) {
  swarf_error err;
  double depth, at[3];
  swarf_stock *initial = copy(s);
  /* Within the tolerance (0.02 and 0.04 mm below the design's top): none. */
  for (int i = 0; i < 2; i++) {
    capsule_shape b = ball(2, 2, -1.47 - 0.02 * i);
    swarf_stock_cut cut = capsule_cut(&b);
    CHECK(swarf_stock_gouge(s, d, &cut, T, &depth, at, &err) == SWARF_OK, "%s", err.message);
    CHECK(depth == 0 && isnan(at[0]), "within tolerance: %.4f", depth);
  }
  capsule_shape b = ball(5, 5, -1.75), c = ball(8, 3.05, -1.55);
  swarf_stock_cut cuts[3] = {capsule_cut(&b), capsule_cut(&b), capsule_cut(&c)};
  CHECK(swarf_stock_gouge(s, d, &cuts[0], T, &depth, at, &err) == SWARF_OK, "%s", err.message);
  printf("gouge query before the cut: %.5f at %.2f %.2f %.2f\n", depth, at[0], at[1], at[2]);
  CHECK_NEAR(depth, 0.3, 1e-4, "the ball's gouge depth on a voxel column");
  CHECK(fabs(at[0] - 5) < 0.15 && fabs(at[1] - 5) < 0.15 && at[2] < -1.45 && at[2] > -1.76,
        "where");
  CHECK(swarf_stock_gouge(s, d, &cuts[2], T, &depth, at, &err) == SWARF_OK, "%s", err.message);
  printf("off the voxel column (y 3.05), 0.1 deep: %.5f\n", depth);
  CHECK_NEAR(depth, 0.1, 0.005, "off-column gouge depth");
  /* The batch, measured: the second, identical ball finds nothing left. */
  swarf_stock *plain = copy(s);
  swarf_stock_cut_effect e[3];
  double before = swarf_stock_volume(s);
  CHECK(swarf_stock_remove_batch_measured(s, cuts, 3, d, T, e, &err) == SWARF_OK, "%s",
        err.message);
  CHECK(swarf_stock_remove_batch(plain, cuts, 3, NULL) == SWARF_OK, "call failed");
  CHECK(stock_differences(s, plain) == 0, "measured grid = plain grid bit for bit");
  double after = swarf_stock_volume(s), sum = e[0].removed + e[1].removed + e[2].removed;
  printf("measured: removed %.6f %.6f %.6f (sum %.9f, change %.9f), gouges %.5f %.5f %.5f\n",
         e[0].removed, e[1].removed, e[2].removed, sum, before - after, e[0].gouge_depth,
         e[1].gouge_depth, e[2].gouge_depth);
  CHECK(fabs(sum - (before - after)) <= 1e-9 * before, "per-cut volumes add up: %.12g vs %.12g",
        sum, before - after);
  CHECK(e[1].removed == 0 && e[1].gouge_depth == 0, "the repeated cut removes nothing: %g",
        e[1].removed);
  CHECK_NEAR(e[0].gouge_depth, 0.3, 1e-4, "batch gouge depth = the query's");
  CHECK_NEAR(e[2].gouge_depth, 0.1, 0.005, "batch gouge depth (off column)");
  CHECK(swarf_stock_gouge(s, d, &cuts[0], T, &depth, at, &err) == SWARF_OK && depth == 0,
        "after the cut: nothing left to gouge (%.4f)", depth);
  /* The comparison after the run. */
  swarf_stock_deviation dev;
  CHECK(swarf_stock_compare(s, d, initial, T, &dev, &err) == SWARF_OK, "%s", err.message);
  const double h = 0.3 - T, cap = M_PI * h * h * (3 * 1.5 - h) / 3, h2 = 0.1 - T,
               cap2 = M_PI * h2 * h2 * (3 * 1.5 - h2) / 3;
  printf("after: gouge %.4f mm^3 (caps %.4f), deepest %.5f at %.2f %.2f %.2f, missing %.4f\n",
         dev.gouge_volume, cap + cap2, dev.gouge_depth, dev.gouge_at[0], dev.gouge_at[1],
         dev.gouge_at[2], dev.missing_volume);
  CHECK_NEAR(dev.gouge_depth, 0.3, 1e-4, "deepest gouge");
  CHECK(fabs(dev.gouge_at[0] - 5) < 0.15 && fabs(dev.gouge_at[1] - 5) < 0.15,
        "deepest gouge's place");
  CHECK(fabs(dev.gouge_volume - (cap + cap2)) < 0.05 * (cap + cap2), "gouge volume %.4f vs %.4f",
        dev.gouge_volume, cap + cap2);
  CHECK(dev.missing_volume < 1e-9, "nothing missing");
  CHECK(dev.gouge_clamped == 0, "not clamped");
  swarf_stock_free(plain);
  swarf_stock_free(initial);
}

/* A ball plunged 1 mm below the design's top, three band widths: the query,
 * the measured batch and the comparison give 1.0 (the design's triangles,
 * not its band, beyond 0.3 mm). */
static void test_deep_gouge(void) {
  swarf_stock *s = stock_box(), *initial = copy(s);
  const double lo[3] = {0.05, 0.05, -4.95}, hi[3] = {9.95, 9.95, -1.45};
  swarf_stock *d = design_box(lo, hi);
  capsule_shape b = ball(5, 5, -2.45);
  swarf_stock_cut cut = capsule_cut(&b);
  swarf_stock_cut_effect e;
  swarf_stock_deviation dev;
  swarf_error err;
  double depth, at[3];
  CHECK(swarf_stock_gouge(s, d, &cut, T, &depth, at, &err) == SWARF_OK, "%s", err.message);
  CHECK_NEAR(depth, 1.0, 1e-4, "deep gouge, the query");
  CHECK(swarf_stock_remove_batch_measured(s, &cut, 1, d, T, &e, &err) == SWARF_OK, "%s",
        err.message);
  CHECK_NEAR(e.gouge_depth, 1.0, 1e-4, "deep gouge, the measured batch");
  CHECK(swarf_stock_compare(s, d, initial, T, &dev, &err) == SWARF_OK, "%s", err.message);
  printf("deep gouge: query %.5f, batch %.5f, comparison %.5f (clamped %d)\n", depth, e.gouge_depth,
         dev.gouge_depth, dev.gouge_clamped);
  CHECK_NEAR(dev.gouge_depth, 1.0, 1e-4, "deep gouge, the comparison");
  CHECK(dev.gouge_clamped == 0, "not clamped");
  swarf_stock_free(d);
  swarf_stock_free(initial);
  swarf_stock_free(s);
}

static void test_cleared_blocks(void) {
  swarf_stock *s = stock_box(), *plain;
  plain = copy(s);
  capsule_shape big = {{-1, 5, -1}, {11, 5, -1}, 4.0}, small = {{5, 1, 0}, {5, 9, 0}, 0.7};
  swarf_stock_cut cuts[2] = {capsule_cut(&small), capsule_cut(&big)};
  swarf_stock_cut_effect e[2];
  swarf_error err;
  double before = swarf_stock_volume(s);
  CHECK(swarf_stock_remove_batch_measured(s, cuts, 2, NULL, T, e, &err) == SWARF_OK, "%s",
        err.message);
  CHECK(swarf_stock_remove_batch(plain, cuts, 2, NULL) == SWARF_OK, "call failed");
  CHECK(stock_differences(s, plain) == 0, "measured = plain with cleared blocks");
  double change = before - swarf_stock_volume(s);
  printf("cleared blocks: removed %.6f + %.6f = %.9f, change %.9f\n", e[0].removed, e[1].removed,
         e[0].removed + e[1].removed, change);
  CHECK(fabs(e[0].removed + e[1].removed - change) <= 1e-9 * before, "adds up with cleared blocks");
  CHECK(e[0].gouge_depth == 0 && isnan(e[0].gouge_at[0]), "no design, no gouge");
  swarf_stock_free(plain);
  swarf_stock_free(s);
}

static double uniform(unsigned *seed, double a, double b) {
  *seed = *seed * 1103515245u + 12345u;
  return a + (b - a) * (double)((*seed >> 8) & 0xffffff) / 16777216.0;
}

/* Gouges only (swarf_stock_remove_batch_gouges_support) against the full
 * measurement: 48 random capsules over the design's top and through its
 * sides, in 4 batches, with the design on the stock's lattice and off it
 * (read at 0.07 mm: sampled trilinearly), at two tolerances. Per cut the
 * same gouge depth and place, bit for bit, no volumes, and the grids bit for
 * bit the same; without a design, the plain removal. */
static void test_gouges_only(void) {
  const double lo[3] = {0.05, 0.05, -4.95}, hi[3] = {9.95, 9.95, -1.45};
  enum { N = 48, B = 12 };
  swarf_error err;
  CHECK(stl_box_write("design_box.stl", lo, hi, 0, STL_GOOD) == 0, "write");
  for (int lattice = 0; lattice < 2; lattice++)
    for (int ti = 0; ti < 2; ti++) {
      swarf_stock *d = NULL, *full = stock_box(), *only = stock_box();
      const double tol = ti ? 0.12 : T;
      CHECK(swarf_stock_read_design("design_box.stl", lattice ? 0.07 : V, &d, &err) == SWARF_OK,
            "design: %s", err.message);
      capsule_shape caps[N];
      swarf_stock_cut cuts[N];
      swarf_stock_cut_effect ef[N], eo[N];
      unsigned seed = 20261203u + 7u * (unsigned)(2 * lattice + ti);
      for (int i = 0; i < N; i++) {
        for (int k = 0; k < 2; k++) {
          caps[i].a[k] = uniform(&seed, -1, 11);
          caps[i].b[k] = caps[i].a[k] + uniform(&seed, -4, 4);
        }
        caps[i].a[2] = uniform(&seed, -2.4, 0.5);
        caps[i].b[2] = caps[i].a[2] + uniform(&seed, -0.5, 0.5);
        caps[i].r = uniform(&seed, 0.3, 1.5);
        cuts[i] = capsule_cut(&caps[i]);
      }
      for (int b = 0; b < N / B; b++) {
        CHECK(swarf_stock_remove_batch_measured_support(full, cuts + B * b, NULL, B, d, tol,
                                                        ef + B * b, &err) == SWARF_OK,
              "%s", err.message);
        CHECK(swarf_stock_remove_batch_gouges_support(only, cuts + B * b, NULL, B, d, tol,
                                                      eo + B * b, &err) == SWARF_OK,
              "%s", err.message);
      }
      int gouging = 0, same = 0, novolume = 0;
      double deepest = 0;
      for (int i = 0; i < N; i++) {
        int at = 1;
        for (int k = 0; k < 3; k++)
          at &= ef[i].gouge_at[k] == eo[i].gouge_at[k] ||
                (isnan(ef[i].gouge_at[k]) && isnan(eo[i].gouge_at[k]));
        same += ef[i].gouge_depth == eo[i].gouge_depth && at;
        novolume += eo[i].removed == 0 && eo[i].removed_voxels == 0;
        gouging += ef[i].gouge_depth > 0;
        if (ef[i].gouge_depth > deepest) deepest = ef[i].gouge_depth;
      }
      printf("gouges only (design %s, tolerance %.2f): %d of %d cuts gouge (deepest %.4f), the "
             "same in %d\n",
             lattice ? "off the lattice" : "on the lattice", tol, gouging, N, deepest, same);
      CHECK(same == N, "every cut's gouge the full measurement's: %d of %d", same, N);
      CHECK(novolume == N, "no volumes: %d of %d", novolume, N);
      CHECK(gouging >= 8 && gouging <= N - 8, "a mix of gouging and clear cuts: %d", gouging);
      CHECK(stock_differences(full, only) == 0, "the same grid bit for bit");
      swarf_stock_free(d);
      swarf_stock_free(only);
      swarf_stock_free(full);
    }
  /* Without a design: the plain removal, no gouge, no volume. */
  swarf_stock *s = stock_box(), *plain = stock_box();
  capsule_shape c = {{1, 1, -1}, {9, 8, -2}, 1.2};
  swarf_stock_cut cut = capsule_cut(&c);
  swarf_stock_cut_effect e;
  CHECK(swarf_stock_remove_batch_gouges_support(s, &cut, NULL, 1, NULL, T, &e, &err) == SWARF_OK,
        "%s", err.message);
  CHECK(swarf_stock_remove_batch(plain, &cut, 1, NULL) == SWARF_OK, "call failed");
  CHECK(stock_differences(s, plain) == 0, "no design: the plain removal");
  CHECK(e.removed == 0 && e.gouge_depth == 0 && isnan(e.gouge_at[0]),
        "no design: nothing measured");
  CHECK(swarf_stock_remove_batch_gouges_support(s, NULL, NULL, 1, NULL, T, &e, &err) ==
            SWARF_ERR_ARG,
        "NULL cuts refused");
  swarf_stock_free(plain);
  swarf_stock_free(s);
}

static void test_missing_and_elsewhere(void) {
  swarf_stock *s = stock_box(), *initial = copy(s);
  const double lo[3] = {0.05, 0.05, -4.95}, hi[3] = {12, 9.95, -1.45};
  swarf_stock *d = design_box(lo, hi);
  swarf_stock_deviation dev;
  swarf_error err;
  CHECK(swarf_stock_compare(s, d, initial, T, &dev, &err) == SWARF_OK, "%s", err.message);
  const double missing = (12 - T - 9.95) * (9.9 - 2 * T) * (3.5 - 2 * T);
  printf("wider design: missing %.4f (analytic %.4f), gouge %.4f\n", dev.missing_volume, missing,
         dev.gouge_volume);
  CHECK(fabs(dev.missing_volume - missing) < 0.002 * missing, "missing volume");
  CHECK(dev.gouge_volume < 1e-9, "no gouge with the initial stock");
  CHECK(swarf_stock_compare(s, d, NULL, T, &dev, &err) == SWARF_OK, "%s", err.message);
  CHECK(fabs(dev.gouge_volume - missing) < 0.002 * missing, "without it, counted as gouge: %.4f",
        dev.gouge_volume);
  swarf_stock_free(d);
  const double flo[3] = {100, 0, -5}, fhi[3] = {110, 10, -1};
  d = design_box(flo, fhi);
  CHECK(swarf_stock_check_design(s, d, &err) == SWARF_ERR_ARG, "far design refused");
  CHECK(strstr(err.message, "does not overlap") != NULL, "message: %s", err.message);
  CHECK(swarf_stock_compare(s, d, NULL, T, &dev, &err) == SWARF_ERR_ARG, "compare refuses it too");
  swarf_stock_free(d);
  swarf_stock_free(initial);
  swarf_stock_free(s);
}

/* The design's band from design_band.vdb, with design_box.stl's triangles. */
static swarf_stock *band_with_surface(void) {
  swarf_stock *d = NULL;
  swarf_error err;
  CHECK(swarf_stock_read_design("design_band.vdb", V, &d, &err) == SWARF_OK, "band: %s",
        err.message);
  if (d == NULL) return NULL;
  CHECK(swarf_stock_design_surface(d, "design_box.stl", &err) == SWARF_OK, "surface: %s",
        err.message);
  return d;
}

static void test_lazy_surface(void) {
  const double lo[3] = {0.05, 0.05, -4.95}, hi[3] = {9.95, 9.95, -1.45};
  swarf_stock *s = stock_box(), *d = design_box(lo, hi), *b;
  swarf_stock_deviation want, got;
  swarf_error err;
  if (s == NULL || d == NULL) return;
  CHECK(swarf_stock_write_vdb(d, "design_band.vdb", &err) == SWARF_OK, "%s", err.message);
  CHECK(swarf_stock_compare(s, d, NULL, T, &want, &err) == SWARF_OK, "%s", err.message);
  b = band_with_surface();
  if (b != NULL) {
    CHECK(swarf_stock_compare(s, b, NULL, T, &got, &err) == SWARF_OK, "%s", err.message);
    printf("band + lazy surface: largest excess %.6f (the STL design's %.6f), volume %.6f (%.6f)\n",
           got.excess_height, want.excess_height, got.excess_volume, want.excess_volume);
    CHECK(got.excess_height == want.excess_height && got.excess_volume == want.excess_volume &&
              memcmp(got.excess_at, want.excess_at, sizeof got.excess_at) == 0 &&
              isinf(got.reach) && got.excess_clamped == 0,
          "the deviation of the band with its triangles is the STL design's");
    CHECK_NEAR(got.excess_height, 1.5, 1e-4, "1.5 mm, beyond the band, on the triangles");
  }
  swarf_stock_free(b);
  /* Its triangles saved in search order and read back (the design cache's
   * .tri): the same deviation; a damaged file is removed and the STL read. */
  CHECK(swarf_stock_design_surface_save(d, "design_band.tri", &err) == SWARF_OK, "save: %s",
        err.message);
  for (int damaged = 0; damaged < 2; damaged++) {
    if (damaged) {
      FILE *f = fopen("design_band.tri", "r+b");
      CHECK(f != NULL && fseek(f, 60, SEEK_SET) == 0 && fputc(0x5a, f) != EOF, "damage");
      if (f) fclose(f);
    }
    b = NULL;
    CHECK(swarf_stock_read_design("design_band.vdb", V, &b, &err) == SWARF_OK, "%s", err.message);
    CHECK(b && swarf_stock_design_surface_cached(b, "design_band.tri", "design_box.stl", &err) ==
                   SWARF_OK,
          "cached: %s", err.message);
    if (b != NULL) {
      CHECK(swarf_stock_compare(s, b, NULL, T, &got, &err) == SWARF_OK, "%s", err.message);
      printf("band + %s .tri: largest excess %.6f, volume %.6f\n", damaged ? "damaged" : "saved",
             got.excess_height, got.excess_volume);
      CHECK(got.excess_height == want.excess_height && got.excess_volume == want.excess_volume &&
                memcmp(got.excess_at, want.excess_at, sizeof got.excess_at) == 0,
            "%s .tri: the STL design's deviation", damaged ? "a damaged" : "the saved");
    }
    struct stat st;
    CHECK((stat("design_band.tri", &st) == 0) == !damaged, "the damaged .tri is removed");
    swarf_stock_free(b);
  }
  /* The STL changes after the band was given its surface, before the first
   * query beyond the band: that query fails, and says why. */
  b = band_with_surface();
  const struct timespec later[2] = {{0, UTIME_OMIT}, {1000000000, 0}};
  CHECK(utimensat(AT_FDCWD, "design_box.stl", later, 0) == 0, "touch the STL");
  if (b != NULL) {
    const swarf_status st = swarf_stock_compare(s, b, NULL, T, &got, &err);
    printf("STL changed before the first query: status %d, %s\n", (int)st, err.message);
    CHECK(st == SWARF_ERR_IO && strstr(err.message, "changed during the run") != NULL,
          "a changed STL fails the query: %d %s", (int)st, err.message);
  }
  swarf_stock_free(b);
  swarf_stock_free(d);
  b = NULL;
  CHECK(swarf_stock_read_design("design_band.vdb", V, &b, &err) == SWARF_OK, "%s", err.message);
  CHECK(b == NULL || swarf_stock_design_surface(b, "no_such_design.stl", &err) == SWARF_ERR_IO,
        "a missing STL is refused at once");
  swarf_stock_free(b);
  swarf_stock_free(s);
}

int main(void) {
  swarf_stock *s = stock_box();
  const double lo[3] = {0.05, 0.05, -4.95}, hi[3] = {9.95, 9.95, -1.45};
  swarf_stock *d = design_box(lo, hi);
  if (s && d) {
    test_excess(s, d);
    test_gouge(s, d);
  }
  swarf_stock_free(d);
  swarf_stock_free(s);
  test_excess_layer();
  test_deep_gouge();
  test_cleared_blocks();
  test_gouges_only();
  test_missing_and_elsewhere();
  test_lazy_surface();
  return check_done();
}
