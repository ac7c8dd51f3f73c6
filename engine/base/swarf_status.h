/* SPDX-License-Identifier: MPL-2.0 */
/* swarf_status.h -- the one status type of the project, and the error record.
 *
 * Role: every public function of libswarf that can fail returns a
 * swarf_status; the codes, their names and generic messages come from one
 * table (status.def). Where a failure has a place in an input (a G-code
 * block, a tool-table line, an option), the callee also fills a swarf_error:
 * the status, a detail code that identifies the error exactly (for G-code the
 * SWARF_GCODE_E_* identities, so tests match codes, not strings), the file,
 * line, column and word, and a message written for the user.
 *
 * This header is the bottom layer: it includes nothing of swarf and every
 * module may include it. No state: thread-safe.
 */
#ifndef SWARF_STATUS_H
#define SWARF_STATUS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Symbols of the shared library are hidden unless marked. */
#if defined(SWARF_BUILDING) && defined(__GNUC__)
#define SWARF_API __attribute__((visibility("default")))
#else
#define SWARF_API
#endif

typedef enum {
#define X(name, value, cls, msg) SWARF_##name = value,
#include "status.def"
#undef X
  SWARF_STATUS_END_
} swarf_status;

/* What a status means for the caller (the CLI's exit status in brackets). */
typedef enum {
  SWARF_CLASS_OK = 0,
  SWARF_CLASS_INTERNAL = 1, /* [1] swarf or the system failed */
  SWARF_CLASS_INPUT = 2,    /* [2] the input is wrong */
  SWARF_CLASS_ABORTED = 3   /* [3] stopped on request */
} swarf_status_class;

/* "SWARF_ERR_SYNTAX"; "SWARF_UNKNOWN" for a value not in the table. */
SWARF_API const char *swarf_status_name(swarf_status s);
/* The generic message of the table. */
SWARF_API const char *swarf_status_message(swarf_status s);
SWARF_API swarf_status_class swarf_status_classify(swarf_status s);

/* Where and why something failed. A value: the caller owns it. */
typedef struct {
  swarf_status status;
  int code;          /* exact identity within the status, 0 if none (gcode.h: SWARF_GCODE_E_*) */
  char file[256];    /* input file (or program name), "" if none */
  long line;         /* 1-based, 0 when not tied to a line */
  int column;        /* 1-based, 0 when unknown */
  char word[32];     /* the offending word or option ("G2", "--voxel"), "" if none */
  char message[512]; /* for the user: what is wrong and, where it helps, what to do */
} swarf_error;

/* Clears e (status SWARF_OK). */
SWARF_API void swarf_error_init(swarf_error *e);
/* Sets status and message (printf format); keeps file, line, column, word.
 * e may be NULL (nothing happens). Returns s, so `return swarf_error_set(...)`. */
SWARF_API swarf_status swarf_error_set(swarf_error *e, swarf_status s, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* Sets the place (file may be NULL: unchanged). */
SWARF_API void swarf_error_at(swarf_error *e, const char *file, long line, int column,
                              const char *word);
/* "file:line:col: message" (parts that are not known are left out) into buf. */
SWARF_API void swarf_error_format(const swarf_error *e, char *buf, size_t len);

#ifdef __cplusplus
}
#endif
#endif
