/* SPDX-License-Identifier: MPL-2.0 */
/* swarf_file.h -- opening untrusted input files (engine/base, plain C).
 *
 * Every reader of a user's file (programs, tool tables, tool libraries,
 * parameter files) opens it here: read only, without blocking (a FIFO with
 * no writer does not hang the open), and only if it is a regular file no
 * larger than the reader's bound, so `--tools /dev/zero` or a FIFO is
 * refused at once instead of read for ever. The caller owns the FILE.
 */
#ifndef SWARF_FILE_H
#define SWARF_FILE_H

#include <stdio.h>

#include "swarf_status.h"

/* Opens `path` for reading (binary) if it is a regular file of at most
 * `max_bytes` bytes (0: no bound). NULL on failure with *err (may be NULL)
 * filled: SWARF_ERR_OPEN (cannot open, or not a regular file: a folder, a
 * device, a FIFO, a socket) or SWARF_ERR_LIMIT (larger than max_bytes),
 * the message the reason only, for the caller to put after its own words
 * ("No such file or directory", "the tool table is a FIFO, not a regular
 * file": `what` names the file's role); err's file is `path`. */
FILE *swarf_file_open_input(const char *path, const char *what, long long max_bytes,
                            swarf_error *err);

#endif
