/* SPDX-License-Identifier: MPL-2.0 */
/* test_remove.c -- removal of volumes against analytic truth.
 *
 * Truth: after removing volumes S_1..S_n from the box B, every voxel holds
 * clamp(max(sdf_B, -sdf_S1, ..., -sdf_Sn), -band, band) (the CSG difference of
 * exact distances, rounded once to float), and is active iff that value,
 * rounded to float, is inside the band. Tolerances: voxel values 0.01 voxel
 * (observed ~1e-7); removed volume (difference of swarf_stock_volume before
 * and after) 0.5 % of the analytic ball / cap volume (observed < 0.1 %); results of different
 * orders and batchings must be bit-identical (max, float rounding and clamping commute),
 * and so must removals with and without a cut's local planes (range_plane), which must
 * spare range calls (a plane raised by a tenth of the radius fails both checks).
 */
#include <stdio.h>

#include "check.h"
#include "shapes.h"

#define VOXEL 0.1
#define HW 3
#define BAND (HW * VOXEL)
#define MAX_SHAPES 1000

static const box_shape box = {{0.0, 0.0, -5.0}, {10.0, 8.0, 0.0}};

/* The removed shapes so far, for the analytic truth. */
static capsule_shape removed[MAX_SHAPES];
static int nremoved;

static double truth(const double p[3]) {
  double v = box_sdf(&box, p);
  for (int i = 0; i < nremoved; i++)
    v = fmax(v, -capsule_dist(&removed[i], p[0], p[1], p[2]));
  return fmin(fmax(v, -BAND), BAND);
}

static swarf_stock *new_stock(void) {
  swarf_error err = {0};
  swarf_stock *s = NULL;
  swarf_stock_new_box(box.lo, box.hi, VOXEL, HW, &s, &err);
  CHECK(s != NULL, "new_box: %s", err.message);
  nremoved = 0;
  return s;
}

static int remove_capsule(swarf_stock *s, capsule_shape c) {
  swarf_error err = {0};
  double lo[3], hi[3];
  removed[nremoved++] = c;
  capsule_bounds(&removed[nremoved - 1], lo, hi);
  int rc = swarf_stock_remove(s, lo, hi, capsule_sdf_cb, &removed[nremoved - 1], &err);
  CHECK(rc == 0, "remove: %s", err.message);
  return rc;
}

/* Every voxel of the index box [lo, hi] (mm) against the truth; returns the
 * largest error (mm) and counts active-state mismatches. */
static double compare_region(const swarf_stock *s, const double lo[3], const double hi[3],
                             long *state_errors, long *band_voxels) {
  double max_err = 0.0;
  *state_errors = *band_voxels = 0;
  for (double x = lo[0]; x <= hi[0]; x += VOXEL)
    for (double y = lo[1]; y <= hi[1]; y += VOXEL)
      for (double z = lo[2]; z <= hi[2]; z += VOXEL) {
        double c[3];
        float v = (float)swarf_stock_voxel_value(s, x, y, z, c);
        double ref = truth(c);
        if (fabs(v - ref) > max_err) max_err = fabs(v - ref);
        if ((float)fabs(ref) < (float)BAND) ++*band_voxels;
      }
  *state_errors = labs((long)swarf_stock_active_voxels(s) - 0); /* filled by caller */
  return max_err;
}

static void check_values(const swarf_stock *s, const double lo[3], const double hi[3],
                         const char *what) {
  long states, band;
  double err = compare_region(s, lo, hi, &states, &band);
  printf("%s: %ld band voxels in region, max |error| %.3g voxel\n", what, band, err / VOXEL);
  CHECK(err <= 0.01 * VOXEL, "%s: voxel values vs CSG truth: %g mm", what, err);
}

