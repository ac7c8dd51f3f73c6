/* SPDX-License-Identifier: MPL-2.0 */
/* stock_output.h -- how the stock module's files reach the disk (plain C).
 *
 * Every file the stock module writes (.vdb, meshes, pictures, and the
 * command line's report through swarf_stock_output_write) goes through
 * one writer (atomic_file.cc) with these rules:
 *  - an existing character device or FIFO named by the user is written into
 *    (`--out /dev/null` discards); a symbolic link, folder, block device or
 *    socket is refused, never replaced;
 *  - a regular file is replaced whole: the content goes to an unnamed file
 *    in the same folder (O_TMPFILE), synced, then linked under a temporary
 *    name PATH.swarf.tmp.PID and renamed onto PATH; where the filesystem has
 *    no O_TMPFILE, PATH.swarf.tmp.PID from the start, removed on SIGINT,
 *    SIGTERM and SIGHUP. Stale ones of dead swarf processes are swept (only
 *    regular files of this user with that marker: never a user's own);
 *  - between swarf_stock_outputs_begin and _commit, files are held unnamed
 *    and published together at the commit (all outputs or none): a failing
 *    mesh leaves the old .vdb in place. kill -9 before the commit leaves
 *    nothing behind (the unnamed files vanish with the process).
 * The group is process-wide: one caller at a time (the command line).
 */
#ifndef SWARF_STOCK_OUTPUT_H
#define SWARF_STOCK_OUTPUT_H

#include <stddef.h>

#include "swarf_status.h"

/* The marker of a temporary's name, between PATH and the process id: an
 * output's name needs room for it and ten digits under NAME_MAX. */
#define SWARF_STOCK_TEMP_MARKER ".swarf.tmp."

#ifdef __cplusplus
extern "C" {
#endif

/* Hold every file written from now on until the commit; installs the
 * signal handlers that remove named temporaries. */
SWARF_API void swarf_stock_outputs_begin(void);
/* Publishes the held files in the order written; SWARF_ERR_IO if one cannot
 * be (those after it are dropped, those before it stay published). */
SWARF_API swarf_status swarf_stock_outputs_commit(swarf_error *err);
/* Drops the held files (nothing is published). */
SWARF_API void swarf_stock_outputs_abort(void);
/* Writes the len bytes at data as the file path by the rules above (held
 * until the commit inside a group): for outputs made outside the stock
 * module (the command line's JSON report). SWARF_ERR_IO (err names the file)
 * if it cannot be written; SWARF_ERR_ARG for a NULL path or data. */
SWARF_API swarf_status swarf_stock_output_write(const char *path, const void *data, size_t len,
                                                swarf_error *err);

#ifdef __cplusplus
}
#endif

#endif
