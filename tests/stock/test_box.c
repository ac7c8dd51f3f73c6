/* SPDX-License-Identifier: MPL-2.0 */
/* test_box.c -- a box stock against the analytic box signed distance.
 *
 * Truth: the exact box SDF (outside: distance to the box; inside: minus the
 * distance to the nearest face), computed in double. Tolerances: stored
 * voxel values 0.01 voxel (the stock rounds the exact value to float once:
 * ~1e-7 mm); trilinear samples 0.01 voxel where the SDF is linear (one face
 * within the band, no edge); the active voxels are exactly those whose SDF,
 * rounded to float, is inside the band. Enclosed volume (OpenVDB's
 * levelSetVolume, whose error grows with the edge length over the volume):
 * 0.5 % for this small box (42 x 27 x 26 voxels), 0.1 % for a 20 x 20 x 10 mm
 * box at 0.1 mm.
 */
#include <stdio.h>

#include "check.h"
#include "shapes.h"

static const box_shape box = {{-1.03, 0.21, -2.0}, {3.17, 2.93, 0.55}};
static const double voxel = 0.1;
static const int half_width = 3;

typedef struct {
  double max_err;
  long n, outside_band;
} visit_ctx;

static void compare_voxel(void *user, const double c[3], float value) {
  visit_ctx *v = (visit_ctx *)user;
  double err = fabs(value - box_sdf(&box, c));
  if (err > v->max_err) v->max_err = err;
  if (fabs(value) >= half_width * voxel) v->outside_band++;
  v->n++;
}

/* Every voxel of the padded box region: stored value vs the clamped SDF. */
static void check_all_voxels(const swarf_stock *s) {
  const double bg = half_width * voxel;
  double max_err = 0.0;
  long band = 0;
  for (int i = -60; i <= 60; i++)
    for (int j = -60; j <= 60; j++)
      for (int k = -60; k <= 60; k++) {
        double p[3] = {i * voxel, j * voxel, k * voxel}, c[3];
        double v = swarf_stock_voxel_value(s, p[0], p[1], p[2], c);
        double ref = fmin(fmax(box_sdf(&box, c), -bg), bg);
        if ((float)fabs(ref) < (float)bg) band++; /* the stock's rule, in float */
        if (fabs(v - ref) > max_err) max_err = fabs(v - ref);
      }
  printf("all voxels: max |error| %.3g voxel\n", max_err / voxel);
  CHECK(max_err <= 0.01 * voxel, "voxel values vs clamped box SDF: %g mm", max_err);
  CHECK((long)swarf_stock_active_voxels(s) == band, "active voxels %llu vs analytic band count %ld",
        swarf_stock_active_voxels(s), band);
}

/* Trilinear samples at random points within the band of one face, away from
 * edges: the SDF is linear there, so interpolation is exact. */
static void check_samples(const swarf_stock *s) {
  double max_err = 0.0;
  srand(7);
  for (int n = 0; n < 2000; n++) {
    int axis = rand() % 3, side = rand() % 2;
    double p[3];
    for (int k = 0; k < 3; k++) {
      double u = rand() / (double)RAND_MAX;
      p[k] = box.lo[k] + 0.6 + u * (box.hi[k] - box.lo[k] - 1.2);
    }
    double off = (rand() / (double)RAND_MAX - 0.5) * 2.0 * (half_width - 1.2) * voxel;
    p[axis] = (side ? box.hi[axis] : box.lo[axis]) + off;
    double err = fabs(swarf_stock_sample(s, p[0], p[1], p[2]) - box_sdf(&box, p));
    if (err > max_err) max_err = err;
  }
  printf("samples near faces: max |error| %.3g voxel\n", max_err / voxel);
  CHECK(max_err <= 0.01 * voxel, "trilinear samples vs box SDF: %g mm", max_err);
}

static void check_large_volume(void) {
  const double lo[3] = {-5, 2, -10}, hi[3] = {15, 22, 0};
  swarf_error err = {0};
  swarf_stock *s = NULL;
  swarf_stock_new_box(lo, hi, 0.1, 3, &s, &err);
  CHECK(s != NULL, "20 x 20 x 10 box: %s", err.message);
  if (s == NULL) return;
  double vol = swarf_stock_volume(s);
  printf("20 x 20 x 10 box: volume %.4f mm^3 (%+.4f%%)\n", vol, 100.0 * (vol - 4000.0) / 4000.0);
  CHECK_NEAR(vol, 4000.0, 1e-3 * 4000.0, "enclosed volume of the 20 x 20 x 10 box");
  CHECK(swarf_stock_check(s, &err) == 0, "checkLevelSet: %s", err.message);
  swarf_stock_free(s);
}