static void check_whole_band(const swarf_stock *s, const char *what) {
  const double lo[3] = {box.lo[0] - 0.5, box.lo[1] - 0.5, box.lo[2] - 0.5};
  const double hi[3] = {box.hi[0] + 0.5, box.hi[1] + 0.5, box.hi[2] + 0.5};
  long states, band;
  double err = compare_region(s, lo, hi, &states, &band);
  printf("%s: whole grid, %ld band voxels (stock: %llu active), max |error| %.3g voxel\n", what,
         band, swarf_stock_active_voxels(s), err / VOXEL);
  CHECK(err <= 0.01 * VOXEL, "%s: voxel values vs CSG truth: %g mm", what, err);
  CHECK((long)swarf_stock_active_voxels(s) == band, "%s: active voxels %llu vs band %ld", what,
        swarf_stock_active_voxels(s), band);
}

static void check_valid(const swarf_stock *s, const char *what) {
  swarf_error err = {0};
  CHECK(swarf_stock_check(s, &err) == 0, "%s: checkLevelSet: %s", what, err.message);
}

/* A ball of radius r centred at c removed; removed volume vs `want`. */
static void ball_case(const char *what, double cx, double cy, double cz, double r, double want) {
  swarf_stock *s = new_stock();
  if (!s) return;
  double before = swarf_stock_volume(s);
  capsule_shape ball = {{cx, cy, cz}, {cx, cy, cz}, r};
  remove_capsule(s, ball);
  double got = before - swarf_stock_volume(s);
  printf("%s: removed %.5f mm^3 vs %.5f analytic (%+.4f%%)\n", what, got, want,
         100.0 * (got - want) / want);
  CHECK_NEAR(got, want, 5e-3 * want, what);
  const double lo[3] = {cx - r - 0.5, cy - r - 0.5, cz - r - 0.5};
  const double hi[3] = {cx + r + 0.5, cy + r + 0.5, cz + r + 0.5};
  check_values(s, lo, hi, what);
  check_whole_band(s, what);
  check_valid(s, what);
  swarf_stock_free(s);
}

static void deep_cavity(void) {
  const double r = 1.5, c[3] = {5.0, 4.0, -2.5};
  swarf_stock *s = new_stock();
  if (!s) return;
  double before = swarf_stock_volume(s);
  capsule_shape ball = {{c[0], c[1], c[2]}, {c[0], c[1], c[2]}, r};
  remove_capsule(s, ball);
  double got = before - swarf_stock_volume(s), want = 4.0 / 3.0 * M_PI * r * r * r;
  printf("cavity: removed %.5f mm^3 vs %.5f (%+.4f%%)\n", got, want, 100.0 * (got - want) / want);
  CHECK_NEAR(got, want, 5e-3 * want, "closed cavity volume");
  CHECK(swarf_stock_sample(s, c[0], c[1], c[2]) == (float)BAND, "cavity centre is outside (+band)");
  CHECK_NEAR(swarf_stock_sample(s, c[0] + r + 0.15, c[1], c[2]), -0.15, 0.01 * VOXEL,
             "material just beyond the cavity wall");
  CHECK(swarf_stock_sample(s, c[0], c[1], c[2] + r + 0.5) == -(float)BAND,
        "material between cavity and top");
  check_whole_band(s, "cavity");
  check_valid(s, "cavity");
  swarf_stock_free(s);
}

static double urand(double a, double b) {
  return a + (b - a) * (rand() / (double)RAND_MAX);
}

/* 1000 random small capsules near the surface, one at a time. */
static void random_removals(void) {
  swarf_stock *s = new_stock();
  if (!s) return;
  srand(12345);
  for (int i = 0; i < MAX_SHAPES; i++) {
    capsule_shape c;
    for (int k = 0; k < 3; k++)
      c.a[k] = urand(box.lo[k] - 0.5, box.hi[k] + 0.5);
    if (i % 2) c.a[2] = urand(-1.5, 0.5); /* half of them at the top face */
    for (int k = 0; k < 3; k++)
      c.b[k] = c.a[k] + urand(-1.0, 1.0);
    c.r = urand(0.05, 0.8);
    if (remove_capsule(s, c) != 0) break;
  }
  check_whole_band(s, "1000 random removals");
  check_valid(s, "1000 random removals");
  swarf_stock_free(s);
}

