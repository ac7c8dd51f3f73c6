/// @file isolate.cc
/// @brief Untrusted parsing in a child process (see isolate.h).
///
/// Protocol on the pipe from child to parent: one status byte, then the
/// payload. 'D': the payload is the result. 'E': a 4-byte status (host order)
/// and the message. The child leaves with _exit, so no destructor or atexit
/// handler of the parent's state runs twice.
#include "isolate.h"

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <new>

#include "stock_error.h"

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/common_interface_defs.h>
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#include <sanitizer/common_interface_defs.h>
#endif
#endif

namespace swarf {
namespace {

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

// AddressSanitizer reserves terabytes of address space for its shadow
// memory: under an address-space limit every allocation of a sanitized build
// would fail, so such a build bounds the reader by CPU time only.
#if defined(__SANITIZE_ADDRESS__)
#define SWARF_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SWARF_ASAN 1
#endif
#endif
#ifdef SWARF_ASAN
constexpr bool kAddressLimit = false;
#else
constexpr bool kAddressLimit = true;
#endif

/// In a sanitized build the child's reports go to its stderr, not to the
/// report files the sanitized suite fails on (ASAN_OPTIONS=log_path): the
/// child is where OpenVDB's unhardened reader may fail on a damaged file (an
/// allocation too big for ASan, where a plain build throws bad_alloc), which
/// the parent turns into an error as it does a crash.
void quiet_sanitizer_reports() {
#ifdef SWARF_ASAN
  __sanitizer_set_report_fd(reinterpret_cast<void *>(2));
#endif
}

void apply_limits(const IsolateLimits &limits) {
  struct rlimit cpu = {limits.cpu_seconds, limits.cpu_seconds + 1};
  if (limits.cpu_seconds) ::setrlimit(RLIMIT_CPU, &cpu);
  struct rlimit as = {limits.address_space, limits.address_space};
  if (kAddressLimit && limits.address_space) ::setrlimit(RLIMIT_AS, &as);
  ::signal(SIGPIPE, SIG_DFL);
}

std::string error_reply(int status, const std::string &message) {
  std::string r(1, 'E');
  r.append(reinterpret_cast<const char *>(&status), sizeof status);
  return r.append(message);
}

/// The child's side: run body, send its result or its error, exit.
[[noreturn]] void child_main(int fd, const std::string &what, const IsolateLimits &limits,
                             const std::function<std::string()> &body) {
  apply_limits(limits);
  quiet_sanitizer_reports();
  std::string reply;
  try {
    reply = 'D' + body();
  } catch (const Error &e) {
    reply = error_reply(e.status, e.what());
  } catch (const std::bad_alloc &) {
    reply = error_reply(SWARF_ERR_FORMAT, what + ": needs more memory than allowed (" +
                                              std::to_string(limits.address_space >> 20) +
                                              " MB): not a readable stock");
  } catch (const std::exception &e) {
    reply = error_reply(SWARF_ERR_FORMAT, e.what());
  } catch (...) {
    reply = error_reply(SWARF_ERR_FORMAT, "unknown failure");
  }
  _exit(write_all(fd, reply.data(), reply.size()) ? 0 : 1);
}

/// Why a child that sent no complete answer failed, in words.
std::string child_failure(int wstatus) {
  if (WIFSIGNALED(wstatus)) {
    const int sig = WTERMSIG(wstatus);
    if (sig == SIGXCPU || sig == SIGKILL) return "it takes too long to read (CPU time limit)";
    return std::string("OpenVDB's reader crashed on it (") + strsignal(sig) + ")";
  }
  return "the reader failed (exit status " + std::to_string(WEXITSTATUS(wstatus)) + ")";
}

} // namespace

void run_isolated(const std::string &what, const IsolateLimits &limits,
                  const std::function<std::string()> &body, std::string &out) {
  int fds[2];
  if (::pipe(fds) != 0)
    throw Error(SWARF_ERR_IO, what + ": cannot create a pipe: " + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(fds[0]), ::close(fds[1]);
    throw Error(SWARF_ERR_IO, what + ": cannot fork: " + std::strerror(err));
  }
  if (pid == 0) {
    ::close(fds[0]);
    child_main(fds[1], what, limits, body);
  }
  ::close(fds[1]);
  std::string reply = read_all(fds[0]);
  ::close(fds[0]);
  int wstatus = 0;
  while (::waitpid(pid, &wstatus, 0) < 0 && errno == EINTR) {
  }
  const bool exited_ok = WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 0;
  if (!exited_ok || reply.empty())
    throw Error(SWARF_ERR_FORMAT, what + ": " + child_failure(wstatus));
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

} // namespace swarf
