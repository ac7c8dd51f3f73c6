/* SPDX-License-Identifier: MPL-2.0 */
/* fault.c -- the error record of the G-code front end, and the table of its
 * error identities (errors.def).
 *
 * Every step (lexer, block, check, interp, arc) reports a failure by filling
 * a swarf_error (swarf_status.h) with an identity, its status, the column on
 * the current line and a message; the parser adds the file name, line number
 * and word to its own, which its callers read.
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "gcode_private.h"

typedef struct {
  const char *name;
  swarf_status status;
  const char *format;
} identity;

static const identity identities[] = {
    {"SWARF_GCODE_E_NONE", SWARF_OK, ""},
#define X(id, status, format) {"SWARF_GCODE_E_" #id, SWARF_##status, format},
#include "errors.def"
#undef X
};

static const identity *find(int code) {
  if (code < 0 || code >= (int)(sizeof identities / sizeof identities[0])) return NULL;
  return &identities[code];
}

const char *swarf_gcode_error_name(int code) {
  return find(code) ? find(code)->name : NULL;
}

swarf_status swarf_gcode_error_status(int code) {
  return find(code) ? find(code)->status : SWARF_ERR_INTERNAL;
}

const char *swarf_gcode_error_format(int code) {
  return find(code) ? find(code)->format : NULL;
}

swarf_status swarf_gc_fail(swarf_error *f, int code, const char *format, int column, ...) {
  va_list ap;
  f->status = swarf_gcode_error_status(code);
  f->code = code;
  f->column = column;
  va_start(ap, column);
  vsnprintf(f->message, sizeof f->message, format, ap);
  va_end(ap);
  return f->status;
}

swarf_status swarf_gc_error(int code, const char *format, swarf_error *err, ...) {
  va_list ap;
  if (err == NULL) return swarf_gcode_error_status(code);
  err->status = swarf_gcode_error_status(code);
  err->code = code;
  va_start(ap, err);
  vsnprintf(err->message, sizeof err->message, format, ap);
  va_end(ap);
  return err->status;
}

swarf_status swarf_gc_fail_code(swarf_error *f, int code, int column) {
  const char *s = swarf_gcode_error_format(code);
  size_t k = 0;
  f->status = swarf_gcode_error_status(code);
  f->code = code;
  f->column = column;
  /* Copied, not formatted (the message takes no argument): only "%%" means "%". */
  for (; s != NULL && *s && k + 1 < sizeof f->message; s++) {
    if (s[0] == '%' && s[1] == '%') s++;
    f->message[k++] = *s;
  }
  f->message[k] = '\0';
  return f->status;
}