static capsule_shape shapes_ab[2] = {{{3.0, 3.0, 0.2}, {6.0, 4.5, -0.8}, 1.2},
                                     {{4.0, 1.0, -0.5}, {4.5, 6.0, -0.3}, 1.6}};

static void order_independence(void) {
  swarf_stock *a = new_stock(), *b = new_stock();
  if (!a || !b) return;
  remove_capsule(a, shapes_ab[0]);
  remove_capsule(a, shapes_ab[1]);
  remove_capsule(b, shapes_ab[1]);
  remove_capsule(b, shapes_ab[0]);
  CHECK(swarf_stock_active_voxels(a) == swarf_stock_active_voxels(b), "same active counts");
  CHECK(stock_differences(a, b) == 0, "A then B == B then A (bit-identical)");
  CHECK(stock_differences(b, a) == 0, "B then A == A then B (bit-identical)");
  swarf_stock_free(a);
  swarf_stock_free(b);
}

/* A zig-zag of 300 capsules removed one at a time and in batches of 64. */
static void batch_equals_single(void) {
  enum { N = 300 };
  static capsule_shape path[N];
  static swarf_stock_cut cuts[N];
  swarf_error err = {0};
  for (int i = 0; i < N; i++) {
    int row = i / 30, col = i % 30;
    double x0 = 1.0 + 0.25 * (row % 2 ? 30 - col : col), x1 = x0 + (row % 2 ? -0.25 : 0.25);
    capsule_shape c = {
        {x0, 1.0 + 0.6 * row, 0.3}, {x1, 1.0 + 0.6 * row + (col == 29 ? 0.6 : 0.0), 0.3}, 0.8};
    path[i] = c;
    cuts[i] = capsule_cut(&path[i]);
  }
  swarf_stock *one = new_stock(), *batch = new_stock();
  if (!one || !batch) return;
  for (int i = 0; i < N; i++)
    CHECK(swarf_stock_remove(one, cuts[i].lo, cuts[i].hi, cuts[i].sdf, cuts[i].ctx, &err) == 0,
          "remove %d: %s", i, err.message);
  for (int i = 0; i < N; i += 64) {
    size_t n = N - i < 64 ? (size_t)(N - i) : 64;
    CHECK(swarf_stock_remove_batch(batch, cuts + i, n, &err) == 0, "batch: %s", err.message);
  }
  CHECK(swarf_stock_remove_batch(batch, cuts, 0, &err) == 0, "empty batch: %s", err.message);
  printf("batch vs single: %llu vs %llu active voxels\n", swarf_stock_active_voxels(batch),
         swarf_stock_active_voxels(one));
  CHECK(stock_differences(one, batch) == 0, "batch == one at a time (bit-identical)");
  CHECK(stock_differences(batch, one) == 0, "one at a time == batch (bit-identical)");
  nremoved = 0;
  for (int i = 0; i < N; i++)
    removed[nremoved++] = path[i];
  check_whole_band(batch, "zig-zag in batches");
  check_valid(batch, "zig-zag in batches");
  swarf_stock_free(one);
  swarf_stock_free(batch);
}

/* A capsule's range function and its range_plane companion, counting their calls
 * (threads: atomics). The plane is the supporting plane lowered by a tenth of the radius
 * (a local plane: pd < d), given only where the value lies in the window. */
static long range_calls, plane_calls;

static double capsule_range(const void *ctx, const double p[3], double lo, double hi) {
  (void)lo, (void)hi;
  __atomic_fetch_add(&range_calls, 1, __ATOMIC_RELAXED);
  return capsule_dist((const capsule_shape *)ctx, p[0], p[1], p[2]);
}

