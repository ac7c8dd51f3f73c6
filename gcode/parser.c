/* parser.c -- the streaming front: bytes -> lines -> blocks -> moves.
 *
 * The parser owns its state, its error and one partial line (the bytes after
 * the last newline, kept until the newline arrives; never longer than
 * SWARF_GC_LINE_MAX). Memory does not grow with the program.
 *
 * Per line, as LinuxCNC reads a file: blank lines are skipped; a first
 * non-blank line made of `%` alone opens the program and a later such line
 * ends it; `/` first on a line deletes the block (block delete on); M2/M30
 * end the program. Anything after the end is not read. Every other line is
 * read, checked and executed on a copy of the state (see gcode_private.h):
 * the state and the moves are committed only when the whole block is good.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gcode_private.h"

#define READ_CHUNK (64 * 1024)

struct swarf_gcode_parser {
  swarf_gcode_move_fn fn;
  void *user;
  swarf_gc_state state;
  swarf_gcode_error error; /* .file holds the program's name from the start */
  int status;              /* first error, sticky */
  long lines;              /* lines read so far */
  int seen_code;           /* a non-blank line was read */
  int percent_open;        /* the program opened with a `%` line */
  int ended;               /* M2, M30 or a closing `%` */
  int finished;            /* swarf_gcode_parser_finish was called */
  char *partial;           /* the unterminated line so far */
  size_t partial_len, partial_cap;
};

static int set_error(swarf_gcode_parser *p, int status, int column, const char *message) {
  p->status = status;
  p->error.line = p->lines;
  p->error.column = column;
  snprintf(p->error.message, sizeof p->error.message, "%s", message);
  return status;
}

static int is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

static size_t skip_blanks(const char *text, size_t n, size_t i) {
  while (i < n && is_blank(text[i]))
    i++;
  return i;
}

/* A line made of `%` alone: opens the program first, closes it later. */
static int percent_line(swarf_gcode_parser *p, size_t at) {
  if (!p->seen_code) {
    p->seen_code = 1;
    p->percent_open = 1;
    return SWARF_GCODE_OK;
  }
  if (p->percent_open) {
    p->ended = 1;
    return SWARF_GCODE_OK;
  }
  return set_error(p, SWARF_GCODE_ERR_SYNTAX, (int)at + 1,
                   "Bad character '%' used (the program did not open with a % line)");
}

static int emit(swarf_gcode_parser *p, swarf_gc_moves *out) {
  for (int i = 0; i < out->count; i++) {
    out->moves[i].line = p->lines;
    if (p->fn != NULL && p->fn(&out->moves[i], p->user) != 0)
      return set_error(p, SWARF_GCODE_ERR_STOPPED, out->moves[i].column,
                       "stopped by the move callback");
  }
  return SWARF_GCODE_OK;
}

/* Read, check, execute on a copy; commit only if all of it succeeded. */
static int run_block(swarf_gcode_parser *p, const char *text, size_t n) {
  swarf_gc_block b;
  swarf_gc_fault f;
  swarf_gc_state next = p->state;
  swarf_gc_moves out;
  int status;
  out.count = 0;
  status = swarf_gc_block_read(text, n, &b, &f);
  if (status == SWARF_GCODE_OK) status = swarf_gc_block_check(&b, &p->state, &f);
  if (status == SWARF_GCODE_OK) status = swarf_gc_execute(&b, &next, &out, &f);
  if (status != SWARF_GCODE_OK) return set_error(p, status, f.column, f.message);
  p->state = next;
  p->ended = next.ended;
  return emit(p, &out);
}

static int process_line(swarf_gcode_parser *p, const char *text, size_t n) {
  size_t first, rest;
  p->lines++;
  if (n > SWARF_GC_LINE_MAX)
    return set_error(p, SWARF_GCODE_ERR_SYNTAX, 1, "line too long (more than 1 MiB)");
  first = skip_blanks(text, n, 0);
  if (first == n) return SWARF_GCODE_OK;
  rest = skip_blanks(text, n, first + 1);
  if (text[first] == '%' && rest == n) return percent_line(p, first);
  p->seen_code = 1;
  if (text[first] == '/') return SWARF_GCODE_OK;
  return run_block(p, text, n);
}

/* Keeps bytes of an unterminated line; refuses to hold more than a line may be. */
static int keep_partial(swarf_gcode_parser *p, const char *s, size_t n) {
  size_t need = p->partial_len + n;
  if (need > SWARF_GC_LINE_MAX) {
    p->lines++;
    return set_error(p, SWARF_GCODE_ERR_SYNTAX, 1, "line too long (more than 1 MiB)");
  }
  if (need > p->partial_cap) {
    size_t cap = p->partial_cap ? p->partial_cap : 256;
    char *grown;
    while (cap < need)
      cap *= 2;
    grown = realloc(p->partial, cap);
    if (grown == NULL) return set_error(p, SWARF_GCODE_ERR_MEMORY, 1, "out of memory");
    p->partial = grown;
    p->partial_cap = cap;
  }
  memcpy(p->partial + p->partial_len, s, n);
  p->partial_len = need;
  return SWARF_GCODE_OK;
}

