/* test_isolation.c -- reading a .vdb in a forked child, and turning it off.
 *
 * Truth: a pthread_atfork handler counts the forks of this process. With
 * isolation on (the default) every swarf_stock_read forks once; with
 * SWARF_VDB_ISOLATE=0 or swarf_stock_set_read_isolation(0) it does not, and
 * the call wins over the variable. Either way the stock read back has the
 * written one's active voxels and volume exactly.
 */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "stock.h"

static int forks;
static void count_fork(void) {
  forks++;
}

/* Reads `path`, returns how many forks that took; checks the contents. */
static int read_forks(const char *path, const swarf_stock *ref, const char *what) {
  swarf_error err = {0};
  const int before = forks;
  swarf_stock *s = NULL;
  swarf_stock_read(path, &s, &err);
  CHECK(s != NULL, "%s: read: %s", what, err.message);
  if (s) {
    CHECK(swarf_stock_active_voxels(s) == swarf_stock_active_voxels(ref), "%s: voxels", what);
    CHECK(swarf_stock_volume(s) == swarf_stock_volume(ref), "%s: volume %.9g vs %.9g", what,
          swarf_stock_volume(s), swarf_stock_volume(ref));
  }
  swarf_stock_free(s);
  return forks - before;
}

int main(int argc, char **argv) {
  const char *path = argc > 1 ? argv[1] : "isolation.vdb";
  swarf_error err = {0};
  const double lo[3] = {0, 0, 0}, hi[3] = {3, 2, 1};
  swarf_stock *ref = NULL;
  swarf_stock_new_box(lo, hi, 0.1, 3, &ref, &err);
  CHECK(ref != NULL, "new_box: %s", err.message);
  if (!ref) return check_done();
  CHECK(swarf_stock_write_vdb(ref, path, &err) == 0, "write: %s", err.message);
  CHECK(pthread_atfork(count_fork, NULL, NULL) == 0, "pthread_atfork");

  unsetenv("SWARF_VDB_ISOLATE");
  CHECK(swarf_stock_read_isolation() == 1, "isolation is on by default");
  CHECK(read_forks(path, ref, "default") == 1, "the default read forks once");

  setenv("SWARF_VDB_ISOLATE", "0", 1);
  CHECK(swarf_stock_read_isolation() == 0, "SWARF_VDB_ISOLATE=0 turns it off");
  CHECK(read_forks(path, ref, "env 0") == 0, "SWARF_VDB_ISOLATE=0: no fork");
  setenv("SWARF_VDB_ISOLATE", "1", 1);
  CHECK(read_forks(path, ref, "env 1") == 1, "SWARF_VDB_ISOLATE=1: a fork");

  swarf_stock_set_read_isolation(0); /* the call wins over the variable */
  CHECK(swarf_stock_read_isolation() == 0, "set(0) over SWARF_VDB_ISOLATE=1");
  CHECK(read_forks(path, ref, "set 0") == 0, "set(0): no fork");
  setenv("SWARF_VDB_ISOLATE", "0", 1);
  swarf_stock_set_read_isolation(1);
  CHECK(read_forks(path, ref, "set 1") == 1, "set(1) over SWARF_VDB_ISOLATE=0: a fork");

  swarf_stock_free(ref);
  remove(path);
  return check_done();
}
