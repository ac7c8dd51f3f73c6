/* SPDX-License-Identifier: MPL-2.0 */
/* test_stockio.c -- stocks from files and placed for a setup (stock.h).
 *
 *  - an STL box (binary and ASCII) = the box stock of the same corners, voxel by
 *    voxel (<= 0.01 voxel), corners off the voxel lattice;
 *  - an STL box placed by a rotation that is not a quarter turn = the exact
 *    distance of the rotated box (<= 0.01 voxel);
 *  - a stock placed by rx=180, tz=-25 (quarter turns, any translation) = the box
 *    stock of the analytic image (bit for bit); by rz=30 = the rotated box's exact
 *    distance (errors printed; volume to the analytic);
 *  - the levels of swarf's band at any voxel size (checkLevelSet's background test,
 *    which 0.3 mm failed in float);
 *  - a .vdb read back as a stock is the stock bit for bit; at another voxel it is
 *    resampled (volume; values on the faces);
 *  - bad input: open, non-manifold, flipped, empty STLs, a missing file, garbage,
 *    bad placements: the status and the words of the message.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "shapes.h"
#include "stl_box.h"

/* Largest |a - b| (mm) over the active voxels of a, b read at a's voxel centres. */
typedef struct {
  const swarf_stock *other;
  double max;
  unsigned long long n;
} diff_acc;

static void diff_visit(void *ctx, const double c[3], float v) {
  diff_acc *d = ctx;
  double centre[3], o = swarf_stock_voxel_value(d->other, c[0], c[1], c[2], centre);
  d->max = fmax(d->max, fabs(o - v));
  d->n++;
}

static double max_diff(const swarf_stock *a, const swarf_stock *b) {
  diff_acc d = {b, 0.0, 0};
  swarf_stock_visit_active(a, diff_visit, &d);
  diff_acc e = {a, 0.0, 0};
  swarf_stock_visit_active(b, diff_visit, &e);
  return fmax(d.max, e.max);
}

/* The exact distance of the box `b` placed by x' = R x + t, R = Rz(deg). */
typedef struct {
  box_shape b;
  double c, s, t[3];
  double max, bandw;
  unsigned long long n;
} rotated_box;

static double rotated_sdf(const rotated_box *r, const double p[3]) {
  double q[3] = {p[0] - r->t[0], p[1] - r->t[1], p[2] - r->t[2]}, x[3];
  x[0] = r->c * q[0] + r->s * q[1];
  x[1] = -r->s * q[0] + r->c * q[1];
  x[2] = q[2];
  return box_sdf(&r->b, x);
}

static void rotated_visit(void *ctx, const double c[3], float v) {
  rotated_box *r = ctx;
  double e = rotated_sdf(r, c);
  if (fabs(e) >= r->bandw) return; /* beyond the band the grid holds +-band */
  r->max = fmax(r->max, fabs(e - v));
  r->n++;
}

static void test_stl_box(void) {
  const double lo[3] = {0.13, -0.41, -5.07}, hi[3] = {10.37, 7.93, 0.21}, v = 0.2;
  swarf_stock *box = test_box_(lo, hi, v, 3);
  CHECK(box != NULL, "box");
  for (int ascii = 0; ascii < 2; ascii++) {
    swarf_stock *s = NULL;
    swarf_error err;
    CHECK(stl_box_write("stockio_box.stl", lo, hi, ascii, STL_GOOD) == 0, "write");
    swarf_status st = swarf_stock_read_stl("stockio_box.stl", NULL, v, 3, &s, &err);
    CHECK(st == SWARF_OK && s != NULL, "read %s STL: %s", ascii ? "ASCII" : "binary", err.message);
    if (s == NULL) continue;
    double d = max_diff(box, s) / v;
    printf("STL box (%s) vs box stock: max %.2e voxel, active %llu / %llu\n",
           ascii ? "ASCII" : "binary", d, swarf_stock_active_voxels(s),
           swarf_stock_active_voxels(box));
    CHECK(d <= 0.01, "STL stock = box stock: %.3g voxel", d);
    CHECK(swarf_stock_active_voxels(s) == swarf_stock_active_voxels(box), "same band");
    CHECK(swarf_stock_check(s, &err) == SWARF_OK, "valid level set: %s", err.message);
    swarf_stock_free(s);
  }
  swarf_stock_free(box);
}

