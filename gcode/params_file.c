/* SPDX-License-Identifier: MPL-2.0 */
/* params_file.c -- LinuxCNC's parameter file (the machine's .var file).
 *
 * One parameter a line, "NUMBER VALUE" ("5221\t10.000000"), as LinuxCNC
 * writes it. LinuxCNC skips lines it cannot read; this reader is strict, so
 * that a typo in an offset is an error at its line and not a silent zero:
 * a line is blank, or an integer, blanks and a decimal number, and nothing
 * more. Every value goes through swarf_gcode_parser_set_param; on any error
 * the parser's state is put back as it was.
 */
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gcode_private.h"
#include "swarf_file.h"

/* A decimal number as G-code writes one: [+-]digits[.digits][e[+-]digits]
 * (strtod alone would take "nan", "inf" and hexadecimal). */
static size_t scan_number(const char *s) {
  size_t i = 0, digits = 0;
  if (s[i] == '+' || s[i] == '-') i++;
  while (isdigit((unsigned char)s[i]))
    i++, digits++;
  if (s[i] == '.') {
    i++;
    while (isdigit((unsigned char)s[i]))
      i++, digits++;
  }
  if (digits == 0) return 0;
  if (s[i] == 'e' || s[i] == 'E') {
    size_t j = i + 1;
    if (s[j] == '+' || s[j] == '-') j++;
    if (!isdigit((unsigned char)s[j])) return i;
    while (isdigit((unsigned char)s[j]))
      j++;
    i = j;
  }
  return i;
}

static size_t skip_blanks(const char *s, size_t i) {
  while (s[i] == ' ' || s[i] == '\t' || s[i] == '\r')
    i++;
  return i;
}

/* One line: 0 blank, 1 a parameter in *index and *value, -1 malformed
 * (*column: 1-based, where). */
static int read_line(const char *s, int *index, double *value, int *column) {
  size_t i = skip_blanks(s, 0), n;
  long k = 0;
  if (s[i] == '\0' || s[i] == '\n') return 0;
  *column = (int)i + 1;
  for (n = 0; isdigit((unsigned char)s[i]) && n < 6; i++, n++)
    k = 10 * k + (s[i] - '0');
  if (n == 0 || n == 6 || (s[i] != ' ' && s[i] != '\t')) return -1;
  i = skip_blanks(s, i);
  *column = (int)i + 1;
  n = scan_number(s + i);
  if (n == 0) return -1;
  *value = strtod(s + i, NULL);
  i = skip_blanks(s, i + n);
  if (s[i] != '\0' && s[i] != '\n') {
    *column = (int)i + 1;
    return -1;
  }
  *index = (int)k;
  return 1;
}

/* What a failed load puts back. */
typedef struct {
  swarf_gc_state state;
  double num[SWARF_GC_NPARAMS];
  int params_set, g92_restore;
} saved_setup;

static void save(const swarf_gcode_parser *p, saved_setup *s) {
  s->state = *p->state;
  memcpy(s->num, p->params.num, sizeof s->num);
  s->params_set = p->params_set;
  s->g92_restore = p->g92_restore;
}

static void restore(swarf_gcode_parser *p, const saved_setup *s) {
  *p->state = s->state;
  memcpy(p->params.num, s->num, sizeof s->num);
  p->params_set = s->params_set;
  p->g92_restore = s->g92_restore;
}

/* set_param refused a value: its message stands, the status is the file's. */
static swarf_status bad_value(swarf_error *err) {
  if (err != NULL) err->status = SWARF_ERR_FORMAT;
  return SWARF_ERR_FORMAT;
}

/* The lines of the open file; SWARF_OK or an error at err's line. */
static swarf_status load(swarf_gcode_parser *p, FILE *in, const char *path, swarf_error *err) {
  char *line = NULL;
  size_t cap = 0;
  long lineno = 0;
  swarf_status s = SWARF_OK;
  long *first = calloc(SWARF_GC_NPARAMS, sizeof *first); /* line that set each one */
  if (first == NULL) return SWARF_GC_ERROR(SWARF_GCODE_E_OUT_OF_MEMORY, err);
  while (s == SWARF_OK && getline(&line, &cap, in) != -1) {
    int index = 0, column = 1, kind;
    double value = 0;
    lineno++;
    kind = read_line(line, &index, &value, &column);
    if (kind == 0) continue;
    swarf_error_at(err, path, lineno, column, NULL);
    if (kind < 0)
      s = SWARF_GC_ERROR(SWARF_GCODE_E_PARAMS_LINE, err);
    else if (index >= 1 && index < SWARF_GC_NPARAMS && first[index] != 0)
      s = SWARF_GC_ERROR(SWARF_GCODE_E_PARAMS_TWICE, err, index, first[index]);
    else if (swarf_gcode_parser_set_param(p, index, value, err) != SWARF_OK)
      s = bad_value(err);
    else
      first[index] = lineno;
  }
  if (s == SWARF_OK && ferror(in)) {
    swarf_error_at(err, path, 0, 0, NULL);
    s = SWARF_GC_ERROR(SWARF_GCODE_E_PARAMS_READ, err, strerror(errno));
  }
  free(first);
  free(line);
  return s;
}

swarf_status swarf_gcode_parser_load_params(swarf_gcode_parser *p, const char *path,
                                            swarf_error *err) {
  saved_setup *saved;
  swarf_error why;
  swarf_status s;
  FILE *in;
  if (p == NULL || path == NULL) return SWARF_GC_ERROR(SWARF_GCODE_E_PARAMS_NO_PATH, err);
  if (p->lines > 0 || p->partial_len > 0) return SWARF_GC_ERROR(SWARF_GCODE_E_SETUP_STARTED, err);
  in = swarf_file_open_input(path, "parameter file", (long long)1 << 26, &why);
  if (in == NULL) { /* missing, not a regular file, or over 64 MiB */
    swarf_error_at(err, path, 0, 0, NULL);
    return SWARF_GC_ERROR(SWARF_GCODE_E_PARAMS_OPEN, err, why.message);
  }
  saved = malloc(sizeof *saved);
  if (saved == NULL) {
    fclose(in);
    return SWARF_GC_ERROR(SWARF_GCODE_E_OUT_OF_MEMORY, err);
  }
  save(p, saved);
  s = load(p, in, path, err);
  if (s != SWARF_OK) restore(p, saved);
  free(saved);
  fclose(in);
  return s;
}
