/* SPDX-License-Identifier: MPL-2.0 */
/// @file stock_error.h
/// @brief The module's internal error (a status and a message), without OpenVDB,
/// for the stock/*.cc files that do not need OpenVDB.
#ifndef SWARF_STOCK_ERROR_H
#define SWARF_STOCK_ERROR_H

#include <stdexcept>
#include <string>

#include "stock.h"

namespace swarf {

/// An error carrying a swarf_status; thrown inside the module and turned into
/// a status and a swarf_error at the C boundary (see guard() in stock_private.h).
class Error : public std::runtime_error {
public:
  Error(swarf_status status, const std::string &what) : std::runtime_error(what), status(status) {}
  swarf_status status;
};

/// Throw Error(SWARF_ERR_ARG) unless `path` is a usable file name (not NULL, not empty).
inline void check_path(const char *path) {
  if (path == nullptr || path[0] == '\0') throw Error(SWARF_ERR_ARG, "path is NULL or empty");
}

} // namespace swarf

#endif
