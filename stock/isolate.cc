/* SPDX-License-Identifier: MPL-2.0 */
/// @file isolate.cc
/// @brief Untrusted parsing in the reader program, run in a child process
/// (see isolate.h): finding the program, running it, and its side of the pipe.
///
/// Protocol on the pipe from child to parent (the child's fd 3): one status
/// byte, then the payload. 'D': the payload is the result. 'E': a 4-byte
/// status (host order) and the message. 'X': exec failed, a 4-byte errno.
/// Between fork and exec the child calls only async-signal-safe functions
/// (the parent may run other threads, holding locks the child would wait on).
#include "isolate.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

#include "stock_error.h"

// Where CMake puts and installs the reader (stock/CMakeLists.txt); the
// defaults are the usual layout.
#ifndef SWARF_READER_FROM_BIN
#define SWARF_READER_FROM_BIN "../libexec/swarf"
#endif
#ifndef SWARF_READER_FROM_LIB
#define SWARF_READER_FROM_LIB "../libexec/swarf"
#endif
#ifndef SWARF_READER_FROM_MODULE
#define SWARF_READER_FROM_MODULE "../../libexec/swarf"
#endif
#ifndef SWARF_READER_INSTALLED
#define SWARF_READER_INSTALLED "/usr/local/libexec/swarf"
#endif
#ifndef SWARF_READER_BUILD_DIR
#define SWARF_READER_BUILD_DIR ""
#endif

extern char **environ;

