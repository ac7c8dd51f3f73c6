/* SPDX-License-Identifier: MPL-2.0 */
/* test_png.c -- the rendered picture is a valid PNG showing the stock.
 *
 * The file is decoded here independently: signature, chunk CRCs (zlib crc32),
 * IHDR (size, 8-bit RGB), IDAT inflated with zlib's uncompress, filter byte 0
 * on every row. The stock must be visible: the centre pixel (on the stock)
 * differs from the corner pixel (background), and the image has many colours.
 * Leaves stock_png_slot.png (a box with a pocket and a slot) to look at.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <zlib.h>

#include "check.h"
#include "shapes.h"

static uint32_t be32(const unsigned char *p) {
  return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* Decode an 8-bit RGB, filter-0 PNG into *rgb; returns 0 on success. */
static int decode_png(const char *path, unsigned *w, unsigned *h, unsigned char **rgb) {
  FILE *f = fopen(path, "rb");
  static unsigned char buf[1 << 24];
  size_t len = f ? fread(buf, 1, sizeof buf, f) : 0, pos = 8, zlen = 0;
  unsigned char *z = malloc(len);
  if (f) fclose(f);
  *rgb = NULL;
  CHECK(len > 8 && memcmp(buf, "\x89PNG\r\n\x1a\n", 8) == 0, "%s: PNG signature", path);
  while (pos + 12 <= len) {
    uint32_t n = be32(buf + pos);
    const unsigned char *type = buf + pos + 4;
    if (pos + 12 + n > len) break;
    uLong crc = crc32(crc32(0, Z_NULL, 0), type, n + 4);
    CHECK(crc == be32(buf + pos + 8 + n), "%s: CRC of chunk %.4s", path, type);
    if (!memcmp(type, "IHDR", 4)) {
      *w = be32(type + 4);
      *h = be32(type + 8);
      CHECK(type[12] == 8 && type[13] == 2 && type[16] == 0, "%s: 8-bit RGB, no interlace", path);
    } else if (!memcmp(type, "IDAT", 4)) {
      memcpy(z + zlen, type + 4, n);
      zlen += n;
    } else if (!memcmp(type, "IEND", 4)) {
      break;
    }
    pos += 12 + n;
  }
  uLongf raw_len = (uLongf)(*w * 3 + 1) * *h;
  unsigned char *raw = malloc(raw_len ? raw_len : 1);
  int rc = uncompress(raw, &raw_len, z, zlen);
  free(z);
  CHECK(rc == Z_OK && raw_len == (uLongf)(*w * 3 + 1) * *h, "%s: IDAT inflates to the image", path);
  if (rc != Z_OK) return free(raw), -1;
  *rgb = malloc((size_t)*w * *h * 3);
  for (unsigned y = 0; y < *h; y++) {
    CHECK(raw[y * (*w * 3 + 1)] == 0, "row %u filter 0", y);
    memcpy(*rgb + (size_t)y * *w * 3, raw + y * (*w * 3 + 1) + 1, (size_t)*w * 3);
  }
  free(raw);
  return 0;
}

static long count_colours(const unsigned char *rgb, size_t npix) {
  static unsigned char seen[1 << 18];
  long n = 0;
  memset(seen, 0, sizeof seen);
  for (size_t i = 0; i < npix; i++) {
    unsigned key = (rgb[3 * i] >> 2) << 12 | (rgb[3 * i + 1] >> 2) << 6 | rgb[3 * i + 2] >> 2;
    if (!seen[key]) seen[key] = 1, n++;
  }
  return n;
}

static void render_case(const swarf_stock *s, const char *path, unsigned w, unsigned h) {
  swarf_error err = {0};
  struct timespec t0, t1;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  int rc = swarf_stock_write_png(s, path, (int)w, (int)h, &err);
  clock_gettime(CLOCK_MONOTONIC, &t1);
  CHECK(rc == 0, "render %s: %s", path, err.message);
  printf("%s: %ux%u rendered in %.3f s\n", path, w, h,
         (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
  unsigned gw = 0, gh = 0;
  unsigned char *rgb;
  if (decode_png(path, &gw, &gh, &rgb) != 0) return;
  CHECK(gw == w && gh == h, "%s: IHDR size %ux%u", path, gw, gh);
  const unsigned char *centre = rgb + 3 * ((size_t)(h / 2) * w + w / 2), *corner = rgb;
  CHECK(memcmp(centre, corner, 3) != 0, "%s: centre (%d,%d,%d) differs from the background corner",
        path, centre[0], centre[1], centre[2]);
  long colours = count_colours(rgb, (size_t)w * h);
  printf("%s: %ld distinct colours\n", path, colours);
  CHECK(colours > 50, "%s: shaded picture, %ld colours", path, colours);
  free(rgb);
}

int main(void) {
  swarf_error err = {0};
  const double lo[3] = {0, 0, -20}, hi[3] = {80, 60, 0};
  swarf_stock *s = NULL;
  swarf_stock_new_box(lo, hi, 0.2, 3, &s, &err);
  CHECK(s != NULL, "new_box: %s", err.message);
  if (!s) return check_done();
  /* A pocket (a 6 mm ball end mill cleared 20 x 15 mm at 5 mm depth) and a slot. */
  static capsule_shape cuts_s[64];
  swarf_stock_cut cuts[64];
  int n = 0;
  for (double y = 15.0; y <= 30.0 && n < 60; y += 2.5) {
    capsule_shape c = {{15.0, y, -2.0}, {35.0, y, -2.0}, 3.0};
    cuts_s[n] = c;
    cuts[n] = capsule_cut(&cuts_s[n]);
    n++;
  }
  capsule_shape slot = {{50.0, 10.0, 1.0}, {70.0, 50.0, 1.0}, 2.0};
  cuts_s[n] = slot;
  cuts[n] = capsule_cut(&cuts_s[n]);
  n++;
  CHECK(swarf_stock_remove_batch(s, cuts, (size_t)n, &err) == 0, "cuts: %s", err.message);
  render_case(s, "stock_png_slot.png", 800, 600);
  render_case(s, "stock_png_small.png", 64, 48);
  CHECK(swarf_stock_write_png(s, "x.png", 0, 10, &err) == SWARF_ERR_ARG, "zero width");
  CHECK(swarf_stock_write_png(s, "x.png", 10, -1, &err) == SWARF_ERR_ARG, "negative height");
  CHECK(swarf_stock_write_png(s, "stock_png_no_dir/x.png", 10, 10, &err) == SWARF_ERR_IO,
        "missing directory: %s", err.message);
  CHECK(swarf_stock_write_png(NULL, "x.png", 10, 10, &err) == SWARF_ERR_ARG, "NULL stock");
  swarf_stock_free(s);
  return check_done();
}