static int capsule_range_plane(const void *ctx, const double p[3], double lo, double hi, double r,
                               double *d, double *pd, double g[3]) {
  const capsule_shape *c = ctx;
  double ab[3], ap[3], len2 = 0.0, t = 0.0, n = 0.0;
  __atomic_fetch_add(&plane_calls, 1, __ATOMIC_RELAXED);
  *d = capsule_dist(c, p[0], p[1], p[2]);
  if (!(*d >= lo && *d < hi)) return 0;
  for (int k = 0; k < 3; k++) {
    ab[k] = c->b[k] - c->a[k], ap[k] = p[k] - c->a[k];
    len2 += ab[k] * ab[k], t += ab[k] * ap[k];
  }
  t = len2 > 0.0 ? fmin(fmax(t / len2, 0.0), 1.0) : 0.0;
  for (int k = 0; k < 3; k++)
    g[k] = ap[k] - t * ab[k], n += g[k] * g[k];
  if (!(n > 1e-12)) return 0; /* on the axis: no gradient */
  for (int k = 0; k < 3; k++)
    g[k] /= sqrt(n);
  *pd = *d - 0.1 * r;
  return 1;
}

/* range_plane (stock.h): the removal asks it at octant and cube centres and bounds their
 * voxels by the plane, so it calls the range function at fewer voxels; the grid is the
 * same bits as with the range function alone. */
static void range_planes(void) {
  enum { N = 300 };
  static capsule_shape path[N];
  static swarf_stock_cut cuts[N];
  swarf_error err = {0};
  long calls[2], planes[2];
  swarf_stock *s[2] = {new_stock(), new_stock()};
  if (!s[0] || !s[1]) return;
  for (int i = 0; i < N; i++) {
    int row = i / 30, col = i % 30;
    double x0 = 1.0 + 0.25 * (row % 2 ? 30 - col : col), x1 = x0 + (row % 2 ? -0.25 : 0.25);
    capsule_shape c = {{x0, 1.0 + 0.6 * row, 0.1}, {x1, 1.0 + 0.6 * row, -0.4}, 0.7};
    path[i] = c;
    cuts[i] = capsule_cut(&path[i]);
    cuts[i].range = capsule_range;
  }
  for (int k = 0; k < 2; k++) {
    range_calls = plane_calls = 0;
    for (int i = 0; i < N; i++)
      cuts[i].range_plane = k ? capsule_range_plane : NULL;
    for (int i = 0; i < N; i += 64) {
      size_t n = N - i < 64 ? (size_t)(N - i) : 64;
      CHECK(swarf_stock_remove_batch(s[k], cuts + i, n, &err) == 0, "batch: %s", err.message);
    }
    calls[k] = range_calls, planes[k] = plane_calls;
  }
  printf("range_plane: range calls %ld without, %ld with (and %ld range_plane calls)\n", calls[0],
         calls[1], planes[1]);
  CHECK(planes[0] == 0 && planes[1] > 0, "range_plane asked only when given");
  CHECK(calls[1] < 0.8 * (calls[0] - planes[1]), "the planes pass voxels over: %ld vs %ld",
        calls[1], calls[0]);
  CHECK(stock_differences(s[0], s[1]) == 0 && stock_differences(s[1], s[0]) == 0,
        "with range_plane == without (bit-identical)");
  nremoved = 0;
  for (int i = 0; i < N; i++)
    removed[nremoved++] = path[i];
  check_whole_band(s[1], "zig-zag with local planes");
  swarf_stock_free(s[0]);
  swarf_stock_free(s[1]);
  /* measured (the replay reads the planes too): the same effects, cut by cut */
  static swarf_stock_cut_effect fx[2][N];
  swarf_stock *m[2] = {new_stock(), new_stock()};
  if (!m[0] || !m[1]) return;
  for (int k = 0; k < 2; k++) {
    for (int i = 0; i < N; i++)
      cuts[i].range_plane = k ? capsule_range_plane : NULL;
    CHECK(swarf_stock_remove_batch_measured(m[k], cuts, N, NULL, 0.0, fx[k], &err) == 0,
          "measured: %s", err.message);
  }
  int same = stock_differences(m[0], m[1]) == 0;
  for (int i = 0; i < N; i++)
    same = same && fx[0][i].removed == fx[1][i].removed &&
           fx[0][i].removed_voxels == fx[1][i].removed_voxels;
  CHECK(same, "measured with range_plane == without (grid and every cut's volume, bits)");
  swarf_stock_free(m[0]);
  swarf_stock_free(m[1]);
}

