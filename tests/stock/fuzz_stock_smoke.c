/* SPDX-License-Identifier: MPL-2.0 */
/* fuzz_stock_smoke.c -- a plain driver for the stock fuzz entry (fuzz_stock.cc),
 * no libFuzzer needed: it builds seeds (binary and ASCII STL boxes, damaged
 * ones, a .vdb swarf wrote, under each of the placement/resampling choices,
 * placement strings, a design's triangle file and a band file), runs the
 * entry on each, then on deterministic mutations of them (byte flips, truncations, insertions,
 * splices) until `-n` inputs or `-t` seconds. A breach of the entry's checks aborts (and ASan/UBSan
 * builds catch memory errors). Usage: fuzz_stock_smoke [-n N] [-t SECONDS] [-w DIR]
 * -w writes the seeds into DIR as files (seed-N) and stops: the libFuzzer
 * target's seeds in tests/stock/fuzz_stock_seeds were made so.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "shapes.h"
#include "stl_box.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static uint64_t rng = 0x9E3779B97F4A7C15ull;
static unsigned next(void) {
  rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
  return (unsigned)(rng >> 32);
}

typedef struct {
  uint8_t *data;
  size_t size;
} blob;

static blob seeds[64];
static int nseeds;

/* A seed: the mode byte, then the bytes of `path` (or `text`). */
static void add_file(uint8_t mode, int how, const char *path) {
  FILE *f = fopen(path, "rb");
  blob b;
  long n;
  if (f == NULL) return;
  fseek(f, 0, SEEK_END);
  n = ftell(f);
  fseek(f, 0, SEEK_SET);
  b.data = malloc((size_t)n + 2);
  b.data[0] = mode;
  b.size = 1;
  if (how >= 0) b.data[b.size++] = (uint8_t)how;
  b.size += fread(b.data + b.size, 1, (size_t)n, f);
  fclose(f);
  seeds[nseeds++] = b;
}

static void add_text(const char *text) {
  blob b;
  b.size = 1 + strlen(text);
  b.data = malloc(b.size);
  b.data[0] = 2;
  memcpy(b.data + 1, text, b.size - 1);
  seeds[nseeds++] = b;
}

static void make_seeds(void) {
  const double lo[3] = {-1, -1.5, -2}, hi[3] = {2.3, 1.7, 0.4};
  for (int ascii = 0; ascii < 2; ascii++)
    for (int how = STL_GOOD; how <= STL_FLIPPED; how++) {
      stl_box_write("stock_fuzz_seed.stl", lo, hi, ascii, how);
      add_file(0, -1, "stock_fuzz_seed.stl");
    }
  swarf_stock *s = test_box_(lo, hi, 0.25, 3);
  capsule_shape c = {{-0.5, 0, 0.4}, {1.5, 1, -0.5}, 0.6};
  swarf_stock_cut cut = capsule_cut(&c);
  swarf_stock_remove_batch(s, &cut, 1, NULL);
  swarf_stock_write_vdb(s, "stock_fuzz_seed.vdb", NULL);
  swarf_stock_write_band(s, "stock_fuzz_seed.band", NULL);
  swarf_stock_free(s);
  for (int how = 0; how < 8; how += 3)
    add_file(1, how, "stock_fuzz_seed.vdb");
  add_text("tx=1,ty=-2.5,tz=3,rx=180,ry=0,rz=90");
  add_text("rz=30");
  add_text("tx=1e308,rx=nan");
  /* 3: a design's triangles in search order (the design cache's .tri) */
  swarf_stock *d = NULL;
  stl_box_write("stock_fuzz_seed.stl", lo, hi, 0, STL_GOOD);
  if (swarf_stock_read_design("stock_fuzz_seed.stl", 0.1, &d, NULL) == SWARF_OK &&
      swarf_stock_design_surface_save(d, "stock_fuzz_seed.tri", NULL) == SWARF_OK)
    add_file(3, -1, "stock_fuzz_seed.tri");
  swarf_stock_free(d);
  /* 4: the band file of the cut box (the design cache's .band) */
  add_file(4, -1, "stock_fuzz_seed.band");
}

