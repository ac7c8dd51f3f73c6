/// @file atomic_file.cc
/// @brief Atomic file output (see atomic_file.h).
#include "atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "stock_error.h"

namespace swarf {
namespace {

[[noreturn]] void fail(const std::string &what, const std::string &file, int err) {
  throw Error(SWARF_ERR_IO, what + " " + file + ": " + std::strerror(err));
}

/// Flush the file's data to the device, so that the rename publishes a whole file.
void sync_file(const std::string &file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail("cannot reopen", file, errno);
  const int rc = ::fsync(fd), err = errno;
  ::close(fd);
  if (rc != 0 && err != EINVAL && err != EROFS) fail("cannot sync", file, err);
}

void write_and_rename(const char *path, const std::string &tmp,
                      const std::function<void(std::ostream &)> &body) {
  std::ofstream out;
  errno = 0;
  out.open(tmp, std::ios::binary | std::ios::trunc);
  if (!out) fail("cannot create", tmp, errno ? errno : EIO);
  body(out);
  out.flush();
  if (!out) fail("cannot write", tmp, errno ? errno : EIO);
  out.close();
  if (out.fail()) fail("cannot close", tmp, errno ? errno : EIO);
  sync_file(tmp);
  if (std::rename(tmp.c_str(), path) != 0) fail("cannot rename " + tmp + " to", path, errno);
}

}  // namespace

void write_atomic(const char *path, const std::function<void(std::ostream &)> &body) {
  check_path(path);
  const std::string tmp = std::string(path) + ".tmp." + std::to_string(long(::getpid()));
  try {
    write_and_rename(path, tmp, body);
  } catch (...) {
    ::unlink(tmp.c_str());  // a file only: never a directory in the way
    throw;
  }
}

}  // namespace swarf