static void test_stl_placed(void) {
  const double lo[3] = {0, 0, -3}, hi[3] = {10, 6, 0}, v = 0.1;
  swarf_stock_placement p;
  swarf_stock *s = NULL;
  swarf_error err;
  CHECK(swarf_stock_placement_parse("rz=30,tx=5,ty=-2.5", &p, &err) == SWARF_OK, "%s", err.message);
  CHECK(stl_box_write("stockio_box.stl", lo, hi, 0, STL_GOOD) == 0, "write");
  CHECK(swarf_stock_read_stl("stockio_box.stl", &p, v, 3, &s, &err) == SWARF_OK, "%s", err.message);
  if (s == NULL) return;
  rotated_box r = {
      {{0, 0, -3}, {10, 6, 0}}, cos(M_PI / 6), sin(M_PI / 6), {5, -2.5, 0}, 0, 3 * v, 0};
  swarf_stock_visit_active(s, rotated_visit, &r);
  printf("STL box placed rz=30: max %.2e voxel over %llu voxels, volume %.4f (180)\n", r.max / v,
         r.n, swarf_stock_volume(s));
  CHECK(r.max / v <= 0.01, "placed STL = the rotated box's distance: %.3g voxel", r.max / v);
  CHECK(fabs(swarf_stock_volume(s) - 180.0) < 0.002 * 180.0, "volume %.4f", swarf_stock_volume(s));
  swarf_stock_free(s);
}

static void test_place(void) {
  const double lo[3] = {0, 0, -5}, hi[3] = {10, 8, 0}, v = 0.2;
  swarf_error err;
  swarf_stock_placement p;
  swarf_stock *s = test_box_(lo, hi, v, 3), *t = NULL;
  capsule_shape c = {{2, 2, 0.5}, {7, 3, -1}, 1.2};
  swarf_stock_cut cut = capsule_cut(&c);
  CHECK(swarf_stock_remove_batch(s, &cut, 1, NULL) == SWARF_OK, "call failed");
  /* Quarter turns: rx=180 maps (x, y, z) to (x, -y, -z), then tz=-25. */
  CHECK(swarf_stock_placement_parse("rx=180,tz=-25", &p, &err) == SWARF_OK, "%s", err.message);
  CHECK(swarf_stock_place(s, &p, &t, &err) == SWARF_OK, "place: %s", err.message);
  if (t != NULL) {
    const double elo[3] = {0, -8, -25}, ehi[3] = {10, 0, -20};
    swarf_stock *e = test_box_(elo, ehi, v, 3);
    capsule_shape ec = {{2, -2, -25.5}, {7, -3, -24}, 1.2};
    swarf_stock_cut ecut = capsule_cut(&ec);
    CHECK(swarf_stock_remove_batch(e, &ecut, 1, NULL) == SWARF_OK, "call failed");
    double d = max_diff(e, t);
    printf("placed rx=180,tz=-25 vs the analytic image: max %.2e mm\n", d);
    CHECK(d <= 1e-6, "quarter-turn placement exact: %.3g mm", d);
    CHECK(fabs(swarf_stock_volume(t) - swarf_stock_volume(s)) <= 1e-9 * swarf_stock_volume(s),
          "volume kept");
    swarf_stock_free(e);
    swarf_stock_free(t);
    t = NULL;
  }
  /* Any rotation: rz=30 about the origin, then tx=5. */
  swarf_stock *b = test_box_(lo, hi, v, 3);
  CHECK(swarf_stock_placement_parse("tx=5,rz=30", &p, &err) == SWARF_OK, "%s", err.message);
  CHECK(swarf_stock_place(b, &p, &t, &err) == SWARF_OK, "place: %s", err.message);
  if (t != NULL) {
    rotated_box r = {
        {{0, 0, -5}, {10, 8, 0}}, cos(M_PI / 6), sin(M_PI / 6), {5, 0, 0}, 0, 3 * v, 0};
    swarf_stock_visit_active(t, rotated_visit, &r);
    printf("placed rz=30 (resampled): max %.3f voxel over %llu voxels, volume %.3f (400)\n",
           r.max / v, r.n, swarf_stock_volume(t));
    CHECK(r.max / v <= 0.3, "resampled placement within 0.3 voxel: %.3f", r.max / v);
    CHECK(fabs(swarf_stock_volume(t) - 400.0) <= 0.002 * 400.0, "volume %.3f",
          swarf_stock_volume(t));
    CHECK(swarf_stock_check(t, &err) == SWARF_OK, "valid level set: %s", err.message);
    swarf_stock_free(t);
  }
  swarf_stock_free(b);
  swarf_stock_free(s);
}

