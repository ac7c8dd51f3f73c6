/* SPDX-License-Identifier: MPL-2.0 */
/// @file band_file.h
/// @brief A stock's grid in swarf's own file, read in-process (band_file.cc).
#ifndef SWARF_STOCK_BAND_FILE_H
#define SWARF_STOCK_BAND_FILE_H

#include <cstddef>

#include "stock_private.h"

namespace swarf {

/// Write s's grid to path, atomically: its transform, band and every value.
void write_band_file(const char *path, const swarf_stock &s);

/// A new stock from the bytes of a band file: the grid written, value for
/// value. Throws Error(SWARF_ERR_FORMAT) for anything else: another magic or
/// version, counts that do not fit the size, a checksum that does not
/// match, a node out of range, a grid swarf_stock_read would refuse.
swarf_stock *parse_band_file(const char *data, size_t len);

/// parse_band_file on the file at path (Error(SWARF_ERR_OPEN) if it cannot
/// be opened).
swarf_stock *read_band_file(const char *path);

} // namespace swarf

#endif
