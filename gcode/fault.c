/* fault.c -- the error record of the G-code front end.
 *
 * Every step (lexer, block, check, interp, arc) reports a failure by filling
 * a swarf_gc_fault with a status, the column on the current line and a
 * message; the parser adds the file name and line number and owns the
 * public swarf_gcode_error.
 */
#include <stdarg.h>
#include <stdio.h>

#include "gcode_private.h"

int swarf_gc_fail(swarf_gc_fault *f, int status, int column, const char *fmt, ...) {
  va_list ap;
  f->status = status;
  f->column = column;
  va_start(ap, fmt);
  vsnprintf(f->message, sizeof f->message, fmt, ap);
  va_end(ap);
  return status;
}