static void test_band_background(void) {
  const double lo[3] = {0, 0, -1}, hi[3] = {2, 2, 0};
  int bad = 0;
  for (int i = 1; i <= 200; i++) {
    double v = 0.005 * i; /* 0.005 .. 1 mm, 0.3 among them */
    swarf_stock *s = test_box_(lo, hi, v, 3);
    swarf_error err;
    if (s == NULL || swarf_stock_check(s, &err) != SWARF_OK) {
      if (bad++ < 3) fprintf(stderr, "voxel %g: %s\n", v, s ? err.message : "no stock");
    }
    swarf_stock_free(s);
  }
  CHECK(bad == 0, "%d of 200 voxel sizes give an invalid level set", bad);
}

static void test_vdb(void) {
  const double lo[3] = {0, 0, -4}, hi[3] = {6, 5, 0};
  swarf_error err;
  swarf_stock *s = test_box_(lo, hi, 0.2, 3), *r = NULL;
  capsule_shape c = {{1, 1, 0.2}, {5, 4, -1.5}, 1.0};
  swarf_stock_cut cut = capsule_cut(&c);
  CHECK(swarf_stock_remove_batch(s, &cut, 1, NULL) == SWARF_OK, "call failed");
  CHECK(swarf_stock_write_vdb(s, "stockio.vdb", NULL) == SWARF_OK, "call failed");
  CHECK(swarf_stock_read_vdb("stockio.vdb", NULL, 0.0, 0, &r, &err) == SWARF_OK, "%s", err.message);
  if (r) CHECK(stock_differences(s, r) == 0, "a .vdb stock is the stock bit for bit");
  swarf_stock_free(r);
  r = NULL;
  CHECK(swarf_stock_read_vdb("stockio.vdb", NULL, 0.2, 0, &r, &err) == SWARF_OK, "%s", err.message);
  if (r) CHECK(stock_differences(s, r) == 0, "--voxel equal to the file's: used as it is");
  swarf_stock_free(r);
  r = NULL;
  CHECK(swarf_stock_read_vdb("stockio.vdb", NULL, 0.1, 0, &r, &err) == SWARF_OK, "%s", err.message);
  if (r) {
    double a = swarf_stock_volume(s), b = swarf_stock_volume(r);
    printf("resampled at 0.1 mm: volume %.3f (was %.3f at 0.2 mm)\n", b, a);
    CHECK(swarf_stock_voxel(r) == 0.1, "voxel %g", swarf_stock_voxel(r));
    CHECK(fabs(a - b) < 0.01 * a, "resampled volume %.3f vs %.3f", b, a);
    CHECK(fabs(swarf_stock_sample(r, 3.0, 4.85, -2.0) - (-0.15)) < 1e-6,
          "a face's distance kept: %.6f", swarf_stock_sample(r, 3.0, 4.85, -2.0));
    CHECK(swarf_stock_check(r, &err) == SWARF_OK, "valid: %s", err.message);
  }
  swarf_stock_free(r);
  swarf_stock_free(s);
}

/* A bad input: the status and a word of the message as the user reads it
 * (FILE: message: the error names the file once). */
