/* SPDX-License-Identifier: MPL-2.0 */
/* status.c -- names, messages and classes of swarf_status (status.def), and
 * the swarf_error record's helpers. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "swarf_status.h"

const char *swarf_status_name(swarf_status s) {
  switch (s) {
#define X(name, value, cls, msg)                                                                   \
  case SWARF_##name:                                                                               \
    return "SWARF_" #name;
#include "status.def"
#undef X
  default:
    return "SWARF_UNKNOWN";
  }
}

const char *swarf_status_message(swarf_status s) {
  switch (s) {
#define X(name, value, cls, msg)                                                                   \
  case SWARF_##name:                                                                               \
    return msg;
#include "status.def"
#undef X
  default:
    return "unknown status";
  }
}

swarf_status_class swarf_status_classify(swarf_status s) {
  switch (s) {
#define X(name, value, cls, msg)                                                                   \
  case SWARF_##name:                                                                               \
    return SWARF_CLASS_##cls;
#include "status.def"
#undef X
  default:
    return SWARF_CLASS_INTERNAL;
  }
}

void swarf_error_init(swarf_error *e) {
  if (e != NULL) memset(e, 0, sizeof *e);
}

swarf_status swarf_error_set(swarf_error *e, swarf_status s, const char *fmt, ...) {
  va_list ap;
  if (e == NULL) return s;
  e->status = s;
  va_start(ap, fmt);
  vsnprintf(e->message, sizeof e->message, fmt, ap);
  va_end(ap);
  return s;
}

void swarf_error_at(swarf_error *e, const char *file, long line, int column, const char *word) {
  if (e == NULL) return;
  if (file != NULL) snprintf(e->file, sizeof e->file, "%s", file);
  e->line = line;
  e->column = column;
  snprintf(e->word, sizeof e->word, "%s", word != NULL ? word : "");
}

void swarf_error_format(const swarf_error *e, char *buf, size_t len) {
  if (buf == NULL || len == 0) return;
  if (e == NULL) {
    buf[0] = '\0';
    return;
  }
  const char *msg = e->message[0] ? e->message : swarf_status_message(e->status);
  if (e->file[0] && e->line > 0 && e->column > 0)
    snprintf(buf, len, "%s:%ld:%d: %s", e->file, e->line, e->column, msg);
  else if (e->file[0] && e->line > 0)
    snprintf(buf, len, "%s:%ld: %s", e->file, e->line, msg);
  else if (e->file[0])
    snprintf(buf, len, "%s: %s", e->file, msg);
  else
    snprintf(buf, len, "%s", msg);
}
