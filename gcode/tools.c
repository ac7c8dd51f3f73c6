/* SPDX-License-Identifier: MPL-2.0 */
/* tools.c -- the tool table of `swarf parse --tools` (swarf_gcode_parser_load_tools).
 *
 * LinuxCNC's format (src/emc/tooldata): one tool a line, `T1 P1 Z0.511
 * D0.125 ;comment`, values in inches (rs274 without an INI file). Where
 * LinuxCNC skips a line it cannot read, this reader refuses the table at
 * TABLE:LINE (the word in the error's word): unknown letters, numbers that
 * are not whole, finite numbers, negative diameters, T outside 0..999,
 * a tool twice, a line without T, NUL bytes, lines over LINE_MAX characters
 * (read whole or refused, never split). Only a regular file of at most
 * FILE_MAX bytes is read (swarf_file.h). The table is set only when all of
 * it was read.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gcode_private.h"
#include "swarf_file.h"

#define LINE_MAX_CHARS 4096           /* longest table line accepted */
#define FILE_MAX ((long long)1 << 24) /* 16 MiB: 999 tools need far less */

typedef struct {
  const char *path;
  long line;
  swarf_error *err;
} table_at;

/* err at TABLE:LINE, naming `word`. */
static swarf_error *at_line(const table_at *at, const char *word) {
  swarf_error_at(at->err, at->path, at->line, 0, word);
  return at->err;
}

/* The number after a word's letter: all of it, finite. */
static int word_value(const char *w, double *v) {
  char *end;
  errno = 0;
  *v = strtod(w + 1, &end);
  return end != w + 1 && *end == '\0' && errno == 0 && isfinite(*v) ? 0 : -1;
}

/* One word into tool *t, length *z and diameter *d (inches). */
static swarf_status table_word(const table_at *at, const char *w, int *t, double *z, double *d) {
  const char letter = (char)toupper((unsigned char)w[0]);
  double v;
  if (w[0] == '\0' || strchr("TPDZXYABCUVWIJQ", letter) == NULL)
    return SWARF_GC_ERROR(SWARF_GCODE_E_TOOL_TABLE_WORD, at_line(at, w), w);
  if (word_value(w, &v) != 0)
    return SWARF_GC_ERROR(SWARF_GCODE_E_TOOL_TABLE_NUMBER, at_line(at, w), w);
  if (strchr("TPQ", letter) && v != floor(v))
    return SWARF_GC_ERROR(SWARF_GCODE_E_TOOL_TABLE_VALUE, at_line(at, w), w,
                          "T, P and Q take whole numbers");
  if (letter == 'T' && (v < 0 || v >= SWARF_GC_NTOOLS))
    return SWARF_GC_ERROR(SWARF_GCODE_E_TOOL_TABLE_VALUE, at_line(at, w), w,
                          "tool numbers run from 0 to 999");
  if ((letter == 'P' || letter == 'D') && v < 0)
    return SWARF_GC_ERROR(SWARF_GCODE_E_TOOL_TABLE_VALUE, at_line(at, w), w,
                          letter == 'P' ? "a pocket number is 0 or more"
                                        : "a diameter cannot be negative");
  if (letter == 'Z' && !(fabs(v) <= 400)) /* inches: 10 m */
    return SWARF_GC_ERROR(SWARF_GCODE_E_TOOL_TABLE_VALUE, at_line(at, w), w,
                          "a length offset beyond 10 m (a typo or a unit slip?)");
  if (letter == 'T') *t = (int)v + 1; /* 0: no T word (T0 is tool 0, the empty spindle) */
  if (letter == 'Z') *z = v;
  if (letter == 'D') *d = v;
  return SWARF_OK;
}

/* One line (NUL-terminated, comment included): *t is -1 without a tool. */
static swarf_status table_line(const table_at *at, char *text, int *t, double *z, double *d) {
  char *semi = strchr(text, ';'), *save = NULL;
  int words = 0;
  *t = 0;
  *z = *d = 0;
  if (semi != NULL) *semi = '\0';
  for (char *w = strtok_r(text, " \t\r\n\v\f", &save); w != NULL;
       w = strtok_r(NULL, " \t\r\n\v\f", &save), words++) {
    swarf_status s = table_word(at, w, t, z, d);
    if (s != SWARF_OK) return s;
  }
  if (words > 0 && *t == 0) return SWARF_GC_ERROR(SWARF_GCODE_E_TOOL_TABLE_NO_T, at_line(at, ""));
  if (*t > 0)
    (*t)--;
  else
    *t = -1;
  return SWARF_OK;
}

