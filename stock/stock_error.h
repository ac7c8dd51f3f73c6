/// @file stock_error.h
/// @brief The module's internal error (a status and a message), without OpenVDB,
/// for the stock/*.cc files that do not need OpenVDB.
#ifndef SWARF_STOCK_ERROR_H
#define SWARF_STOCK_ERROR_H

#include <stdexcept>
#include <string>

#include "stock.h"

namespace swarf {

/// An error carrying a swarf_stock_status; thrown inside the module and turned
/// into a status and a message at the C boundary (see guard() in stock_private.h).
class Error : public std::runtime_error {
public:
  Error(int status, const std::string &what) : std::runtime_error(what), status(status) {}
  int status;
};

/// The status of an Error for an input file that cannot be opened: the old
/// API (int statuses) reports it as SWARF_STOCK_ERR_IO, the swarf_status API
/// as SWARF_ERR_OPEN (the user's to fix).
constexpr int kErrOpen = 100;
/// An input that exceeds a bound on work or memory (SWARF_ERR_LIMIT; the old
/// API's SWARF_STOCK_ERR_MEMORY).
constexpr int kErrLimit = 101;

/// The swarf_status of an Error's status.
inline swarf_status to_swarf_status(int status) {
  switch (status) {
    case SWARF_STOCK_OK: return SWARF_OK;
    case SWARF_STOCK_ERR_ARG: return SWARF_ERR_ARG;
    case SWARF_STOCK_ERR_IO: return SWARF_ERR_IO;
    case SWARF_STOCK_ERR_FORMAT: return SWARF_ERR_FORMAT;
    case SWARF_STOCK_ERR_MEMORY: return SWARF_ERR_MEMORY;
    case kErrOpen: return SWARF_ERR_OPEN;
    case kErrLimit: return SWARF_ERR_LIMIT;
    default: return SWARF_ERR_INTERNAL;
  }
}

/// The old API's status for an Error's status.
inline int to_stock_status(int status) {
  return status == kErrOpen ? SWARF_STOCK_ERR_IO : status == kErrLimit ? SWARF_STOCK_ERR_MEMORY : status;
}

/// Throw Error(SWARF_STOCK_ERR_ARG) unless `path` is a usable file name (not NULL, not empty).
inline void check_path(const char *path) {
  if (path == nullptr || path[0] == '\0') throw Error(SWARF_STOCK_ERR_ARG, "path is NULL or empty");
}

}  // namespace swarf

#endif