static size_t mutate(const blob *b, uint8_t *out, size_t cap) {
  size_t n = b->size < cap ? b->size : cap;
  memcpy(out, b->data, n);
  switch (next() % 4) {
  case 0: /* flips, the mode byte kept */
    for (int k = 1 + (int)(next() % 8); k > 0 && n > 1; k--)
      out[1 + next() % (n - 1)] ^= (uint8_t)(1 + next() % 255);
    break;
  case 1: /* truncation */
    if (n > 2) n = 2 + next() % (n - 2);
    break;
  case 2: /* insertion of random bytes */
    if (n + 16 < cap && n > 1) {
      size_t at = 1 + next() % (n - 1), k = 1 + next() % 16;
      memmove(out + at + k, out + at, n - at);
      for (size_t i = 0; i < k; i++)
        out[at + i] = (uint8_t)next();
      n += k;
    }
    break;
  default: /* splice with another seed of the same mode */
    for (int tries = 0; tries < 8; tries++) {
      const blob *o = &seeds[next() % nseeds];
      if (o->data[0] != b->data[0] || o->size < 2 || n < 2) continue;
      size_t at = 1 + next() % (n - 1), from = 1 + next() % (o->size - 1), k = o->size - from;
      if (at + k > cap) k = cap - at;
      memcpy(out + at, o->data + from, k);
      n = at + k;
      break;
    }
  }
  return n;
}

/* -w DIR: every seed as DIR/seed-N; 0 or 1 (a file not written). */
static int write_seeds(const char *dir) {
  char path[4096];
  for (int i = 0; i < nseeds; i++) {
    FILE *f;
    snprintf(path, sizeof path, "%s/seed-%02d", dir, i);
    if ((f = fopen(path, "wb")) == NULL ||
        fwrite(seeds[i].data, 1, seeds[i].size, f) != seeds[i].size) {
      fprintf(stderr, "fuzz_stock_smoke: cannot write %s\n", path);
      return 1;
    }
    fclose(f);
  }
  return 0;
}

int main(int argc, char **argv) {
  long limit = 100000;
  double seconds = 10;
  const char *seed_dir = NULL;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!strcmp(argv[i], "-n")) limit = atol(argv[i + 1]);
    if (!strcmp(argv[i], "-t")) seconds = atof(argv[i + 1]);
    if (!strcmp(argv[i], "-w")) seed_dir = argv[i + 1];
  }
  make_seeds();
  if (seed_dir) return write_seeds(seed_dir);
  clock_t start = clock();
  time_t wall = time(NULL);
  long runs = 0, per_mode[5] = {0, 0, 0, 0, 0};
  for (int i = 0; i < nseeds; i++, runs++)
    LLVMFuzzerTestOneInput(seeds[i].data, seeds[i].size);
  size_t cap = 0;
  for (int i = 0; i < nseeds; i++)
    cap = seeds[i].size > cap ? seeds[i].size : cap;
  cap += 64;
  uint8_t *buf = malloc(cap);
  while (runs < limit && difftime(time(NULL), wall) < seconds) {
    const blob *b = &seeds[next() % nseeds];
    size_t n = mutate(b, buf, cap);
    LLVMFuzzerTestOneInput(buf, n);
    per_mode[b->data[0] % 5]++;
    runs++;
  }
  printf("fuzz_stock_smoke: %ld inputs (%d seeds; mutations: %ld STL, %ld vdb, %ld placement, "
         "%ld triangle file, %ld band file) in %.1f s CPU\n",
         runs, nseeds, per_mode[0], per_mode[1], per_mode[2], per_mode[3], per_mode[4],
         (double)(clock() - start) / CLOCKS_PER_SEC);
  free(buf);
  for (int i = 0; i < nseeds; i++)
    free(seeds[i].data);
  return 0;
}
