/* SPDX-License-Identifier: MPL-2.0 */
/// @file atomic_file.cc
/// @brief Atomic file output and the all-or-none output group (atomic_file.h,
/// stock_output.h).
#include "atomic_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>
#include <string>
#include <vector>

#include "stock_error.h"
#include "stock_output.h"

namespace swarf {
namespace {

[[noreturn]] void fail(const std::string &what, const std::string &file, int err) {
  throw Error(SWARF_ERR_IO, what + " " + file + ": " + std::strerror(err));
}

/// Named temporaries that exist now, for the signal handler (fixed storage:
/// the handler only reads it and calls unlink).
constexpr int kMaxNamed = 16;
char named[kMaxNamed][4096];
volatile sig_atomic_t named_used[kMaxNamed];

int remember(const std::string &tmp) {
  for (int i = 0; i < kMaxNamed; i++)
    if (!named_used[i] && tmp.size() < sizeof named[i]) {
      std::memcpy(named[i], tmp.c_str(), tmp.size() + 1);
      named_used[i] = 1;
      return i;
    }
  return -1;
}

void forget(int slot) {
  if (slot >= 0) named_used[slot] = 0;
}

extern "C" void remove_named_and_die(int sig) {
  for (int i = 0; i < kMaxNamed; i++)
    if (named_used[i]) ::unlink(named[i]);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void install_handlers() {
  static bool done = false;
  if (done) return;
  done = true;
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_DFL) {
      struct sigaction sa {};
      sa.sa_handler = remove_named_and_die;
      sigemptyset(&sa.sa_mask);
      ::sigaction(sig, &sa, nullptr);
    }
  }
}

std::string folder_of(const std::string &path) {
  const size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

/// The temporary beside PATH: a marker no user's file name carries by chance
/// (a file of the user's named like PATH.tmp.N is never touched).
const char kTempMarker[] = SWARF_STOCK_TEMP_MARKER;

std::string temp_name(const char *path) {
  return std::string(path) + kTempMarker + std::to_string(long(::getpid()));
}

/// Removes PATH.swarf.tmp.PID left by swarf processes that no longer run
/// (kill -9 in the instant between link and rename, or a filesystem without
/// O_TMPFILE): only regular files of this user with that marker.
void sweep_stale(const char *path) {
  const std::string p(path), folder = folder_of(p);
  const std::string base = p.substr(p.rfind('/') == std::string::npos ? 0 : p.rfind('/') + 1);
  const std::string prefix = base + kTempMarker;
  DIR *d = ::opendir(folder.c_str());
  if (d == nullptr) return;
  while (struct dirent *e = ::readdir(d)) {
    const std::string name(e->d_name);
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    char *end = nullptr;
    const long pid = std::strtol(name.c_str() + prefix.size(), &end, 10);
    if (pid <= 0 || *end != '\0' || pid == long(::getpid())) continue;
    if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue; // alive, or not ours to judge
    struct stat st {};
    const std::string stale = folder + "/" + name;
    if (::lstat(stale.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_uid != ::geteuid())
      continue;
    ::unlink(stale.c_str());
  }
  ::closedir(d);
}

/// A file being written: an unnamed one (fd, O_TMPFILE) or a named temporary.
struct Pending {
  int fd = -1;
  std::string path, named_tmp;
  int slot = -1;
};

bool group_open = false;
std::vector<Pending> group;

/// Opens the file that will become `path`.
Pending open_pending(const char *path) {
  Pending p;
  p.path = path;
  p.fd = ::open(folder_of(p.path).c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (p.fd >= 0) {
    ::fchmod(
        p.fd, 0666 & ~[] {
          mode_t m = ::umask(0);
          ::umask(m);
          return m;
        }());
    return p;
  }
  p.named_tmp = temp_name(path); // no O_TMPFILE here: a name, removed on signals
  p.slot = remember(p.named_tmp);
  p.fd = ::open(p.named_tmp.c_str(), O_CREAT | O_TRUNC | O_WRONLY | O_CLOEXEC | O_NOFOLLOW, 0666);
  if (p.fd < 0) {
    const int err = errno;
    forget(p.slot);
    fail("cannot create", p.named_tmp, err);
  }
  return p;
}

void drop(Pending &p) {
  if (!p.named_tmp.empty()) ::unlink(p.named_tmp.c_str());
  forget(p.slot);
  if (p.fd >= 0) ::close(p.fd);
  p.fd = -1;
}

/// Names the written file PATH (through PATH.tmp.PID: rename replaces atomically).
void publish(Pending &p) {
  if (p.named_tmp.empty()) {
    const std::string proc = "/proc/self/fd/" + std::to_string(p.fd);
    p.named_tmp = temp_name(p.path.c_str());
    p.slot = remember(p.named_tmp);
    ::unlink(p.named_tmp.c_str()); // our own leftover, if any
    if (::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, p.named_tmp.c_str(), AT_SYMLINK_FOLLOW) != 0) {
      const int err = errno;
      forget(p.slot);
      p.named_tmp.clear();
      fail("cannot link the new file as", temp_name(p.path.c_str()), err);
    }
  }
  if (std::rename(p.named_tmp.c_str(), p.path.c_str()) != 0)
    fail("cannot rename " + p.named_tmp + " to", p.path, errno);
  p.named_tmp.clear();
  forget(p.slot);
  ::close(p.fd);
  p.fd = -1;
}

void write_body(int fd, const std::string &shown, const std::function<void(std::ostream &)> &body) {
  std::ofstream out;
  errno = 0;
  out.open("/proc/self/fd/" + std::to_string(fd), std::ios::binary | std::ios::trunc);
  if (!out) fail("cannot write", shown, errno ? errno : EIO);
  body(out);
  out.flush();
  if (!out) fail("cannot write", shown, errno ? errno : EIO);
  out.close();
  if (out.fail()) fail("cannot close", shown, errno ? errno : EIO);
  if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) fail("cannot sync", shown, errno);
}

/// Writes into an existing device or FIFO the user named (no rename).
void write_into(const char *path, const std::function<void(std::ostream &)> &body) {
  std::ofstream out;
  errno = 0;
  out.open(path, std::ios::binary);
  if (!out) fail("cannot open", path, errno ? errno : EIO);
  body(out);
  out.flush();
  if (!out) fail("cannot write", path, errno ? errno : EIO);
}

const char *refused_kind(mode_t m) {
  if (S_ISLNK(m)) return "a symbolic link (give the file it points to)";
  if (S_ISDIR(m)) return "a folder";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISSOCK(m)) return "a socket";
  return nullptr;
}

} // namespace