typedef struct {
  int calls, stop_at;
  double last;
  int increasing;
} ticks;

static int on_tick(void *user, double done) {
  ticks *t = user;
  if (!(done > t->last && done <= 1.0)) t->increasing = 0;
  t->last = done;
  return ++t->calls == t->stop_at;
}

/* A pass with a tick told after every chunk: the same grid as without one,
 * ticks in increasing order; a tick that answers 1 stops the pass (ABORTED)
 * and leaves a valid stock. */
static void ticks_within_a_pass(void) {
  enum { N = 300 };
  static capsule_shape path[N];
  static swarf_stock_cut cuts[N];
  swarf_error err = {0};
  for (int i = 0; i < N; i++) {
    capsule_shape c = {{1.0 + 0.03 * i, 1.0, 0.3}, {1.0 + 0.03 * i, 7.0, 0.3}, 0.8};
    path[i] = c;
    cuts[i] = capsule_cut(&path[i]);
  }
  swarf_stock *plain = new_stock(), *ticked = new_stock(), *stopped = new_stock();
  if (!plain || !ticked || !stopped) return;
  ticks t = {0, 0, -1.0, 1}, u = {0, 3, -1.0, 1};
  CHECK(swarf_stock_set_tick(ticked, on_tick, &t, -1.0, &err) == SWARF_ERR_ARG, "every < 0");
  CHECK(swarf_stock_set_tick(ticked, on_tick, &t, 0.0, &err) == 0, "%s", err.message);
  CHECK(swarf_stock_set_tick(stopped, on_tick, &u, 0.0, &err) == 0, "%s", err.message);
  CHECK(swarf_stock_remove_batch(plain, cuts, N, &err) == 0, "plain: %s", err.message);
  CHECK(swarf_stock_remove_batch(ticked, cuts, N, &err) == 0, "ticked: %s", err.message);
  printf("ticks: %d in one pass\n", t.calls);
  CHECK(t.calls >= 3 && t.increasing && t.last == 1.0, "%d ticks, increasing to 1 (%g)", t.calls,
        t.last);
  CHECK(stock_differences(plain, ticked) == 0 && stock_differences(ticked, plain) == 0,
        "ticks change nothing (bit-identical)");
  CHECK(swarf_stock_remove_batch(stopped, cuts, N, &err) == SWARF_ERR_ABORTED && u.calls == 3,
        "a tick answering 1 stops the pass");
  check_valid(stopped, "a stopped pass");
  CHECK(stock_differences(plain, stopped) > 0, "a stopped pass is partly done");
  swarf_stock_free(plain);
  swarf_stock_free(ticked);
  swarf_stock_free(stopped);
}

static double nan_sdf(const void *ctx, double x, double y, double z) {
  return NAN;
}

