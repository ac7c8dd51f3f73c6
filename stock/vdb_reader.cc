/* SPDX-License-Identifier: MPL-2.0 */
/// @file vdb_reader.cc
/// @brief swarf-vdb-read, the reader program of .vdb files (isolate.h): run by
/// the stock module in a child process, never by hand.
///
///   swarf-vdb-read [--room BYTES] [--] PATH
///
/// reads the stock grid of PATH (io.cc's checks), under an address-space
/// limit of BYTES beyond what it maps once started, with TBB on one thread
/// (memory as a single-threaded read needs it), and writes the grid
/// re-serialized, or the error, on fd 3 in isolate.cc's protocol. Exit
/// status 0 when the reply was written, 1 when it could not be, 2 on a bad
/// command line. In a sanitized build its reports go to stderr, not to the
/// report files of ASAN_OPTIONS=log_path: OpenVDB failing on a damaged file
/// here is expected (the parent turns it into an error as it does a crash).
#include <fcntl.h>

#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "isolate.h"

namespace {

int usage(const char *why) {
  std::fprintf(stderr,
               "swarf-vdb-read: %s\n"
               "usage: swarf-vdb-read [--room BYTES] [--] PATH (reply on fd 3)\n"
               "An internal helper of swarf: it reads a .vdb stock file for swarf in a child\n"
               "process, so that a damaged file cannot take swarf down.\n",
               why);
  return 2;
}

} // namespace

int main(int argc, char **argv) {
#ifdef SWARF_ASAN
  __sanitizer_set_report_fd(reinterpret_cast<void *>(2));
#endif
  swarf::IsolateLimits limits = {0, 0};
  int i = 1;
  for (; i < argc && argv[i][0] == '-'; i++) {
    if (std::strcmp(argv[i], "--") == 0) {
      i++;
      break;
    }
    if (std::strcmp(argv[i], "--room") != 0 || i + 1 >= argc) return usage("unknown option");
    char *end = nullptr;
    limits.room = std::strtoull(argv[++i], &end, 10);
    if (end == argv[i] || *end) return usage("--room takes a number of bytes");
  }
  if (i + 1 != argc) return usage("one PATH expected");
  if (::fcntl(3, F_GETFD) < 0) return usage("fd 3 is not open");
  const std::string path = argv[i];
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  swarf::reader_reply(3, "reading " + path, limits,
                      [&] { return swarf::read_grid_serialized(path); });
}
