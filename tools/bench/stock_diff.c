/* SPDX-License-Identifier: MPL-2.0 */
/* stock_diff.c -- `stock_diff REFERENCE.vdb OTHER.vdb`: how far a stock grid
 * is from a reference one of the same voxel (tools/bench/bench_rotary compares
 * stamped runs with the swept one).
 *
 * Prints one line, key=value:
 *   max, mean    |other - reference| in voxels over the voxels active in
 *                either grid (the narrow bands: near the surfaces)
 *   left         mm^3 of material in OTHER where REFERENCE has none (the
 *                inside fractions clamp(1/2 - value / voxel, 0, 1) over
 *                those voxels, as swarf_stock_volume counts them)
 *   extra        the same the other way round
 * Exit status 2 on unreadable files or different voxel sizes.
 */
#include <math.h>
#include <stdio.h>

#include "stock.h"

typedef struct {
  const swarf_stock *other;
  double voxel, max, sum, left, extra;
  unsigned long long n;
  int pass; /* 0: voxels of the reference, 1: of the other (not active in the reference) */
  const swarf_stock *ref;
} diff_acc;

static double inside(double value, double voxel) {
  return fmin(1.0, fmax(0.0, 0.5 - value / voxel));
}

static void visit(void *ctx, const double c[3], float value) {
  diff_acc *d = ctx;
  const swarf_stock *look = d->pass == 0 ? d->other : d->ref;
  double centre[3], other = swarf_stock_voxel_value(look, c[0], c[1], c[2], centre);
  double ref = value, e;
  if (d->pass == 1) {
    if (fabs(other) < swarf_stock_half_width(d->ref) * d->voxel) return; /* seen in pass 0 */
    ref = other, other = value;
  }
  e = fabs(other - ref) / d->voxel;
  d->max = fmax(d->max, e), d->sum += e, d->n++;
  d->left += fmax(0.0, inside(other, d->voxel) - inside(ref, d->voxel));
  d->extra += fmax(0.0, inside(ref, d->voxel) - inside(other, d->voxel));
}

int main(int argc, char **argv) {
  swarf_error err = {0};
  swarf_stock *a = NULL, *b = NULL;
  diff_acc d = {0};
  if (argc != 3) {
    fprintf(stderr, "usage: stock_diff REFERENCE.vdb OTHER.vdb\n");
    return 2;
  }
  if (swarf_stock_read(argv[1], &a, &err) == SWARF_OK) swarf_stock_read(argv[2], &b, &err);
  if (b == NULL || swarf_stock_voxel(a) != swarf_stock_voxel(b)) {
    fprintf(stderr, "stock_diff: %s\n", b == NULL ? err.message : "the voxel sizes differ");
    swarf_stock_free(a);
    swarf_stock_free(b);
    return 2;
  }
  d.ref = a, d.other = b, d.voxel = swarf_stock_voxel(a);
  swarf_stock_visit_active(a, visit, &d);
  d.pass = 1;
  swarf_stock_visit_active(b, visit, &d);
  printf("max=%.4f mean=%.5f left=%.3f extra=%.3f voxels=%llu\n", d.max, d.n ? d.sum / d.n : 0.0,
         d.left * pow(d.voxel, 3), d.extra * pow(d.voxel, 3), d.n);
  swarf_stock_free(a);
  swarf_stock_free(b);
  return 0;
}