static void check_bad_arguments(void) {
  swarf_error err = {0};
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, flat[3] = {1, 0, 1};
  const double nan3[3] = {0, NAN, 0};
  struct {
    const double *lo, *hi;
    double voxel;
    int hw;
    const char *what;
  } bad[] = {{NULL, hi, 0.1, 3, "NULL lo"},       {lo, NULL, 0.1, 3, "NULL hi"},
             {lo, hi, 0.0, 3, "zero voxel"},      {lo, hi, -0.1, 3, "negative voxel"},
             {lo, hi, NAN, 3, "NaN voxel"},       {lo, hi, INFINITY, 3, "infinite voxel"},
             {lo, hi, 0.1, 2, "half width 2"},    {lo, flat, 0.1, 3, "lo == hi on y"},
             {hi, lo, 0.1, 3, "lo > hi"},         {nan3, hi, 0.1, 3, "NaN corner"},
             {lo, hi, 1e-9, 3, "too many voxels"}};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    err.message[0] = '\0';
    swarf_stock *s = NULL;
    swarf_stock_new_box(bad[i].lo, bad[i].hi, bad[i].voxel, bad[i].hw, &s, &err);
    CHECK(s == NULL && err.message[0] != '\0', "%s refused with a message", bad[i].what);
    printf("  %-16s -> %s\n", bad[i].what, err.message);
    swarf_stock_free(s);
  }
  swarf_stock_free(NULL);
  CHECK(isnan(swarf_stock_volume(NULL)), "volume of NULL is NaN");
  CHECK(swarf_stock_check(NULL, &err) != 0, "check of NULL fails");
}

int main(void) {
  swarf_error err = {0};
  swarf_stock *s = NULL;
  swarf_stock_new_box(box.lo, box.hi, voxel, half_width, &s, &err);
  CHECK(s != NULL, "new_box: %s", err.message);
  if (s == NULL) return check_done();
  CHECK(swarf_stock_voxel(s) == voxel, "voxel %g", swarf_stock_voxel(s));
  CHECK(swarf_stock_half_width(s) == half_width, "half width %d", swarf_stock_half_width(s));

  visit_ctx v = {0.0, 0, 0};
  swarf_stock_visit_active(s, compare_voxel, &v);
  printf("active voxels %ld, max |error| %.3g voxel\n", v.n, v.max_err / voxel);
  CHECK(v.n > 1000, "enough active voxels (%ld)", v.n);
  CHECK(v.max_err <= 0.01 * voxel, "active values vs box SDF: %g mm", v.max_err);
  CHECK(v.outside_band == 0, "%ld active voxels with |value| >= band", v.outside_band);
  check_all_voxels(s);
  check_samples(s);

  double dx = box.hi[0] - box.lo[0], dy = box.hi[1] - box.lo[1], dz = box.hi[2] - box.lo[2];
  double vol = swarf_stock_volume(s), want = dx * dy * dz;
  printf("volume %.6f mm^3 vs %.6f (%+.4f%%)\n", vol, want, 100.0 * (vol - want) / want);
  CHECK_NEAR(vol, want, 5e-3 * want, "enclosed volume");
  check_large_volume();

  double lo[3], hi[3];
  swarf_stock_bounds(s, lo, hi);
  for (int k = 0; k < 3; k++) {
    double bg = half_width * voxel;
    CHECK(lo[k] > box.lo[k] - bg && lo[k] <= box.lo[k] - bg + voxel, "bounds lo[%d] = %g", k,
          lo[k]);
    CHECK(hi[k] < box.hi[k] + bg && hi[k] >= box.hi[k] + bg - voxel, "bounds hi[%d] = %g", k,
          hi[k]);
  }
  CHECK(swarf_stock_check(s, &err) == 0, "checkLevelSet: %s", err.message);
  CHECK(swarf_stock_sample(s, 1.0, 1.5, -0.5) == -(float)(half_width * voxel),
        "deep inside is -band");
  CHECK(swarf_stock_sample(s, 50.0, 1.5, -0.5) == (float)(half_width * voxel),
        "far outside is +band");
  CHECK(isnan(swarf_stock_sample(s, NAN, 0, 0)), "NaN sample point gives NaN");
  swarf_stock_free(s);
  check_bad_arguments();
  return check_done();
}
