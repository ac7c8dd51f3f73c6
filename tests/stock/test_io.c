/* SPDX-License-Identifier: MPL-2.0 */
/* test_io.c -- .vdb write and read back, refused files, atomic writes.
 *
 * Usage: test_stock_io OUT.vdb -- also leaves OUT.vdb and OUT.vdb.txt (grid
 * name, voxel size, half width, active voxel count and a few voxels) for the
 * pyopenvdb cross-check (check_vdb.py).
 *
 * Truth: the read-back grid equals the written one exactly (same voxel size,
 * band, active voxels and bit-identical values); every unusable file gives a
 * NULL stock, a message, and no crash; a failed write leaves no file behind
 * and leaves an existing file byte-identical.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "shapes.h"

static const box_shape box = {{0.0, 0.0, -3.0}, {6.0, 5.0, 0.0}};

static int file_exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}

static long file_size(const char *path) {
  struct stat st;
  return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

static char *read_all(const char *path, long *len) {
  FILE *f = fopen(path, "rb");
  char *buf = NULL;
  *len = file_size(path);
  if (f && *len >= 0 && (buf = malloc(*len + 1)) && fread(buf, 1, *len, f) != (size_t)*len) {
    free(buf);
    buf = NULL;
  }
  if (f) fclose(f);
  return buf;
}

static void write_bytes(const char *path, const void *data, size_t len) {
  FILE *f = fopen(path, "wb");
  CHECK(f && fwrite(data, 1, len, f) == len, "write %s", path);
  if (f) fclose(f);
}

static swarf_stock *make_stock(void) {
  swarf_error err = {0};
  swarf_stock *s = NULL;
  swarf_stock_new_box(box.lo, box.hi, 0.1, 3, &s, &err);
  CHECK(s != NULL, "new_box: %s", err.message);
  capsule_shape slot = {{1.0, 2.5, 0.5}, {5.0, 2.5, 0.5}, 1.2};
  swarf_stock_cut cut = capsule_cut(&slot);
  CHECK(s && swarf_stock_remove_batch(s, &cut, 1, &err) == 0, "slot: %s", err.message);
  return s;
}

/* The sidecar for check_vdb.py: name, voxel, half width, active count, voxels. */
static void write_sidecar(const swarf_stock *s, const char *vdb) {
  char path[1024];
  snprintf(path, sizeof path, "%s.txt", vdb);
  FILE *f = fopen(path, "w");
  CHECK(f != NULL, "sidecar %s", path);
  if (!f) return;
  fprintf(f, "stock %.17g %d %llu\n", swarf_stock_voxel(s), swarf_stock_half_width(s),
          swarf_stock_active_voxels(s));
  const double pts[4][3] = {{3.0, 2.5, -0.7}, {0.0, 1.0, -1.0}, {3.0, 1.3, 0.0}, {6.1, 4.0, -2.0}};
  for (int i = 0; i < 4; i++) {
    double c[3];
    double v = swarf_stock_voxel_value(s, pts[i][0], pts[i][1], pts[i][2], c);
    fprintf(f, "%d %d %d %.9g\n", (int)lround(c[0] / 0.1), (int)lround(c[1] / 0.1),
            (int)lround(c[2] / 0.1), v);
  }
  fclose(f);
}

static void round_trip(const char *out) {
  swarf_error err = {0};
  swarf_stock *s = make_stock();
  if (!s) return;
  CHECK(swarf_stock_write_vdb(s, out, &err) == 0, "write %s: %s", out, err.message);
  swarf_stock *r = NULL;
  swarf_stock_read(out, &r, &err);
  CHECK(r != NULL, "read back %s: %s", out, err.message);
  if (r) {
    CHECK(swarf_stock_voxel(r) == swarf_stock_voxel(s), "voxel %g", swarf_stock_voxel(r));
    CHECK(swarf_stock_half_width(r) == 3, "half width %d", swarf_stock_half_width(r));
    CHECK(swarf_stock_active_voxels(r) == swarf_stock_active_voxels(s), "active %llu vs %llu",
          swarf_stock_active_voxels(r), swarf_stock_active_voxels(s));
    CHECK(stock_differences(s, r) == 0 && stock_differences(r, s) == 0, "bit-identical values");
    CHECK(swarf_stock_volume(r) == swarf_stock_volume(s), "same volume");
    CHECK(swarf_stock_check(r, &err) == 0, "read grid valid: %s", err.message);
    /* A read stock can be cut like a new one. */
    capsule_shape hole = {{2.0, 2.0, -1.0}, {2.0, 2.0, 1.0}, 0.4};
    swarf_stock_cut cut = capsule_cut(&hole);
    CHECK(swarf_stock_remove_batch(r, &cut, 1, &err) == 0, "cut read stock: %s", err.message);
    CHECK(swarf_stock_volume(r) < swarf_stock_volume(s), "the hole removed material");
    swarf_stock_free(r);
  }
  write_sidecar(s, out);
  swarf_stock_free(s);
}

