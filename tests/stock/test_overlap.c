/* SPDX-License-Identifier: MPL-2.0 */
/* test_overlap.c -- swarf_stock_overlaps: does a volume reach into the
 * material deeper than a given depth? (what the simulator asks of a rapid).
 *
 * Checked against the geometry of a box stock and a ball (a capsule of zero
 * length) whose penetration into the box is known in closed form: the ball
 * of radius r centred at height zc above the top face z = 0 overlaps the
 * material by r - zc. Found when r - zc exceeds the depth asked for by more
 * than a voxel's half diagonal (the test looks at voxel centres), not found
 * when r - zc is below the depth; an overlap in a pocket already cut away is
 * not found; the stock is not changed by the query.
 */
#include <stdio.h>

#include "check.h"
#include "shapes.h"

static int overlaps(const swarf_stock *s, const capsule_shape *c, double depth, double where[3]) {
  swarf_error err = {0};
  int hit = -1;
  swarf_stock_cut cut = capsule_cut(c);
  CHECK(swarf_stock_overlaps(s, &cut, depth, &hit, where, &err) == 0, "query: %s", err.message);
  return hit;
}

int main(void) {
  swarf_error err = {0};
  const double lo[3] = {0, 0, -5}, hi[3] = {20, 10, 0}, h = 0.1, depth = 0.05;
  swarf_stock *s = NULL;
  swarf_stock_new_box(lo, hi, h, 3, &s, &err);
  CHECK(s != NULL, "box: %s", err.message);
  if (!s) return check_done();
  const double vol0 = swarf_stock_volume(s);
  const unsigned long long act0 = swarf_stock_active_voxels(s);
  double where[3] = {0, 0, 0};
  for (int i = 0; i <= 20; i++) {
    const double pen = -0.5 + 0.05 * i; /* penetration r - zc, mm */
    capsule_shape ball = {{5.0, 5.0, 1.0 - pen}, {5.0, 5.0, 1.0 - pen}, 1.0};
    int hit = overlaps(s, &ball, depth, where);
    if (pen < depth)
      CHECK(hit == 0, "ball %+.2f mm into the top face: not deeper than %.2f", pen, depth);
    if (pen > depth + 0.5 * h * 1.7320508) {
      CHECK(hit == 1, "ball %+.2f mm into the top face: found", pen);
      CHECK(where[2] < -depth && where[2] > -pen, "voxel found at depth %.3f", -where[2]);
    }
  }
  /* a rapid along the whole stock 0.3 mm into its side face y = 10 */
  capsule_shape side = {{-5.0, 11.2, -2.0}, {25.0, 11.2, -2.0}, 1.5};
  CHECK(overlaps(s, &side, depth, where) == 1, "a long move into the side face is found");
  CHECK(where[1] > 10.0 - 0.3 && where[1] < 10.0 - depth, "found inside the face band: y %.3f",
        where[1]);
  capsule_shape above = {{-5.0, 5.0, 3.0}, {25.0, 5.0, 3.0}, 1.5};
  CHECK(overlaps(s, &above, depth, where) == 0, "a move 1.5 mm above the top is not");
  CHECK(swarf_stock_volume(s) == vol0 && swarf_stock_active_voxels(s) == act0,
        "the query changes nothing");
  /* cut a pocket, then the same ball inside the pocket touches nothing */
  capsule_shape pocket = {{15.0, 5.0, 0.0}, {15.0, 5.0, 0.0}, 3.0};
  swarf_stock_cut pc = capsule_cut(&pocket);
  CHECK(swarf_stock_remove_batch(s, &pc, 1, &err) == 0, "pocket: %s", err.message);
  capsule_shape inside = {{15.0, 5.0, 0.0}, {15.0, 5.0, 0.0}, 2.5};
  CHECK(overlaps(s, &inside, depth, where) == 0, "a ball inside the pocket is not found");
  capsule_shape wider = {{15.0, 5.0, 0.0}, {15.0, 5.0, 0.0}, 3.5};
  CHECK(overlaps(s, &wider, depth, where) == 1, "a ball 0.5 mm wider than the pocket is");
  /* bad arguments */
  int hit;
  swarf_stock_cut cut = capsule_cut(&inside);
  CHECK(swarf_stock_overlaps(NULL, &cut, depth, &hit, NULL, &err) == SWARF_ERR_ARG, "NULL stock");
  CHECK(swarf_stock_overlaps(s, &cut, 1.0, &hit, NULL, &err) == SWARF_ERR_ARG,
        "depth beyond the band refused: %s", err.message);
  swarf_stock_free(s);
  return check_done();
}
