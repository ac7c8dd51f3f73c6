/// @file isolate.h
/// @brief Run untrusted parsing in a child process: OpenVDB's reader is not
/// hardened against corrupt files (a damaged .vdb can corrupt its heap), so
/// the stock reads a file in a forked child, which sends back a re-serialized
/// copy of what it read; a crash, a hang or a runaway allocation in the child
/// becomes an error in the caller instead of taking the process down.
#ifndef SWARF_STOCK_ISOLATE_H
#define SWARF_STOCK_ISOLATE_H

#include <cstddef>
#include <functional>
#include <string>

namespace swarf {

/// Limits on the child: CPU seconds and address space (bytes, 0: no limit).
struct IsolateLimits {
  unsigned cpu_seconds;
  size_t address_space;
};

/// Run `body` in a forked child. `body` returns the bytes to hand back in
/// `out`, or throws: an Error's status and message are handed back as they
/// are. Returns normally with `out` filled, or throws Error(FORMAT) saying how
/// the child failed (signal, time limit, memory limit). `what` names the work
/// in messages ("reading x.vdb"). The child runs no other thread: `body` must
/// not start any (no TBB parallel algorithms).
void run_isolated(const std::string &what, const IsolateLimits &limits,
                  const std::function<std::string()> &body, std::string &out);

}  // namespace swarf

#endif
