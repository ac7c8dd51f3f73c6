/* SPDX-License-Identifier: MPL-2.0 */
/* test_isolation.c -- reading a .vdb with the reader program in a child
 * process, finding that program, and turning the child off.
 *
 * Truth: a pthread_atfork handler counts the forks of this process. With
 * isolation on (the default) every swarf_stock_read forks once; with
 * SWARF_VDB_ISOLATE=0 or swarf_stock_set_read_isolation(0) it does not, and
 * the call wins over the variable. Either way the stock read back has the
 * written one's active voxels and volume exactly. The child runs the reader
 * program (not a copy of this process): with SWARF_VDB_READER naming a
 * script that logs its arguments and then runs the real reader, the log holds
 * the file's path; a missing program, one that fails or one that sends
 * nothing are errors that say so, never a stock.
 *
 * usage: test_stock_isolation FILE.vdb READER (the built swarf-vdb-read)
 */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

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

/* Reads `path` with SWARF_VDB_READER=reader: expects `status` and `words`
 * in the message. */
static void read_fails(const char *path, const char *reader, swarf_status status,
                       const char *words) {
  swarf_error err = {0};
  swarf_stock *s = NULL;
  setenv("SWARF_VDB_READER", reader, 1);
  const swarf_status got = swarf_stock_read(path, &s, &err);
  CHECK(got == status && s == NULL, "reader %s: status %d (%s), expected %d", reader, (int)got,
        err.message, (int)status);
  CHECK(strstr(err.message, words) != NULL, "reader %s: '%s' lacks '%s'", reader, err.message,
        words);
  swarf_stock_free(s);
  unsetenv("SWARF_VDB_READER");
}

/* The reader program runs, with the file's path: a logging wrapper around it. */
static void reader_runs(const char *path, const swarf_stock *ref, const char *reader) {
  char script[4096], log[4096], line[4096] = "";
  snprintf(script, sizeof script, "%s.reader.sh", path);
  snprintf(log, sizeof log, "%s.reader.log", path);
  remove(log);
  FILE *f = fopen(script, "w");
  CHECK(f != NULL, "cannot write %s", script);
  if (!f) return;
  fprintf(f, "#!/bin/sh\necho \"$*\" > '%s'\nexec '%s' \"$@\"\n", log, reader);
  fclose(f);
  CHECK(chmod(script, 0755) == 0, "chmod %s", script);
  setenv("SWARF_VDB_READER", script, 1);
  CHECK(read_forks(path, ref, "through the wrapper") == 1, "the wrapper: one fork");
  unsetenv("SWARF_VDB_READER");
  f = fopen(log, "r");
  CHECK(f != NULL, "the reader program did not run (no %s)", log);
  if (f) {
    CHECK(fgets(line, sizeof line, f) != NULL, "empty log");
    fclose(f);
  }
  CHECK(strstr(line, path) != NULL, "the reader's arguments '%s' lack the path", line);
  remove(script);
  remove(log);
}

int main(int argc, char **argv) {
  const char *path = argc > 1 ? argv[1] : "isolation.vdb";
  const char *reader = argc > 2 ? argv[2] : NULL;
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

  swarf_stock_set_read_isolation(1);
  unsetenv("SWARF_VDB_ISOLATE");
  if (reader) reader_runs(path, ref, reader);
  read_fails(path, "/nonexistent/swarf-vdb-read", SWARF_ERR_IO, "SWARF_VDB_READER");
  read_fails(path, "/bin/false", SWARF_ERR_FORMAT, "the reader failed (exit status 1)");
  read_fails(path, "/bin/true", SWARF_ERR_FORMAT, "the reader program sent no answer");

  swarf_stock_free(ref);
  remove(path);
  return check_done();
}
