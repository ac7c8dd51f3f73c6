/* SPDX-License-Identifier: MPL-2.0 */
/// @file isolate.h
/// @brief Run untrusted parsing in another program: OpenVDB's reader is not
/// hardened against corrupt files (a damaged .vdb can corrupt its heap), so
/// the stock reads a file by running the reader program `swarf-vdb-read`
/// (stock/vdb_reader.cc) in a child process (fork, then exec), which sends
/// back a re-serialized copy of what it read; a crash, a hang or a runaway
/// allocation there becomes an error in the caller instead of taking the
/// process down. exec, not a bare fork: the child starts afresh, without the
/// caller's threads, locks (a sanitizer's allocator) or signal handlers (a
/// fuzzer's).
///
/// Where the program is found (the first that exists and is executable):
///   1. $SWARF_VDB_READER, if set (only there: a wrong value is an error);
///   2. beside the running executable (/proc/self/exe) or the library holding
///      this code (dladdr: libswarf.so, the command's stock module), or at
///      LIBEXECDIR/swarf/ relative to either (the installed layout: bin/,
///      LIBDIR/, LIBDIR/swarf/ for the module);
///   3. the install path CMake was configured with (LIBEXECDIR/swarf/);
///   4. in the build tree (BUILD/tools/), when the running program or
///      library is itself below that build tree.
#ifndef SWARF_STOCK_ISOLATE_H
#define SWARF_STOCK_ISOLATE_H

#include <cstddef>
#include <functional>
#include <string>

// SWARF_ASAN: this code is built with AddressSanitizer, which takes no
// address-space limit (its shadow memory) and bounds allocations instead.
#if defined(__SANITIZE_ADDRESS__)
#define SWARF_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SWARF_ASAN 1
#endif
#endif
#ifdef SWARF_ASAN
#include <sanitizer/common_interface_defs.h>
#endif

namespace swarf {

/// Limits on the reading child: CPU seconds (set before exec) and room, the
/// address space (bytes) the reader may map beyond what it maps once started
/// (0: no limit; a sanitized reader cannot take one: ASan maps terabytes of
/// shadow memory, so it bounds each allocation to `room` instead).
struct IsolateLimits {
  unsigned cpu_seconds;
  size_t room;
};

/// The reader program's file name.
constexpr const char *kReaderName = "swarf-vdb-read";

/// The reader program's path (see the file comment), or throws
/// Error(SWARF_ERR_IO) saying where it looked.
std::string reader_program();

/// Run the reader program on `path` under `limits`. Returns normally with
/// `out` holding what the reader sent, or throws: the reader's own Error
/// (status and message), or Error(FORMAT) saying how it failed (signal, time
/// limit, memory limit), or Error(IO) when it cannot be run. `what` names
/// the work in messages ("reading x.vdb").
void run_reader(const std::string &what, const std::string &path, const IsolateLimits &limits,
                std::string &out);

/// The reader program's side: apply limits.room (an address-space limit),
/// run `body`, write its bytes or its error on `fd`, and leave the process
/// with _exit (no destructor, no leak check: OpenVDB leaks on the errors of
/// damaged files). Never returns.
[[noreturn]] void reader_reply(int fd, const std::string &what, const IsolateLimits &limits,
                               const std::function<std::string()> &body);

/// The reader's work (io.cc): read and check the stock grid of `path` in this
/// process and return it serialized as an OpenVDB stream.
std::string read_grid_serialized(const std::string &path);

} // namespace swarf

#endif
