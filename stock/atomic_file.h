/* SPDX-License-Identifier: MPL-2.0 */
/// @file atomic_file.h
/// @brief Atomic file output: write <path>.tmp.<pid> in the same folder, sync
/// it, then rename() it onto <path>. A failed write never leaves a partial file.
#ifndef SWARF_STOCK_ATOMIC_FILE_H
#define SWARF_STOCK_ATOMIC_FILE_H

#include <functional>
#include <ostream>

namespace swarf {

/// Write `path` through `body`, which writes the whole content to the stream.
/// On any failure (creating, writing, syncing or renaming the temporary file,
/// or an exception from body) the temporary file is removed and any existing
/// file at `path` is left untouched; the failure is thrown as
/// Error(SWARF_ERR_IO), an exception from body is rethrown as it is.
void write_atomic(const char *path, const std::function<void(std::ostream &)> &body);

} // namespace swarf

#endif
