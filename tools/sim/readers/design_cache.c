/* SPDX-License-Identifier: MPL-2.0 */
/* design_cache.c -- a design's band kept between runs (swarf_sim.h,
 * swarf_sim_read_design_cached).
 *
 * Making a level set of a CAD-size STL costs more than a whole coarse run
 * (bear's 1.36 M-triangle isosurface: 2.4 s CPU against 1.9 s for the run),
 * and a machinist verifies the same part against program after program. As
 * Vericut prepares a design model once, the band is kept in swarf's own band
 * file (KEY.band, swarf_stock_write_band) in the user's cache folder under a
 * key of everything it depends on: the design file's bytes (a 128-bit hash
 * and the length), the voxel, the band, the library's version. A hit is
 * parsed in-process with every count, origin and value checked
 * (swarf_stock_read_band: no child process, no OpenVDB parser, 0.3 s CPU
 * less than a .vdb for bear's design at 0.2 mm), so a damaged or planted
 * file costs a rebuild, never a crash; the values are the ones written, bit
 * for bit, and the STL's triangles are kept too, beside the band (KEY.tri),
 * in the order the exact distances beyond the band search them: a warm run
 * reads them back, when the first such distance is asked for, instead of
 * parsing, welding and sorting the STL (swarf_stock_design_surface_cached; a
 * damaged .tri costs a reading of the STL, and is written again by the next
 * run). Each file's writer goes through a temporary renamed into place, so
 * concurrent runs never see half a file;
 * then the oldest files go until the folder is within its bound. The cache
 * is best effort: any failure of it falls back to reading the design, and
 * only the design's own errors are reported.
 */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <unistd.h>

#include "swarf_file.h"
#include "swarf_sim.h"

#define DEFAULT_MAX_BYTES (1024LL * 1024 * 1024)
#define KEY_HEX 32

/* Two independent 64-bit hashes of the design's bytes, a word of 8 bytes
 * at a time (FNV-1a's step and a multiply-xorshift): a 128-bit content key.
 * A CAD-size STL (150 MB) hashes in ~0.05 s. */
typedef struct {
  uint64_t a, b, n;
} hash128;

static void hash_word(hash128 *h, uint64_t w) {
  h->a = (h->a ^ w) * 0x100000001b3ULL;
  h->b = (h->b ^ w) * 0x9e3779b97f4a7c15ULL;
  h->b ^= h->b >> 29;
}

static void hash_bytes(hash128 *h, const unsigned char *p, size_t len) {
  size_t i = 0;
  for (; i + 8 <= len; i += 8) {
    uint64_t w;
    memcpy(&w, p + i, 8);
    hash_word(h, w);
  }
  if (i < len) { /* the tail, zero-padded (its length is in n) */
    uint64_t w = 0;
    memcpy(&w, p + i, len - i);
    hash_word(h, w);
  }
  h->n += len;
}

/* The key of (file bytes, voxel, band, version) as 32 hex digits; 0 or -1
 * when the file cannot be read (the design's reader then says why). */
static int design_key(const char *path, double voxel, int half_width, char key[KEY_HEX + 1]) {
  hash128 h = {0xcbf29ce484222325ULL, 0x6a09e667f3bcc908ULL, 0};
  char tail[128];
  unsigned char buf[1 << 16];
  size_t got;
  FILE *f = swarf_file_open_input(path, "the design", 0, NULL);
  if (f == NULL) return -1;
  while ((got = fread(buf, 1, sizeof buf, f)) > 0)
    hash_bytes(&h, buf, got);
  const int bad = ferror(f);
  fclose(f);
  if (bad) return -1;
  int n = snprintf(tail, sizeof tail, "|%llu|%.17g|%d|%s|band1", (unsigned long long)h.n, voxel,
                   half_width, SWARF_SIM_VERSION);
  hash_bytes(&h, (const unsigned char *)tail, (size_t)n);
  snprintf(key, KEY_HEX + 1, "%016llx%016llx", (unsigned long long)h.a, (unsigned long long)h.b);
  return 0;
}

/* The cache folder: cache->dir, else $XDG_CACHE_HOME/swarf/designs, else
 * $HOME/.cache/swarf/designs; created (0700) if missing. 0 or -1. */
static int cache_dir(const swarf_design_cache *cache, char *out, size_t len) {
  const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
  int n;
  if (cache != NULL && cache->dir != NULL)
    n = snprintf(out, len, "%s", cache->dir);
  else if (xdg != NULL && xdg[0] == '/')
    n = snprintf(out, len, "%s/swarf/designs", xdg);
  else if (home != NULL && home[0] == '/')
    n = snprintf(out, len, "%s/.cache/swarf/designs", home);
  else
    return -1;
  if (n <= 0 || (size_t)n >= len) return -1;
  for (char *p = out + 1;; p++) { /* mkdir -p */
    const char c = *p;
    if (c != '/' && c != '\0') continue;
    *p = '\0';
    const int rc = mkdir(out, 0700);
    *p = c;
    if (rc != 0 && errno != EEXIST) return -1;
    if (c == '\0') break;
  }
  struct stat st;
  return stat(out, &st) == 0 && S_ISDIR(st.st_mode) ? 0 : -1;
}

/* A cached band, if there is a sound one: the voxel and band must be the
 * ones asked for. A file that cannot be used is removed. */
