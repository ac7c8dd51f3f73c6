/* SPDX-License-Identifier: MPL-2.0 */
/* fuzz_smoke.c -- a plain driver for the fuzz entry (no libFuzzer needed).
 *
 * Usage: fuzz_smoke [-n mutations] [-t seconds] [-k] [-o optional-dir]... <dir-or-file>...
 * Runs LLVMFuzzerTestOneInput (fuzz_gcode.c) on every seed file, then on
 * `mutations` inputs made from random windows of the seeds by byte flips,
 * insertions of G-code fragments, deletions and splices, with a fixed seed
 * so every run is the same; stops early after `seconds`. A window keeps its
 * seed's head: the first line when the seed starts with ';' (the dialect
 * line of fuzz_gcode.c: ";fanuc", ";haas", ";grbl"), and with -k the first
 * byte (the reader selector of fuzz_inputs.c). A breach of the entry's
 * checks aborts; a missing seed folder fails, but for one given with -o (the
 * corpus in ../shared, which a plain clone does not have).
 */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define WINDOW_MAX 4096
#define MAX_SEEDS 256

typedef struct {
  unsigned char *data;
  size_t size;
} seed;

static seed seeds[MAX_SEEDS];
static int nseeds;
static uint64_t rng = 0x9E3779B97F4A7C15ull;

static uint32_t next_random(void) {
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return (uint32_t)(rng >> 11);
}

static int load_file(const char *path) {
  FILE *in = fopen(path, "rb");
  long size;
  if (in == NULL || nseeds == MAX_SEEDS) {
    if (in) fclose(in);
    return in != NULL;
  }
  fseek(in, 0, SEEK_END);
  size = ftell(in);
  fseek(in, 0, SEEK_SET);
  seeds[nseeds].data = malloc(size > 0 ? (size_t)size : 1);
  seeds[nseeds].size = fread(seeds[nseeds].data, 1, size > 0 ? (size_t)size : 0, in);
  fclose(in);
  nseeds++;
  return 1;
}

static int load_path(const char *path) {
  struct stat st;
  DIR *d;
  struct dirent *e;
  char sub[4096];
  if (stat(path, &st) != 0) return 0;
  if (!S_ISDIR(st.st_mode)) return load_file(path);
  if ((d = opendir(path)) == NULL) return 0;
  while ((e = readdir(d)) != NULL) {
    snprintf(sub, sizeof sub, "%s/%s", path, e->d_name);
    if (e->d_name[0] != '.' && stat(sub, &st) == 0 && S_ISREG(st.st_mode)) load_file(sub);
  }
  closedir(d);
  return 1;
}

static const char *fragments[] = {
    "G2",   "G3",         "G17",   "G18",    "G19",    "G20",  "G21",  "G91",    "G90.1",  "R-",
    "R",    "I",          "J",     "K",      "P3",     "X",    "Y",    "Z",      "A",      "F0",
    "F100", "#",          "[",     "(",      ")",      ";",    "\n",   "\r\n",   "%",      "/",
    "N",    "M2",         "M6",    "T",      "G53",    "G4",   "G80",  "G0",     "G1",     ".",
    "-",    "9999999999", "1e308", "nan",    "\0",     " ",    "O",    "$",      "G43H",   "G64P",
    "G40",  "G41",        "G42",   "G41.1D", "G42.1D", "D",    "D-1",  "M0",     "G93",    "G94",
    "M98P", "M99",        "M97P",  "G65P",   "L",      "#100", "#500", "G10L2P", "G54.1P", "G187"};

/* One mutation of `buf` (length *len, capacity WINDOW_MAX * 2). */
static void mutate(unsigned char *buf, size_t *len) {
  size_t at = *len ? next_random() % *len : 0;
  switch (next_random() % 4) {
  case 0:
    if (*len) buf[at] ^= (unsigned char)(1u << (next_random() % 8));
    break;
  case 1: {
    const char *f = fragments[next_random() % (sizeof fragments / sizeof fragments[0])];
    size_t n = f[0] ? strlen(f) : 1;
    if (*len + n > 2 * WINDOW_MAX) break;
    memmove(buf + at + n, buf + at, *len - at);
    memcpy(buf + at, f, n);
    *len += n;
    break;
  }
  case 2:
    if (*len) {
      size_t n = 1 + next_random() % 8;
      if (n > *len - at) n = *len - at;
      memmove(buf + at, buf + at + n, *len - at - n);
      *len -= n;
    }
    break;
  default:
    if (*len) buf[at] = (unsigned char)next_random();
  }
}

static int keep_first_byte; /* -k */

/* How many leading bytes of `s` every window keeps (see the top comment). */
static size_t head_of(const seed *s) {
  size_t n = 0;
  if (s->size > 0 && s->data[0] == ';')
    while (n < s->size && n < 64 && s->data[n++] != '\n') {
    }
  else if (keep_first_byte && s->size > 0)
    n = 1;
  return n;
}

static void one_mutation(unsigned char *buf) {
  const seed *s = &seeds[next_random() % nseeds];
  size_t head = head_of(s), rest = s->size - head;
  size_t start = head + (rest ? next_random() % rest : 0);
  size_t len = 1 + next_random() % WINDOW_MAX;
  int edits = 1 + (int)(next_random() % 8);
  if (len > s->size - start) len = s->size - start;
  memcpy(buf, s->data, head);
  memcpy(buf + head, s->data + start, len);
  len += head;
  for (int i = 0; i < edits; i++) {
    size_t keep = len - head;
    mutate(buf + head, &keep);
    len = head + keep;
  }
  LLVMFuzzerTestOneInput(buf, len);
}

int main(int argc, char **argv) {
  long mutations = 20000, done = 0;
  double seconds = 5;
  unsigned char *buf = malloc(2 * WINDOW_MAX + 64); /* head + window + insertions */
  clock_t t0 = clock();
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "-n") == 0 && i + 1 < argc)
      mutations = atol(argv[++i]);
    else if (strcmp(argv[i], "-t") == 0 && i + 1 < argc)
      seconds = atof(argv[++i]);
    else if (strcmp(argv[i], "-k") == 0)
      keep_first_byte = 1;
    else if (strcmp(argv[i], "-o") == 0 && i + 1 < argc) {
      if (!load_path(argv[++i])) /* optional: the corpus beside a checkout */
        printf("fuzz_smoke: no seeds from %s (not here), the others only\n", argv[i]);
    } else if (!load_path(argv[i])) {
      fprintf(stderr, "fuzz_smoke: cannot read seeds from %s\n", argv[i]);
      return 1;
    }
  }
  if (nseeds == 0) {
    fprintf(stderr, "fuzz_smoke: no seeds\n");
    return 1;
  }
  for (int i = 0; i < nseeds; i++)
    LLVMFuzzerTestOneInput(seeds[i].data, seeds[i].size);
  while (done < mutations && (double)(clock() - t0) / CLOCKS_PER_SEC < seconds) {
    one_mutation(buf);
    done++;
  }
  printf("fuzz_smoke: %d seeds, %ld mutations, %.1f s, no failure\n", nseeds, done,
         (double)(clock() - t0) / CLOCKS_PER_SEC);
  for (int i = 0; i < nseeds; i++)
    free(seeds[i].data);
  free(buf);
  return 0;
}
