/* SPDX-License-Identifier: MPL-2.0 */
/* outputs.c -- the command line's checks of output paths, before any work.
 *
 * An output path must name a file swarf may write: not empty, not ending
 * in '/', not an existing folder, symbolic link, block device or socket,
 * in a folder that exists and is writable; an existing character device or
 * FIFO is accepted (the stock module writes into it: `--out /dev/null`).
 * No output may be an input (the program, a stock, design or fixture file,
 * a table) or another output, nor a .ngc file in the subroutine path; an
 * output's name leaves room for its temporary's. Each refusal names the
 * flag; the caller exits 2.
 */
#include <errno.h>
#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "stock_output.h"

/* The temporary beside an output: NAME.swarf.tmp.PID (stock/atomic_file.cc). */
#define TEMP_SUFFIX ((int)sizeof SWARF_STOCK_TEMP_MARKER - 1 + 10)

static int refuse(const char *cmd, const char *flag, const char *path, const char *why) {
  fprintf(stderr, "swarf %s: %s: cannot write \"%s\": %s\n", cmd, flag, path, why);
  return 2;
}

int swarf_cli_output_ok(const char *cmd, const char *flag, const char *path) {
  char copy[PATH_MAX];
  struct stat st;
  size_t n;
  if (path == NULL) return 0;
  n = strlen(path);
  if (n == 0) return refuse(cmd, flag, path, "no file name");
  if (n >= sizeof copy) return refuse(cmd, flag, path, "the name is too long");
  const char *base = strrchr(path, '/') != NULL ? strrchr(path, '/') + 1 : path;
  if (strlen(base) + TEMP_SUFFIX > NAME_MAX) {
    char why[160];
    snprintf(why, sizeof why,
             "the file name is too long: at most %d characters (swarf writes it through a "
             "temporary name beside it)",
             NAME_MAX - TEMP_SUFFIX);
    return refuse(cmd, flag, path, why);
  }
  if (path[n - 1] == '/') return refuse(cmd, flag, path, "it names a folder, not a file");
  if (lstat(path, &st) == 0) {
    if (S_ISDIR(st.st_mode)) return refuse(cmd, flag, path, "it is a folder");
    if (S_ISLNK(st.st_mode))
      return refuse(cmd, flag, path, "it is a symbolic link (not replaced: give its target)");
    if (S_ISBLK(st.st_mode) || S_ISSOCK(st.st_mode))
      return refuse(cmd, flag, path, "it is a block device or a socket");
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return 0; /* written into */
  }
  snprintf(copy, sizeof copy, "%s", path);
  if (access(dirname(copy), W_OK) != 0) return refuse(cmd, flag, path, strerror(errno));
  return 0;
}

/* The absolute name of `path` with its folder resolved (the file itself
 * need not exist); the path as given if the folder cannot be resolved. */
static void canonical(const char *path, char out[PATH_MAX]) {
  char d[PATH_MAX], b[PATH_MAX], real[PATH_MAX];
  snprintf(d, sizeof d, "%s", path);
  snprintf(b, sizeof b, "%s", path);
  if (realpath(dirname(d), real) == NULL) {
    snprintf(out, PATH_MAX, "%s", path);
    return;
  }
  snprintf(out, PATH_MAX, "%.2000s/%.2000s", real, basename(b));
}

/* 1 when a and b are the same file (a device or FIFO given twice is not:
 * writing into /dev/null twice is harmless). */
static int same_file(const char *a, const char *b, int outputs) {
  struct stat sa, sb;
  char ca[PATH_MAX], cb[PATH_MAX];
  if (stat(a, &sa) == 0 && stat(b, &sb) == 0) {
    if (outputs && (S_ISCHR(sa.st_mode) || S_ISFIFO(sa.st_mode))) return 0;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  }
  canonical(a, ca);
  canonical(b, cb);
  return strcmp(ca, cb) == 0;
}

int swarf_cli_outputs_distinct(const char *cmd, const swarf_cli_path *outs, int nout,
                               const swarf_cli_path *ins, int nin) {
  for (int i = 0; i < nout; i++) {
    if (outs[i].path == NULL) continue;
    for (int k = 0; k < nin; k++)
      if (ins[k].path != NULL && same_file(outs[i].path, ins[k].path, 0)) {
        fprintf(stderr, "swarf %s: %s \"%s\" is the input %s: it would be overwritten\n", cmd,
                outs[i].flag, outs[i].path, ins[k].flag);
        return 2;
      }
    for (int k = 0; k < i; k++)
      if (outs[k].path != NULL && same_file(outs[i].path, outs[k].path, 1)) {
        fprintf(stderr, "swarf %s: %s \"%s\" is also the output of %s: give each its own file\n",
                cmd, outs[i].flag, outs[i].path, outs[k].flag);
        return 2;
      }
  }
  return 0;
}

int swarf_cli_outputs_outside(const char *cmd, const swarf_cli_path *outs, int nout,
                              const char *flag, const char *dirs, const char *ext) {
  for (int i = 0; dirs != NULL && i < nout; i++) {
    const char *p = outs[i].path;
    size_t n = p != NULL ? strlen(p) : 0, e = strlen(ext);
    char out[PATH_MAX], dir[PATH_MAX], real[PATH_MAX];
    if (n <= e || strcmp(p + n - e, ext) != 0) continue;
    canonical(p, out);
    if (strrchr(out, '/') == NULL) continue; /* its folder cannot be resolved */
    *strrchr(out, '/') = '\0';
    for (const char *d = dirs; *d;) {
      size_t k = strcspn(d, ":");
      snprintf(dir, sizeof dir, "%.*s", (int)k, d);
      if (k > 0 && realpath(dir, real) != NULL && strcmp(real, out) == 0) {
        fprintf(stderr,
                "swarf %s: %s \"%s\" is in %s %s: it could be a subroutine file the program "
                "calls, and would be overwritten; write it elsewhere\n",
                cmd, outs[i].flag, p, flag, dir);
        return 2;
      }
      d += k + (d[k] == ':');
    }
  }
  return 0;
}