/* A whole line has arrived: its head may wait in `partial`. */
static int complete_line(swarf_gcode_parser *p, const char *s, size_t n) {
  int status;
  if (p->partial_len == 0) return process_line(p, s, n);
  status = keep_partial(p, s, n);
  if (status == SWARF_GCODE_OK) status = process_line(p, p->partial, p->partial_len);
  p->partial_len = 0;
  return status;
}

swarf_gcode_parser *swarf_gcode_parser_new(const char *filename, swarf_gcode_move_fn fn,
                                           void *user) {
  swarf_gcode_parser *p = calloc(1, sizeof *p);
  if (p == NULL) return NULL;
  p->fn = fn;
  p->user = user;
  swarf_gc_state_init(&p->state);
  snprintf(p->error.file, sizeof p->error.file, "%s", filename ? filename : "");
  return p;
}

int swarf_gcode_parser_feed(swarf_gcode_parser *p, const char *buf, size_t len) {
  const char *s = buf, *end = buf + len;
  if (p == NULL || (buf == NULL && len > 0)) return SWARF_GCODE_ERR_ARG;
  if (p->status != SWARF_GCODE_OK) return p->status;
  if (p->finished) return SWARF_GCODE_ERR_ARG;
  while (s < end && !p->ended && p->status == SWARF_GCODE_OK) {
    const char *nl = memchr(s, '\n', (size_t)(end - s));
    if (nl == NULL) return keep_partial(p, s, (size_t)(end - s));
    complete_line(p, s, (size_t)(nl - s));
    s = nl + 1;
  }
  return p->status;
}

int swarf_gcode_parser_finish(swarf_gcode_parser *p) {
  if (p == NULL) return SWARF_GCODE_ERR_ARG;
  if (p->status == SWARF_GCODE_OK && !p->ended && !p->finished && p->partial_len > 0) {
    process_line(p, p->partial, p->partial_len);
    p->partial_len = 0;
  }
  p->finished = 1;
  return p->status;
}

const swarf_gcode_error *swarf_gcode_parser_error(const swarf_gcode_parser *p) {
  return (p != NULL && p->status != SWARF_GCODE_OK) ? &p->error : NULL;
}

long swarf_gcode_parser_lines(const swarf_gcode_parser *p) {
  return p ? p->lines : 0;
}

int swarf_gcode_parser_ended(const swarf_gcode_parser *p) {
  return p ? p->ended : 0;
}

void swarf_gcode_parser_free(swarf_gcode_parser *p) {
  if (p == NULL) return;
  free(p->partial);
  free(p);
}

static int file_error(swarf_gcode_error *err, const char *path, const char *what) {
  if (err != NULL) {
    memset(err, 0, sizeof *err);
    snprintf(err->file, sizeof err->file, "%s", path);
    snprintf(err->message, sizeof err->message, "%s", what);
  }
  return SWARF_GCODE_ERR_ARG;
}

static int stream_file(FILE *in, swarf_gcode_parser *p, const char *path, swarf_gcode_error *err) {
  char *chunk = malloc(READ_CHUNK);
  int status = SWARF_GCODE_OK;
  size_t got;
  if (chunk == NULL) {
    file_error(err, path, "out of memory");
    return SWARF_GCODE_ERR_MEMORY;
  }
  while (status == SWARF_GCODE_OK && !p->ended && (got = fread(chunk, 1, READ_CHUNK, in)) > 0)
    status = swarf_gcode_parser_feed(p, chunk, got);
  free(chunk);
  if (status == SWARF_GCODE_OK && ferror(in)) return file_error(err, path, "cannot read file");
  return status;
}

int swarf_gcode_parse_file(const char *path, swarf_gcode_move_fn fn, void *user,
                           swarf_gcode_error *err) {
  swarf_gcode_parser *p;
  FILE *in;
  int status;
  char why[200];
  if (path == NULL) return file_error(err, "", "no file name given");
  in = fopen(path, "rb");
  if (in == NULL) {
    snprintf(why, sizeof why, "cannot open file: %s", strerror(errno));
    return file_error(err, path, why);
  }
  p = swarf_gcode_parser_new(path, fn, user);
  if (p == NULL) {
    fclose(in);
    return file_error(err, path, "out of memory");
  }
  status = stream_file(in, p, path, err);
  fclose(in);
  if (status == SWARF_GCODE_OK) status = swarf_gcode_parser_finish(p);
  if (status != SWARF_GCODE_OK && err != NULL && swarf_gcode_parser_error(p) != NULL)
    *err = *swarf_gcode_parser_error(p);
  swarf_gcode_parser_free(p);
  return status;
}
