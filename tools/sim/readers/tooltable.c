/* SPDX-License-Identifier: MPL-2.0 */
/* tooltable.c -- LinuxCNC tool tables (`--tool-table FILE`) into the
 * simulation's tool table.
 *
 * The format is LinuxCNC's (src/emc/tooldata): one tool a line,
 *
 *   T1 P1 D6 Z+30 ;comment
 *
 * words of a letter and a number separated by blanks, text after ';' a
 * comment, lines starting with ';' and blank lines ignored. T (tool number)
 * is required; P pocket, D diameter, Z the G43 length; X Y A B C must be 0
 * (a mill's table: the simulator applies Z only); U V W I J Q (lathe and
 * other-axis fields) are read and ignored. Where LinuxCNC skips a line it
 * cannot read, this reader stops with FILE:LINE: what is wrong; lines over
 * TABLE_LINE_MAX characters and files that are not regular (a device, a
 * FIFO) or over TABLE_FILE_MAX bytes are refused.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assembly.h"
#include "swarf_file.h"

#define TABLE_LINE_MAX 4096                 /* longest line accepted */
#define TABLE_FILE_MAX ((long long)1 << 24) /* 16 MiB, only a regular file */

/* One entry as read, table units converted to mm. */
typedef struct {
  int number; /* 0: T0, LinuxCNC's empty spindle (rs274 reads such a line) */
  int has_t;
  double diameter, length;
} table_entry;

typedef struct {
  const char *path;
  long line;
  swarf_error *err;
} table_place;