static void bad_arguments(void) {
  swarf_error err = {0};
  swarf_stock *s = new_stock();
  if (!s) return;
  unsigned long long n = swarf_stock_active_voxels(s);
  capsule_shape c = {{1, 1, 0}, {2, 1, 0}, 0.5};
  swarf_stock_cut cut = capsule_cut(&c), bad = cut;
  bad.sdf = NULL;
  CHECK(swarf_stock_remove(NULL, cut.lo, cut.hi, cut.sdf, cut.ctx, &err) == SWARF_ERR_ARG,
        "NULL stock");
  CHECK(swarf_stock_remove(s, NULL, cut.hi, cut.sdf, cut.ctx, &err) == SWARF_ERR_ARG, "NULL lo");
  CHECK(swarf_stock_remove(s, cut.lo, cut.hi, NULL, cut.ctx, &err) == SWARF_ERR_ARG, "NULL sdf");
  CHECK(swarf_stock_remove(s, cut.hi, cut.lo, cut.sdf, cut.ctx, &err) == SWARF_ERR_ARG, "lo > hi");
  bad = cut;
  bad.lo[1] = NAN;
  CHECK(swarf_stock_remove_batch(s, &bad, 1, &err) == SWARF_ERR_ARG, "NaN bound: %s", err.message);
  swarf_stock_cut two[2] = {cut, cut};
  two[1].sdf = NULL;
  CHECK(swarf_stock_remove_batch(s, two, 2, &err) == SWARF_ERR_ARG, "batch with a NULL sdf: %s",
        err.message);
  CHECK(swarf_stock_remove_batch(s, NULL, 3, &err) == SWARF_ERR_ARG, "NULL cuts");
  CHECK(swarf_stock_active_voxels(s) == n, "refused removals change nothing");
  CHECK(swarf_stock_remove(s, cut.lo, cut.hi, nan_sdf, NULL, &err) == 0, "NaN sdf: %s",
        err.message);
  CHECK(swarf_stock_active_voxels(s) == n, "a NaN sdf removes nothing");
  const double far_lo[3] = {100, 100, 100}, far_hi[3] = {101, 101, 101};
  CHECK(swarf_stock_remove(s, far_lo, far_hi, capsule_sdf_cb, &c, &err) == 0, "far away: %s",
        err.message);
  CHECK(swarf_stock_active_voxels(s) == n, "a cut away from the stock changes nothing");
  check_valid(s, "after refused removals");
  swarf_stock_free(s);
}

static void remove_everything(void) {
  swarf_error err = {0};
  swarf_stock *s = new_stock();
  if (!s) return;
  capsule_shape c = {{5, 4, -2.5}, {5, 4, -2.5}, 20.0};
  double lo[3], hi[3];
  capsule_bounds(&c, lo, hi);
  CHECK(swarf_stock_remove(s, lo, hi, capsule_sdf_cb, &c, &err) == 0, "remove all: %s",
        err.message);
  CHECK(swarf_stock_active_voxels(s) == 0, "no active voxels left (%llu)",
        swarf_stock_active_voxels(s));
  CHECK(swarf_stock_volume(s) == 0.0, "no volume left (%g)", swarf_stock_volume(s));
  CHECK(swarf_stock_sample(s, 5, 4, -2.5) == (float)BAND, "all outside");
  swarf_stock_bounds(s, lo, hi);
  CHECK(isnan(lo[0]) && isnan(hi[2]), "bounds of an empty stock are NaN");
  check_valid(s, "everything removed");
  swarf_stock_free(s);
}

int main(void) {
  const double r = 2.0, ball = 4.0 / 3.0 * M_PI * r * r * r;
  ball_case("ball at a corner", 10.0, 8.0, 0.0, r, ball / 8.0);
  ball_case("ball on the top face", 5.0, 4.0, 0.0, r, ball / 2.0);
  /* A cap of height h = r - d when the centre is d above the face. */
  const double d = 0.7, h = r - d;
  ball_case("cap on the top face", 4.03, 3.97, d, r, M_PI * h * h * (3.0 * r - h) / 3.0);
  ball_case("ball on a side face", 0.0, 4.0, -2.5, r, ball / 2.0);
  deep_cavity();
  random_removals();
  order_independence();
  batch_equals_single();
  range_planes();
  ticks_within_a_pass();
  bad_arguments();
  remove_everything();
  return check_done();
}
