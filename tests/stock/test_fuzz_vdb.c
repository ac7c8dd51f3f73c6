/* SPDX-License-Identifier: MPL-2.0 */
/* test_fuzz_vdb.c -- reading damaged .vdb files never crashes.
 *
 * A valid file is written, then 200 damaged copies (deterministic seed):
 * random byte flips (anywhere or in the first 256 bytes: header, metadata,
 * transform, tree topology), truncations, and both. Each must be refused
 * with a message or give a stock that works (queries, check, a cut, a
 * write); never a crash. Run it under ASan/UBSan (-DSWARF_SANITIZE=ON) too.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "shapes.h"

#define COPIES 200

static unsigned long long rng = 0x9e3779b97f4a7c15ULL;

static unsigned next_rand(void) { /* xorshift64*, fixed seed */
  rng ^= rng >> 12;
  rng ^= rng << 25;
  rng ^= rng >> 27;
  return (unsigned)((rng * 2685821657736338717ULL) >> 33);
}

static unsigned char *load(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  unsigned char *buf = malloc(1 << 22);
  *len = f ? fread(buf, 1, 1 << 22, f) : 0;
  if (f) fclose(f);
  return buf;
}

static void save(const char *path, const unsigned char *data, size_t len) {
  FILE *f = fopen(path, "wb");
  if (f) fwrite(data, 1, len, f), fclose(f);
}

/* A damaged copy of data into out; returns its length. */
static size_t damage(const unsigned char *data, size_t len, unsigned char *out, int i) {
  size_t n = len;
  memcpy(out, data, len);
  int mode = i % 4;
  if (mode == 0 || mode == 3) {
    int flips = 1 + (int)(next_rand() % 8);
    for (int k = 0; k < flips; k++)
      out[next_rand() % len] ^= (unsigned char)(1 + next_rand() % 255);
  }
  if (mode == 1) {
    int flips = 1 + (int)(next_rand() % 4);
    for (int k = 0; k < flips; k++)
      out[next_rand() % (len < 256 ? len : 256)] ^= (unsigned char)(1 + next_rand() % 255);
  }
  if (mode == 2 || mode == 3) n = next_rand() % len;
  return n;
}

/* Use a stock read from a damaged file as the simulator would. */
static void exercise(swarf_stock *s) {
  swarf_error err = {0};
  double lo[3], hi[3];
  (void)swarf_stock_active_voxels(s);
  (void)swarf_stock_volume(s);
  swarf_stock_bounds(s, lo, hi);
  (void)swarf_stock_check(s, &err);
  capsule_shape c = {{1.0, 1.0, 0.0}, {3.0, 2.0, 0.0}, 0.8};
  swarf_stock_cut cut = capsule_cut(&c);
  (void)swarf_stock_remove_batch(s, &cut, 1, &err);
  (void)swarf_stock_write_vdb(s, "stock_fuzz_out.vdb", &err);
}

int main(void) {
  swarf_error err = {0};
  const double lo[3] = {0, 0, -2}, hi[3] = {4, 3, 0};
  swarf_stock *s = NULL;
  swarf_stock_new_box(lo, hi, 0.2, 3, &s, &err);
  capsule_shape c = {{0.5, 1.5, 0.3}, {3.5, 1.5, 0.3}, 0.7};
  swarf_stock_cut cut = capsule_cut(&c);
  CHECK(s && swarf_stock_remove_batch(s, &cut, 1, &err) == 0, "setup: %s", err.message);
  CHECK(s && swarf_stock_write_vdb(s, "stock_fuzz_good.vdb", &err) == 0, "write: %s", err.message);
  swarf_stock_free(s);
  size_t len;
  unsigned char *good = load("stock_fuzz_good.vdb", &len), *bad = malloc(len + 1);
  CHECK(len > 256, "valid file of %zu bytes", len);
  if (len <= 256) return check_done();
  int refused = 0, accepted = 0;
  for (int i = 0; i < COPIES; i++) {
    size_t n = damage(good, len, bad, i);
    save("stock_fuzz_bad.vdb", bad, n);
    err.message[0] = '\0';
    swarf_stock *r = NULL;
    swarf_stock_read("stock_fuzz_bad.vdb", &r, &err);
    if (r == NULL) {
      refused++;
      CHECK(err.message[0] != '\0', "copy %d refused without a message", i);
      if (i < 8) printf("  copy %3d (%zu bytes): %s\n", i, n, err.message);
    } else {
      accepted++;
      exercise(r);
      swarf_stock_free(r);
    }
  }
  printf("%d damaged copies: %d refused, %d read (and used)\n", COPIES, refused, accepted);
  CHECK(refused + accepted == COPIES, "all copies handled");
  CHECK(refused > COPIES / 4, "damage is detected (%d refused)", refused);
  free(good);
  free(bad);
  return check_done();
}