/* FILE:LINE: what is wrong (the word, if any, in the error's word). */
static swarf_status bad(const table_place *at, const char *word, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static swarf_status bad(const table_place *at, const char *word, const char *fmt, ...) {
  char what[sizeof at->err->message];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  swarf_error_at(at->err, at->path, at->line, 0, word);
  return swarf_error_set(at->err, SWARF_ERR_TOOL, "%s", what);
}

/* The number after a word's letter: all of it, finite. */
static int word_value(const char *w, double *v) {
  char *end;
  errno = 0;
  *v = strtod(w + 1, &end);
  return end != w + 1 && *end == '\0' && errno == 0 && isfinite(*v) ? 0 : -1;
}

/* One word ("T1", "z+30") into the entry; mm_per_unit scales lengths. */
static swarf_status table_word(const table_place *at, const char *w, double mm_per_unit,
                               table_entry *e) {
  const char letter = (char)toupper((unsigned char)w[0]);
  double v;
  if (strchr("TPDZXYABCUVWIJQ", letter) == NULL || w[0] == '\0')
    return bad(at, w, "unknown word \"%s\" (a tool table has T P D Z X Y A B C U V W I J Q)", w);
  if (word_value(w, &v) != 0) return bad(at, w, "bad number in \"%s\"", w);
  if (strchr("TPQ", letter) && v != floor(v))
    return bad(at, w, "\"%s\": T, P and Q take whole numbers", w);
  switch (letter) {
  case 'T':
    if (v < 0 || v > SWARF_SIM_MAX_TOOL_NUMBER)
      return bad(at, w, "\"%s\": tool numbers run from 0 to %d", w, SWARF_SIM_MAX_TOOL_NUMBER);
    e->number = (int)v;
    e->has_t = 1;
    break;
  case 'P':
    if (v < 0) return bad(at, w, "\"%s\": a pocket number is 0 or more", w);
    break;
  case 'D':
    if (v < 0) return bad(at, w, "\"%s\": a diameter cannot be negative", w);
    e->diameter = v * mm_per_unit;
    break;
  case 'Z':
    if (!(fabs(v * mm_per_unit) <= 1e4))
      return bad(at, w, "\"%s\": a length offset beyond 10 m (a typo or a unit slip?)", w);
    e->length = v * mm_per_unit;
    break;
  case 'X':
  case 'Y':
  case 'A':
  case 'B':
  case 'C':
    if (v != 0) return bad(at, w, "\"%s\": only Z offsets are simulated (X Y A B C must be 0)", w);
    break;
  default: /* U V W I J Q: other machines' fields */
    break;
  }
  return SWARF_OK;
}

/* One line of the table: *e->number stays 0 for a line without a tool. */
static swarf_status table_line(const table_place *at, char *text, double mm_per_unit,
                               table_entry *e) {
  char *semi = strchr(text, ';'), *save = NULL;
  memset(e, 0, sizeof *e);
  if (semi != NULL) *semi = '\0';
  int words = 0;
  for (char *w = strtok_r(text, " \t\r\n\v\f", &save); w != NULL;
       w = strtok_r(NULL, " \t\r\n\v\f", &save), words++) {
    swarf_status s = table_word(at, w, mm_per_unit, e);
    if (s != SWARF_OK) return s;
  }
  if (words > 0 && !e->has_t) return bad(at, "", "no T word (each line is one tool: T<n> ...)");
  return SWARF_OK;
}

/* The table's entry merged into cfg: a new tool is a flat end mill of the
 * table's diameter (no cutter when it is 0); an existing one keeps its
 * description and takes the table's length offset. */
static swarf_status merge_entry(swarf_sim_config *cfg, const table_place *at,
                                const table_entry *e) {
  swarf_sim_tool *t = swarf_sim_tool_slot(cfg, e->number, 0);
  swarf_error why;
  if (t != NULL) {
    t->length = e->length;
    return SWARF_OK;
  }
  t = swarf_sim_tool_slot(cfg, e->number, 1);
  if (t == NULL) return bad(at, "", "too many tools (at most %d)", SWARF_SIM_MAX_TOOLS);
  t->length = e->length;
  if (e->diameter > 0 &&
      swarf_cutter_init(&t->cutter, SWARF_CUTTER_FLAT, e->diameter, 0, 0, &why) != SWARF_OK) {
    swarf_sim_tool_drop(cfg, e->number);
    return bad(at, "", "%s", why.message);
  }
  return SWARF_OK;
}

/* The numbers read so far, to refuse a tool given twice. */
typedef struct {
  int number;
  long line;
} seen_tool;

static swarf_status check_twice(const table_place *at, seen_tool *seen, int *nseen, int number) {
  char what[64];
  for (int i = 0; i < *nseen; i++)
    if (seen[i].number == number) {
      snprintf(what, sizeof what, "T%d", number);
      swarf_error_at(at->err, at->path, at->line, 0, what);
      return swarf_error_set(at->err, SWARF_ERR_TOOL, "T%d is already in the table (line %ld)",
                             number, seen[i].line);
    }
  if (*nseen < SWARF_SIM_MAX_TOOLS) seen[(*nseen)++] = (seen_tool){number, at->line};
  return SWARF_OK;
}

swarf_status swarf_sim_config_load_tool_table(swarf_sim_config *cfg, const char *path,
                                              double mm_per_unit, swarf_error *err) {
  table_place at = {path, 0, err};
  seen_tool seen[SWARF_SIM_MAX_TOOLS];
  int nseen = 0;
  char *text = NULL;
  size_t cap = 0;
  swarf_status s = SWARF_OK;
  if (cfg == NULL || path == NULL || !(mm_per_unit > 0))
    return swarf_error_set(err, SWARF_ERR_ARG, "tool table: no config, path or unit");
  swarf_error why;
  FILE *in = swarf_file_open_input(path, "tool table", TABLE_FILE_MAX, &why);
  if (in == NULL) {
    swarf_error_at(err, path, 0, 0, "--tool-table");
    return swarf_error_set(err, why.status, "cannot open the tool table: %.400s", why.message);
  }
  ssize_t n;
  while (s == SWARF_OK && (n = getline(&text, &cap, in)) >= 0) {
    table_entry e;
    at.line++;
    if (n > TABLE_LINE_MAX)
      s = bad(&at, "", "line longer than %d characters (not a tool table?)", TABLE_LINE_MAX);
    else if ((size_t)n != strlen(text))
      s = bad(&at, "", "a NUL byte in the line (not a text file?)");
    else if ((s = table_line(&at, text, mm_per_unit, &e)) == SWARF_OK && e.number > 0 &&
             (s = check_twice(&at, seen, &nseen, e.number)) == SWARF_OK)
      s = merge_entry(cfg, &at, &e);
  }
  if (s == SWARF_OK && ferror(in)) {
    swarf_error_at(err, path, at.line, 0, "--tool-table");
    s = swarf_error_set(err, SWARF_ERR_IO, "read error: %s", strerror(errno));
  }
  free(text);
  fclose(in);
  return s;
}