namespace swarf {
namespace {

/// The fd the reader writes its reply on.
constexpr int kReplyFd = 3;

bool write_all(int fd, const char *p, size_t n) {
  while (n > 0) {
    const ssize_t k = ::write(fd, p, n);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return false;
    p += k, n -= size_t(k);
  }
  return true;
}

std::string read_all(int fd) {
  std::string data;
  char buf[1 << 16];
  for (;;) {
    const ssize_t k = ::read(fd, buf, sizeof buf);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) break;
    data.append(buf, size_t(k));
  }
  return data;
}

// ---- Finding the reader program -------------------------------------------

bool is_program(const std::string &path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

std::string real_path(const char *path) {
  char buf[PATH_MAX];
  return ::realpath(path, buf) ? std::string(buf) : std::string();
}

std::string dir_of(const std::string &path) {
  const size_t k = path.rfind('/');
  return k == std::string::npos || k == 0 ? std::string("/") : path.substr(0, k);
}

/// The folders of the running executable and of the object holding this code
/// (libswarf.so, or the executable itself when linked statically).
std::vector<std::string> own_dirs() {
  std::vector<std::string> dirs;
  const std::string exe = real_path("/proc/self/exe");
  if (!exe.empty()) dirs.push_back(dir_of(exe));
  Dl_info info;
  if (::dladdr(reinterpret_cast<void *>(&reader_program), &info) && info.dli_fname &&
      std::strchr(info.dli_fname, '/')) {
    const std::string lib = real_path(info.dli_fname);
    if (!lib.empty() && dir_of(lib) != (dirs.empty() ? "" : dirs[0])) dirs.push_back(dir_of(lib));
  }
  return dirs;
}

bool below(const std::string &dir, const std::string &top) {
  return !top.empty() && (dir == top || dir.compare(0, top.size() + 1, top + "/") == 0);
}

// ---- The child ----------------------------------------------------------------

/// Everything the child needs, made before fork (it may not allocate).
struct ExecPlan {
  std::string program;
  std::vector<std::string> args, env;
  std::vector<char *> argv, envp;
  int max_fd;
};

/// The reader's environment: ours, and under ASan a bound on each allocation
/// (max_allocation_size_mb), the sanitized reader's memory limit.
std::vector<std::string> reader_env(const IsolateLimits &limits) {
  std::vector<std::string> env;
  std::string asan;
  for (char **e = environ; e && *e; e++) {
    if (std::strncmp(*e, "ASAN_OPTIONS=", 13) == 0)
      asan = *e + 13;
    else
      env.emplace_back(*e);
  }
#ifdef SWARF_ASAN
  if (limits.room)
    asan += (asan.empty() ? "" : ":") + std::string("max_allocation_size_mb=") +
            std::to_string((limits.room >> 20) + 1);
#else
  (void)limits;
#endif
  if (!asan.empty()) env.push_back("ASAN_OPTIONS=" + asan);
  return env;
}

ExecPlan plan_exec(const std::string &path, const IsolateLimits &limits) {
  ExecPlan p;
  p.program = reader_program();
  p.args = {p.program, "--room", std::to_string(limits.room), "--", path};
  p.env = reader_env(limits);
  for (std::string &a : p.args)
    p.argv.push_back(&a[0]);
  p.argv.push_back(nullptr);
  for (std::string &e : p.env)
    p.envp.push_back(&e[0]);
  p.envp.push_back(nullptr);
  const long open_max = ::sysconf(_SC_OPEN_MAX);
  p.max_fd = open_max > 0 && open_max < 65536 ? int(open_max) : 65536;
  return p;
}

/// The child between fork and exec: the pipe on fd 3, no other descriptor
/// beyond stderr, the CPU limit, default signals; async-signal-safe calls only.
[[noreturn]] void child_exec(int fd, const ExecPlan &p, const IsolateLimits &limits) {
  if (fd != kReplyFd) {
    if (::dup2(fd, kReplyFd) < 0) ::_exit(127);
  } else {
    ::fcntl(kReplyFd, F_SETFD, 0);
  }
#ifdef SYS_close_range
  if (::syscall(SYS_close_range, kReplyFd + 1, ~0U, 0) != 0)
#endif
    for (int k = kReplyFd + 1; k < p.max_fd; k++)
      ::close(k);
  struct rlimit cpu = {limits.cpu_seconds, limits.cpu_seconds + 1};
  if (limits.cpu_seconds) ::setrlimit(RLIMIT_CPU, &cpu);
  struct sigaction dfl;
  std::memset(&dfl, 0, sizeof dfl);
  dfl.sa_handler = SIG_DFL;
  for (int sig = 1; sig < NSIG; sig++)
    ::sigaction(sig, &dfl, nullptr); // ignored ones survive exec
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  ::execve(p.program.c_str(), p.argv.data(), p.envp.data());
  char reply[1 + sizeof(int)] = {'X'};
  const int err = errno;
  std::memcpy(reply + 1, &err, sizeof err);
  write_all(kReplyFd, reply, sizeof reply);
  ::_exit(127);
}

/// Why a child that sent no complete answer failed, in words.
std::string child_failure(int wstatus, const IsolateLimits &limits) {
  if (WIFSIGNALED(wstatus)) {
    const int sig = WTERMSIG(wstatus);
    if (sig == SIGXCPU || sig == SIGKILL) return "it takes too long to read (CPU time limit)";
#ifdef SWARF_ASAN
    // The sanitized reader's memory bound is ASan's max_allocation_size_mb:
    // an allocation over it is a report and an abort, not a bad_alloc.
    if (sig == SIGABRT)
      return "the sanitized reader stopped on it (a sanitizer report on its stderr, e.g. an "
             "allocation over its bound of " +
             std::to_string((limits.room >> 20) + 1) + " MB)";
#else
    (void)limits;
#endif
    return std::string("OpenVDB's reader crashed on it (") + strsignal(sig) + ")";
  }
  if (WEXITSTATUS(wstatus) == 0) return "the reader program sent no answer";
  return "the reader failed (exit status " + std::to_string(WEXITSTATUS(wstatus)) + ")";
}

std::string error_reply(int status, const std::string &message) {
  std::string r(1, 'E');
  r.append(reinterpret_cast<const char *>(&status), sizeof status);
  return r.append(message);
}

/// In the reader: an address-space limit of what the process maps now plus
/// `room` (not under ASan, whose shadow memory needs terabytes of it).
void limit_address_space(size_t room) {
#ifndef SWARF_ASAN
  if (room == 0) return;
  size_t pages = 0;
  if (FILE *f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%zu", &pages) != 1) pages = 0;
    std::fclose(f);
  }
  if (pages == 0) return;
  const rlim_t as = pages * size_t(::sysconf(_SC_PAGESIZE)) + room;
  struct rlimit lim = {as, as};
  ::setrlimit(RLIMIT_AS, &lim);
#else
  (void)room;
#endif
}

} // namespace

std::string reader_program() {
  if (const char *env = std::getenv("SWARF_VDB_READER"); env && *env) {
    if (is_program(env)) return env;
    throw Error(SWARF_ERR_IO, std::string("SWARF_VDB_READER=") + env +
                                  ": not an executable file (the .vdb reader program)");
  }
  const std::vector<std::string> dirs = own_dirs();
  std::vector<std::string> tried;
  auto found = [&](const std::string &dir) {
    const std::string p = dir + "/" + kReaderName;
    for (const std::string &t : tried)
      if (t == dir) return false;
    tried.push_back(dir);
    return is_program(p);
  };
  for (const std::string &d : dirs)
    for (const char *rel :
         {"", SWARF_READER_FROM_BIN, SWARF_READER_FROM_LIB, SWARF_READER_FROM_MODULE}) {
      const std::string dir = *rel ? d + "/" + rel : d;
      if (found(dir)) return dir + "/" + kReaderName;
    }
  if (found(SWARF_READER_INSTALLED)) return std::string(SWARF_READER_INSTALLED) + "/" + kReaderName;
  const std::string build = real_path(SWARF_READER_BUILD_DIR);
  for (const std::string &d : dirs)
    if (below(d, build) && found(build + "/tools")) return build + "/tools/" + kReaderName;
  std::string where;
  for (const std::string &t : tried)
    where += (where.empty() ? "" : ", ") + t;
  throw Error(SWARF_ERR_IO, std::string("the .vdb reader program ") + kReaderName +
                                " was not found (looked in " + where +
                                "); set SWARF_VDB_READER to its path");
}

void run_reader(const std::string &what, const std::string &path, const IsolateLimits &limits,
                std::string &out) {
  const ExecPlan plan = plan_exec(path, limits);
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw Error(SWARF_ERR_IO, what + ": cannot create a pipe: " + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(fds[0]), ::close(fds[1]);
    throw Error(SWARF_ERR_IO, what + ": cannot fork: " + std::strerror(err));
  }
  if (pid == 0) child_exec(fds[1], plan, limits);
  ::close(fds[1]);
  std::string reply = read_all(fds[0]);
  ::close(fds[0]);
  int wstatus = 0;
  while (::waitpid(pid, &wstatus, 0) < 0 && errno == EINTR) {
  }
  int code = 0;
  if (reply.size() == 1 + sizeof code && reply[0] == 'X') {
    std::memcpy(&code, reply.data() + 1, sizeof code);
    throw Error(SWARF_ERR_IO, what + ": cannot run the reader program " + plan.program + ": " +
                                  std::strerror(code));
  }
  const bool exited_ok = WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 0;
  if (!exited_ok || reply.empty())
    throw Error(SWARF_ERR_FORMAT, what + ": " + child_failure(wstatus, limits));
  if (reply[0] == 'D') {
    out.assign(reply, 1, std::string::npos);
    return;
  }
  int status = SWARF_ERR_FORMAT;
  if (reply.size() >= 1 + sizeof status) std::memcpy(&status, reply.data() + 1, sizeof status);
  throw Error(static_cast<swarf_status>(status), reply.size() > 1 + sizeof status
                                                     ? reply.substr(1 + sizeof status)
                                                     : what + ": failed");
}

void reader_reply(int fd, const std::string &what, const IsolateLimits &limits,
                  const std::function<std::string()> &body) {
  limit_address_space(limits.room);
  std::string reply;
  try {
    reply = 'D' + body();
  } catch (const Error &e) {
    reply = error_reply(e.status, e.what());
  } catch (const std::bad_alloc &) {
    reply = error_reply(SWARF_ERR_FORMAT, what + ": needs more memory than allowed (" +
                                              std::to_string(limits.room >> 20) +
                                              " MB): not a readable stock");
  } catch (const std::exception &e) {
    reply = error_reply(SWARF_ERR_FORMAT, e.what());
  } catch (...) {
    reply = error_reply(SWARF_ERR_FORMAT, "unknown failure");
  }
  ::_exit(write_all(fd, reply.data(), reply.size()) ? 0 : 1);
}

} // namespace swarf