static void expect_bad(swarf_status got, swarf_status want, const swarf_error *e, const char *words,
                       const char *what) {
  char msg[1024];
  swarf_error_format(e, msg, sizeof msg);
  CHECK(got == want, "%s: status %d, want %d (%s)", what, (int)got, (int)want, msg);
  CHECK(strstr(msg, words) != NULL, "%s: message \"%s\" lacks \"%s\"", what, msg, words);
}

static void test_bad_input(void) {
  const double lo[3] = {0, 0, -2}, hi[3] = {4, 3, 0};
  swarf_stock *s = NULL;
  swarf_error err;
  swarf_stock_placement p;
  static const struct {
    int how;
    const char *words;
  } cases[] = {{STL_OPEN, "not closed"},
               {STL_NONMANIFOLD, "not manifold"},
               {STL_FLIPPED, "not consistently oriented"}};
  for (int ascii = 0; ascii < 2; ascii++)
    for (int i = 0; i < 3; i++) {
      stl_box_write("stockio_bad.stl", lo, hi, ascii, cases[i].how);
      swarf_status st = swarf_stock_read_stl("stockio_bad.stl", NULL, 0.2, 3, &s, &err);
      expect_bad(st, SWARF_ERR_FORMAT, &err, cases[i].words, cases[i].words);
      CHECK(s == NULL, "no stock");
      CHECK(!strcmp(err.file, "stockio_bad.stl") && strstr(err.message, "stockio_bad") == NULL,
            "the file is named once: %s: %s", err.file, err.message);
    }
  FILE *f = fopen("stockio_empty.stl", "wb");
  unsigned char head[84] = {0};
  fwrite(head, 1, 84, f), fclose(f);
  expect_bad(swarf_stock_read_stl("stockio_empty.stl", NULL, 0.2, 3, &s, &err), SWARF_ERR_FORMAT,
             &err, "no triangles", "empty binary STL");
  f = fopen("stockio_empty.stl", "wb");
  fputs("solid nothing\nendsolid nothing\n", f), fclose(f);
  expect_bad(swarf_stock_read_stl("stockio_empty.stl", NULL, 0.2, 3, &s, &err), SWARF_ERR_FORMAT,
             &err, "no triangles", "empty ASCII STL");
  f = fopen("stockio_empty.stl", "wb");
  fclose(f);
  expect_bad(swarf_stock_read_stl("stockio_empty.stl", NULL, 0.2, 3, &s, &err), SWARF_ERR_FORMAT,
             &err, "not an STL", "empty file");
  f = fopen("stockio_empty.stl", "wb");
  fputs("solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 nan\n", f), fclose(f);
  expect_bad(swarf_stock_read_stl("stockio_empty.stl", NULL, 0.2, 3, &s, &err), SWARF_ERR_FORMAT,
             &err, "stockio_empty.stl:4:", "ASCII error at its line");
  expect_bad(swarf_stock_read_stl("stockio_none.stl", NULL, 0.2, 3, &s, &err), SWARF_ERR_OPEN, &err,
             "cannot open", "missing STL");
  expect_bad(swarf_stock_read_vdb("stockio_none.vdb", NULL, 0, 0, &s, &err), SWARF_ERR_OPEN, &err,
             "cannot open", "missing .vdb");
  expect_bad(swarf_stock_read_vdb("stockio_empty.stl", NULL, 0, 0, &s, &err), SWARF_ERR_FORMAT,
             &err, "stockio_empty.stl", "not a .vdb");
  static const char *bad_places[] = {
      "", "tx=1,tx=2", "tq=1", "tx=", "tx=1,", "rx=nan", "ty=1e999", "tx=1;ty=2"};
  for (size_t i = 0; i < sizeof bad_places / sizeof bad_places[0]; i++)
    CHECK(swarf_stock_placement_parse(bad_places[i], &p, &err) == SWARF_ERR_ARG,
          "placement \"%s\" refused", bad_places[i]);
  CHECK(swarf_stock_placement_parse("rz=-90,ty=3.5", &p, &err) == SWARF_OK && p.r[2] == -90 &&
            p.t[1] == 3.5,
        "placement parsed");
}

int main(void) {
  test_stl_box();
  test_stl_placed();
  test_place();
  test_band_background();
  test_vdb();
  test_bad_input();
  return check_done();
}
