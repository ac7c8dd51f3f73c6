/* SPDX-License-Identifier: MPL-2.0 */
/* file.c -- opening untrusted input files (swarf_file.h). */
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "swarf_file.h"

static const char *kind_of(mode_t m) {
  if (S_ISDIR(m)) return "a folder";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISFIFO(m)) return "a FIFO";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

FILE *swarf_file_open_input(const char *path, const char *what, long long max_bytes,
                            swarf_error *err) {
  struct stat st;
  FILE *in;
  int fd;
  if (path == NULL || path[0] == '\0') {
    swarf_error_set(err, SWARF_ERR_OPEN, "no %s named", what);
    return NULL;
  }
  swarf_error_at(err, path, 0, 0, NULL);
  fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    swarf_error_set(err, SWARF_ERR_OPEN, "%s", strerror(errno));
    return NULL;
  }
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    swarf_error_set(err, SWARF_ERR_OPEN, "the %s is %s, not a regular file", what,
                    kind_of(st.st_mode)); /* reading it could block or never end */
    close(fd);
    return NULL;
  }
  if (max_bytes > 0 && (long long)st.st_size > max_bytes) {
    swarf_error_set(err, SWARF_ERR_LIMIT, "the %s is %lld bytes, more than the %lld accepted", what,
                    (long long)st.st_size, max_bytes);
    close(fd);
    return NULL;
  }
  fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  in = fdopen(fd, "rb");
  if (in == NULL) {
    swarf_error_set(err, SWARF_ERR_MEMORY, "%s", strerror(errno));
    close(fd);
  }
  return in;
}