/* The next line into buf (LINE_MAX_CHARS + 1 bytes, NUL-terminated, no
 * newline); *got 0 at the end of the file. */
static swarf_status next_line(FILE *in, char *buf, table_at *at, int *got) {
  size_t n = 0;
  int c;
  *got = 0;
  while ((c = getc(in)) != EOF && c != '\n') {
    if (n == 0 && !*got) at->line++, *got = 1;
    if (c == '\0') return SWARF_GC_ERROR(SWARF_GCODE_E_TOOL_TABLE_BINARY, at_line(at, NULL));
    if (n == LINE_MAX_CHARS)
      return SWARF_GC_ERROR(SWARF_GCODE_E_TOOL_TABLE_LINE_LONG, at_line(at, NULL), LINE_MAX_CHARS);
    buf[n++] = (char)c;
  }
  if (c == '\n' && !*got) at->line++, *got = 1;
  buf[n] = '\0';
  if (ferror(in))
    return SWARF_GC_ERROR(SWARF_GCODE_E_TOOL_TABLE_FILE, at_line(at, NULL), "read error");
  return SWARF_OK;
}

/* The whole table into tools[t] = {length mm, diameter mm}; lines of each tool in seen. */
static swarf_status read_table(FILE *in, table_at *at, double (*tools)[2], long *seen) {
  char *buf = malloc(LINE_MAX_CHARS + 1);
  swarf_status s = SWARF_OK;
  int got = 1, t;
  double z, d;
  if (buf == NULL) return SWARF_GC_ERROR(SWARF_GCODE_E_OUT_OF_MEMORY, at_line(at, NULL));
  while (s == SWARF_OK && (s = next_line(in, buf, at, &got)) == SWARF_OK && got) {
    s = table_line(at, buf, &t, &z, &d);
    if (s != SWARF_OK || t < 0) continue;
    if (seen[t] > 0) {
      char word[16];
      snprintf(word, sizeof word, "T%d", t);
      s = SWARF_GC_ERROR(SWARF_GCODE_E_TOOL_TABLE_TWICE, at_line(at, word), t, seen[t]);
      continue;
    }
    seen[t] = at->line;
    tools[t][0] = z * SWARF_GC_MM_PER_INCH;
    tools[t][1] = d * SWARF_GC_MM_PER_INCH;
  }
  free(buf);
  return s;
}

swarf_status swarf_gcode_parser_load_tools(swarf_gcode_parser *p, const char *path,
                                           swarf_error *err) {
  swarf_error why;
  table_at at = {path, 0, err};
  double(*tools)[2];
  long *seen;
  swarf_status s;
  FILE *in;
  if (p == NULL || path == NULL) return SWARF_ERR_ARG;
  swarf_error_init(err);
  swarf_error_init(&why);
  in = swarf_file_open_input(path, "tool table", FILE_MAX, &why);
  if (in == NULL)
    return SWARF_GC_ERROR(SWARF_GCODE_E_TOOL_TABLE_FILE, at_line(&at, NULL), why.message);
  tools = malloc(sizeof(double[SWARF_GC_NTOOLS][2]));
  seen = calloc(SWARF_GC_NTOOLS, sizeof *seen);
  if (tools == NULL || seen == NULL) {
    s = SWARF_GC_ERROR(SWARF_GCODE_E_OUT_OF_MEMORY, at_line(&at, NULL));
  } else {
    for (int t = 0; t < SWARF_GC_NTOOLS; t++)
      tools[t][0] = NAN, tools[t][1] = 0;
    s = read_table(in, &at, tools, seen);
    if (s == SWARF_OK) memcpy(p->tools, tools, sizeof p->tools);
  }
  free(tools);
  free(seen);
  fclose(in);
  return s;
}