static swarf_stock *cache_get(const char *file, double voxel, int half_width) {
  swarf_stock *s = NULL;
  struct stat st;
  if (lstat(file, &st) != 0 || !S_ISREG(st.st_mode)) return NULL;
  if (swarf_stock_read_band(file, &s, NULL) != SWARF_OK || swarf_stock_voxel(s) != voxel ||
      swarf_stock_half_width(s) != half_width) {
    swarf_stock_free(s);
    unlink(file);
    return NULL;
  }
  utimes(file, NULL); /* recently used: the last to be evicted */
  return s;
}

typedef struct {
  char name[KEY_HEX + 8];
  time_t mtime;
  long long size;
} entry;

static int older_first(const void *a, const void *b) {
  const entry *x = a, *y = b;
  return (x->mtime > y->mtime) - (x->mtime < y->mtime);
}

/* The oldest .band and .tri files of the folder (and .vdb, the bands of
 * earlier versions) removed until it holds at most max. */
static void cache_evict(const char *dir, long long max) {
  DIR *d = opendir(dir);
  entry *e = NULL;
  size_t n = 0, cap = 0;
  long long total = 0;
  char path[4096];
  struct dirent *de;
  if (d == NULL) return;
  while ((de = readdir(d)) != NULL) {
    struct stat st;
    const size_t len = strlen(de->d_name);
    const char *ext = len > KEY_HEX ? de->d_name + KEY_HEX : "";
    if (strcmp(ext, ".band") && strcmp(ext, ".vdb") && strcmp(ext, ".tri")) continue;
    if (snprintf(path, sizeof path, "%s/%s", dir, de->d_name) >= (int)sizeof path ||
        lstat(path, &st) != 0 || !S_ISREG(st.st_mode))
      continue;
    if (n == cap) {
      entry *more = realloc(e, (cap = cap ? 2 * cap : 64) * sizeof *e);
      if (more == NULL) break;
      e = more;
    }
    snprintf(e[n].name, sizeof e[n].name, "%s", de->d_name);
    e[n].mtime = st.st_mtime;
    e[n].size = (long long)st.st_size;
    total += e[n++].size;
  }
  closedir(d);
  qsort(e, n, sizeof *e, older_first);
  for (size_t i = 0; i < n && total > max; i++) {
    if (snprintf(path, sizeof path, "%s/%s", dir, e[i].name) < (int)sizeof path &&
        unlink(path) == 0)
      total -= e[i].size;
  }
  free(e);
}

/* The band written under its key and its triangles beside it (tri), each
 * atomically by its writer (a temporary renamed into place). */
static void cache_put(const char *dir, const char *file, const char *tri, const swarf_stock *s,
                      long long max) {
  if (swarf_stock_write_band(s, file, NULL) != SWARF_OK) return;
  swarf_stock_design_surface_save(s, tri, NULL);
  cache_evict(dir, max);
}

/* A cached band's triangles: from tri if it is there, else from the STL at
 * path, then written to tri for the next run. SWARF_OK or the STL's error. */
static swarf_status cache_surface(swarf_stock *band, const char *tri, const char *path) {
  struct stat st;
  if (lstat(tri, &st) == 0 && S_ISREG(st.st_mode)) {
    utimes(tri, NULL);
    return swarf_stock_design_surface_cached(band, tri, path, NULL);
  }
  const swarf_status status = swarf_stock_design_surface(band, path, NULL);
  if (status == SWARF_OK) swarf_stock_design_surface_save(band, tri, NULL);
  return status;
}

static int is_vdb(const char *path) {
  const size_t n = strlen(path);
  return n >= 4 && !strcasecmp(path + n - 4, ".vdb");
}

swarf_status swarf_sim_read_design_cached(const char *path, double voxel, int half_width,
                                          const swarf_design_cache *cache, swarf_stock **out,
                                          int *hit, swarf_error *err) {
  char dir[4096], key[KEY_HEX + 1], file[4200], tri[4200];
  const long long max =
      cache != NULL && cache->max_bytes > 0 ? cache->max_bytes : DEFAULT_MAX_BYTES;
  if (hit != NULL) *hit = 0;
  if (path == NULL || out == NULL)
    return swarf_error_set(err, SWARF_ERR_ARG, "swarf_sim_read_design_cached: NULL argument");
  *out = NULL;
  const int use = (cache == NULL || !cache->off) && !is_vdb(path) && voxel > 0 &&
                  design_key(path, voxel, half_width, key) == 0 &&
                  cache_dir(cache, dir, sizeof dir) == 0 &&
                  snprintf(file, sizeof file, "%s/%s.band", dir, key) < (int)sizeof file &&
                  snprintf(tri, sizeof tri, "%s/%s.tri", dir, key) < (int)sizeof tri;
  if (use && (*out = cache_get(file, voxel, half_width)) != NULL) {
    /* the triangles too, for exact distances beyond the band */
    if (cache_surface(*out, tri, path) == SWARF_OK) {
      if (hit != NULL) *hit = 1;
      return SWARF_OK;
    }
    swarf_stock_free(*out);
    *out = NULL;
  }
  const swarf_status st = swarf_stock_read_design_band(path, voxel, half_width, out, err);
  if (st == SWARF_OK && use) cache_put(dir, file, tri, *out, max);
  return st;
}
