/* SPDX-License-Identifier: MPL-2.0 */
/* test_penetrate.c -- swarf_stock_penetrates: does a volume enter the
 * material by more than a given thickness? (what the simulator asks of a
 * tool's shank and holder).
 *
 * Against geometry known in closed form: a box stock with its top face at
 * z = 0 and a flat-bottomed box "holder" whose bottom face is `pen` mm below
 * it. Where the faces are parallel the score -stock - sdf is the thickness of
 * the overlap at every voxel centre between (and near) the faces, so the
 * answer must flip exactly at depth = pen (to float rounding), even for
 * overlaps thinner than a voxel that hold no voxel centre.
 * Also: a deep overlap (beyond the band) is found; material cut away first is
 * not; the stock is not changed; bad arguments are refused.
 */
#include <stdio.h>

#include "check.h"
#include "shapes.h"

static double box_cb(const void *ctx, double x, double y, double z) {
  const double p[3] = {x, y, z};
  return box_sdf((const box_shape *)ctx, p);
}

static int penetrates(const swarf_stock *s, const box_shape *b, double depth, double where[3]) {
  swarf_error err;
  int hit = -1;
  swarf_stock_cut cut = {
      {b->lo[0], b->lo[1], b->lo[2]}, {b->hi[0], b->hi[1], b->hi[2]}, box_cb, b, NULL, NULL};
  CHECK(swarf_stock_penetrates(s, &cut, NULL, 0, depth, &hit, where, &err) == SWARF_OK, "query: %s",
        err.message);
  return hit;
}

int main(void) {
  swarf_error e;
  const double lo[3] = {0, 0, -10}, hi[3] = {20, 10, 0}, h = 0.1;
  swarf_stock *s = NULL;
  CHECK(swarf_stock_new_box(lo, hi, h, 3, &s, &e) == SWARF_OK, "box: %s", e.message);
  if (!s) return check_done();
  const double vol0 = swarf_stock_volume(s);
  double where[3];
  /* face-parallel plunges, the bottom face at any offset from the voxel centres */
  for (int i = 1; i <= 23; i++) {
    const double pen = 0.0137 * i; /* mm, up to ~0.32 (inside the band, 0.3 mm) and beyond */
    box_shape holder = {{4.0, 3.0, -pen}, {9.0, 7.0, 20.0}};
    CHECK(penetrates(s, &holder, pen - 2e-4, where) == 1, "%.4f mm deep: found at depth %.4f", pen,
          pen - 2e-4);
    CHECK(where[2] < 0.3 && where[2] > -pen - 0.3, "the voxel found lies near the overlap (z %.3f)",
          where[2]);
    CHECK(penetrates(s, &holder, pen + 2e-4, where) == 0, "%.4f mm deep: not found at depth %.4f",
          pen, pen + 2e-4);
  }
  /* a side face: the holder 0.25 mm into the face y = 10 over the whole length */
  box_shape side = {{-5.0, 9.75, -4.0}, {25.0, 14.0, 8.0}};
  CHECK(penetrates(s, &side, 0.2499, where) == 1 && penetrates(s, &side, 0.2501, where) == 0,
        "0.25 mm into the side face: flips at 0.25");
  /* deep: 3 mm into the top, beyond the band: the sum is at least band + sdf */
  box_shape deep = {{5.0, 2.0, -3.0}, {8.0, 6.0, 5.0}};
  CHECK(penetrates(s, &deep, 1.0, where) == 1, "3 mm deep: found at depth 1");
  CHECK(penetrates(s, &deep, 3.0001, where) == 0, "3 mm deep: not found at depth 3.0001");
  box_shape above = {{5.0, 2.0, 0.05}, {8.0, 6.0, 5.0}};
  CHECK(penetrates(s, &above, 0.0, where) == 0, "a body above the top face is not found");
  CHECK(swarf_stock_volume(s) == vol0, "the queries change nothing");
  /* the same pocket, cut away but not removed yet (clear): a body inside it
   * is not found, and one 0.5 mm wider than it is, by 0.5 */
  capsule_shape pocket0 = {{10.0, 5.0, 0.0}, {16.0, 5.0, 0.0}, 2.0};
  swarf_stock_cut clear = capsule_cut(&pocket0);
  capsule_shape wide = {{10.0, 5.0, 0.0}, {16.0, 5.0, 0.0}, 2.5}, narrow = wide;
  narrow.r = 1.5;
  swarf_stock_cut wc = capsule_cut(&wide), nc = capsule_cut(&narrow);
  int hit2 = -1;
  CHECK(swarf_stock_penetrates(s, &nc, &clear, 1, 0.0, &hit2, where, NULL) == SWARF_OK && hit2 == 0,
        "a body inside a cleared pocket is not found");
  CHECK(swarf_stock_penetrates(s, &nc, NULL, 0, 0.0, &hit2, where, NULL) == SWARF_OK && hit2 == 1,
        "the same body without the clear volume is");
  CHECK(swarf_stock_penetrates(s, &wc, &clear, 1, 0.49, &hit2, where, NULL) == SWARF_OK &&
            hit2 == 1,
        "0.5 mm wider than the cleared pocket: found at 0.49");
  CHECK(swarf_stock_penetrates(s, &wc, &clear, 1, 0.51, &hit2, where, NULL) == SWARF_OK &&
            hit2 == 0,
        "0.5 mm wider than the cleared pocket: not found at 0.51");
  /* a pocket 2 mm deep cut away first: the same body 1 mm into its floor only */
  capsule_shape pocket = {{10.0, 5.0, 0.0}, {16.0, 5.0, 0.0}, 2.0};
  swarf_stock_cut pc = capsule_cut(&pocket);
  CHECK(swarf_stock_remove_batch(s, &pc, 1, &e) == SWARF_OK, "pocket: %s", e.message);
  box_shape inside = {{11.0, 4.5, -1.0}, {15.0, 5.5, 3.0}};
  CHECK(penetrates(s, &inside, 0.0, where) == 0, "a body inside the pocket is not found");
  /* bad arguments */
  int hit;
  swarf_stock_cut cut = {{0, 0, 0}, {1, 1, 1}, box_cb, &inside, NULL, NULL};
  swarf_error err;
  CHECK(swarf_stock_penetrates(NULL, &cut, NULL, 0, 0.0, &hit, NULL, &err) == SWARF_ERR_ARG,
        "NULL stock refused");
  CHECK(swarf_stock_penetrates(s, &cut, NULL, 0, -1.0, &hit, NULL, &err) == SWARF_ERR_ARG,
        "negative depth refused: %s", err.message);
  CHECK(swarf_stock_penetrates(s, &cut, NULL, 0, 0.0, &hit, NULL, NULL) == SWARF_OK,
        "err may be NULL");
  swarf_stock_free(s);
  return check_done();
}