static void refuse(const char *path, const char *what) {
  swarf_error err = {0};
  swarf_stock *s = NULL;
  swarf_stock_read(path, &s, &err);
  CHECK(s == NULL && err.message[0] != '\0', "%s refused with a message", what);
  printf("  %-14s -> %s\n", what, err.message);
  swarf_stock_free(s);
}

static void bad_files(const char *good) {
  long len;
  char *data = read_all(good, &len);
  CHECK(data != NULL && len > 100, "read %s", good);
  if (!data) return;
  write_bytes("stock_io_truncated.vdb", data, (size_t)len / 2);
  refuse("stock_io_truncated.vdb", "truncated");
  write_bytes("stock_io_header_only.vdb", data, 64);
  refuse("stock_io_header_only.vdb", "header only");
  unsigned char noise[4096];
  srand(99);
  for (size_t i = 0; i < sizeof noise; i++)
    noise[i] = (unsigned char)rand();
  write_bytes("stock_io_random.vdb", noise, sizeof noise);
  refuse("stock_io_random.vdb", "random bytes");
  write_bytes("stock_io_empty.vdb", "", 0);
  refuse("stock_io_empty.vdb", "empty");
  write_bytes("stock_io_text.vdb", "this is not a vdb\n", 18);
  refuse("stock_io_text.vdb", "text");
  refuse("stock_io_missing.vdb", "missing");
  refuse(".", "a directory");
  refuse("", "empty path");
  refuse(NULL, "NULL path");
  free(data);
}

static void failed_writes(void) {
  char tmp[1024], name[300];
  swarf_error err = {0};
  swarf_stock *s = make_stock();
  if (!s) return;
  /* A missing directory: error, nothing created. */
  int rc = swarf_stock_write_vdb(s, "stock_io_no_such_dir/out.vdb", &err);
  CHECK(rc == SWARF_ERR_IO, "missing directory: %d %s", rc, err.message);
  printf("  missing dir    -> %s\n", err.message);
  CHECK(!file_exists("stock_io_no_such_dir"), "nothing created");

  /* An existing file, and its temporary name taken by a directory: the write
   * fails and the file keeps its bytes. */
  write_bytes("stock_io_keep.vdb", "precious", 8);
  snprintf(tmp, sizeof tmp, "stock_io_keep.vdb.swarf.tmp.%ld", (long)getpid());
  mkdir(tmp, 0755);
  rc = swarf_stock_write_vdb(s, "stock_io_keep.vdb", &err);
  CHECK(rc == SWARF_ERR_IO, "blocked temporary: %d %s", rc, err.message);
  printf("  blocked tmp    -> %s\n", err.message);
  CHECK(file_size("stock_io_keep.vdb") == 8, "existing file untouched");
  CHECK(file_exists(tmp), "a directory in the way is not removed");
  rmdir(tmp);

  /* An existing file whose temporary name is too long for the file system. */
  memset(name, 'k', 250);
  strcpy(name + 250, ".vdb");
  write_bytes(name, "precious", 8);
  rc = swarf_stock_write_vdb(s, name, &err);
  CHECK(rc == SWARF_ERR_IO, "long name: %d %s", rc, err.message);
  CHECK(file_size(name) == 8, "existing file untouched (long name)");
  unlink(name);

  /* The target is a directory: the rename fails, the temporary file is removed. */
  mkdir("stock_io_dir.vdb", 0755);
  rc = swarf_stock_write_vdb(s, "stock_io_dir.vdb", &err);
  CHECK(rc == SWARF_ERR_IO, "directory target: %d %s", rc, err.message);
  printf("  dir target     -> %s\n", err.message);
  snprintf(tmp, sizeof tmp, "stock_io_dir.vdb.swarf.tmp.%ld", (long)getpid());
  CHECK(!file_exists(tmp), "temporary file removed");
  rmdir("stock_io_dir.vdb");

  CHECK(swarf_stock_write_vdb(NULL, "x.vdb", &err) == SWARF_ERR_ARG, "NULL stock");
  CHECK(swarf_stock_write_vdb(s, NULL, &err) == SWARF_ERR_ARG, "NULL path");
  CHECK(swarf_stock_write_vdb(s, "", &err) == SWARF_ERR_ARG, "empty path");
  /* Overwriting an existing file works. */
  CHECK(swarf_stock_write_vdb(s, "stock_io_keep.vdb", &err) == 0, "overwrite: %s", err.message);
  CHECK(file_size("stock_io_keep.vdb") > 8, "file replaced");
  unlink("stock_io_keep.vdb");
  swarf_stock_free(s);
}

int main(int argc, char **argv) {
  const char *out = argc > 1 ? argv[1] : "stock_io_out.vdb";
  round_trip(out);
  bad_files(out);
  failed_writes();
  return check_done();
}