void write_atomic(const char *path, const std::function<void(std::ostream &)> &body) {
  check_path(path);
  struct stat st;
  if (::lstat(path, &st) == 0) {
    if (const char *kind = refused_kind(st.st_mode))
      throw Error(SWARF_ERR_IO, std::string(path) + " is " + kind + ": not replaced");
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return write_into(path, body);
  }
  sweep_stale(path);
  install_handlers();
  Pending p = open_pending(path);
  try {
    write_body(p.fd, path, body);
    if (group_open) {
      group.push_back(p);
      return;
    }
    publish(p);
  } catch (...) {
    drop(p);
    throw;
  }
}

} // namespace swarf

extern "C" void swarf_stock_outputs_begin(void) {
  swarf_stock_outputs_abort();
  swarf::group_open = true;
  swarf::install_handlers();
}

extern "C" swarf_status swarf_stock_outputs_commit(swarf_error *err) {
  swarf_status s = SWARF_OK;
  for (swarf::Pending &p : swarf::group) {
    if (s != SWARF_OK) {
      swarf::drop(p);
      continue;
    }
    try {
      swarf::publish(p);
    } catch (const swarf::Error &e) {
      s = swarf_error_set(err, SWARF_ERR_IO, "%s", e.what());
      swarf::drop(p);
    }
  }
  swarf::group.clear();
  swarf::group_open = false;
  return s;
}

extern "C" void swarf_stock_outputs_abort(void) {
  for (swarf::Pending &p : swarf::group)
    swarf::drop(p);
  swarf::group.clear();
  swarf::group_open = false;
}

extern "C" swarf_status swarf_stock_output_write(const char *path, const void *data, size_t len,
                                                 swarf_error *err) {
  if (path == nullptr || (data == nullptr && len > 0))
    return swarf_error_set(err, SWARF_ERR_ARG, "swarf_stock_output_write: path or data is NULL");
  try {
    swarf::write_atomic(path, [&](std::ostream &os) {
      os.write(static_cast<const char *>(data), std::streamsize(len));
    });
    return SWARF_OK;
  } catch (const swarf::Error &e) {
    return swarf_error_set(err, e.status, "%s", e.what());
  } catch (const std::bad_alloc &) {
    return swarf_error_set(err, SWARF_ERR_MEMORY, "out of memory");
  } catch (const std::exception &e) {
    return swarf_error_set(err, SWARF_ERR_INTERNAL, "internal error: %s", e.what());
  } catch (...) {
    return swarf_error_set(err, SWARF_ERR_INTERNAL, "internal error: unknown exception");
  }
}
