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
 * Under cutter compensation the last move (and the calls after it) is held
 * over to the next block, as LinuxCNC does; the end of the program lets it
 * go.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gcode_private.h"

#define READ_CHUNK (64 * 1024)

static int set_error(swarf_gcode_parser *p, int status, int column, const char *message) {
  p->status = status;
  p->error.line = p->cur_line;
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

/* ---- canon text ------------------------------------------------------- */

static void canon_line(swarf_gcode_parser *p, const char *nfield, const char *call) {
  char buf[512];
  if (p->canon == NULL) return;
  if (strlen(call) + 32 < sizeof buf) {
    snprintf(buf, sizeof buf, "%5ld %s %s", ++p->seq, nfield, call);
    p->canon(buf, p->canon_user);
  } else {
    size_t n = strlen(call) + 32;
    char *big = malloc(n);
    if (big == NULL) return;
    snprintf(big, n, "%5ld %s %s", ++p->seq, nfield, call);
    p->canon(big, p->canon_user);
    free(big);
  }
}

static void canon_start(swarf_gcode_parser *p) {
  static const char *pre[] = {"USE_LENGTH_UNITS(CANON_UNITS_MM)",
                              "SET_G5X_OFFSET(1, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
                              "SET_G92_OFFSET(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
                              "SET_XY_ROTATION(0.0000)",
                              "SET_FEED_REFERENCE(CANON_XYZ)",
                              "ON_RESET()"};
  if (p->canon_started || p->canon == NULL) return;
  p->canon_started = 1;
  for (size_t i = 0; i < sizeof pre / sizeof pre[0]; i++)
    canon_line(p, "N.....", pre[i]);
}

/* rs274's N field: "N123" (fraction dropped) if the block starts with an
 * N word, else "N.....". */
static void n_field(const char *text, size_t n, char out[24]) {
  size_t i = 0, k = 1;
  while (i < n && (text[i] == ' ' || text[i] == '\t' || text[i] == '/'))
    i++;
  if (i < n && (text[i] == 'N' || text[i] == 'n')) {
    out[0] = 'N';
    for (i++; i < n && k < 12; i++) {
      if (text[i] == ' ' || text[i] == '\t') continue;
      if (text[i] < '0' || text[i] > '9') break;
      out[k++] = text[i];
    }
    out[k] = '\0';
    if (k > 1) return;
  }
  strcpy(out, "N.....");
}

static void print_call(swarf_gcode_parser *p, const swarf_gc_call *c, const char *nf) {
  char buf[400];
  const double *v = c->prog;
  switch (c->kind) {
  case SWARF_GC_CALL_TEXT:
    canon_line(p, nf, p->out.text + c->text_at);
    return;
  case SWARF_GC_CALL_TRAVERSE:
  case SWARF_GC_CALL_FEED:
    snprintf(buf, sizeof buf, "%s(%.4f, %.4f, %.4f, %.4f, %.4f, %.4f)",
             c->kind == SWARF_GC_CALL_FEED ? "STRAIGHT_FEED" : "STRAIGHT_TRAVERSE", v[0], v[1],
             v[2], v[3], v[4], v[5]);
    break;
  case SWARF_GC_CALL_ARC:
    snprintf(buf, sizeof buf, "ARC_FEED(%.4f, %.4f, %.4f, %.4f, %d, %.4f, %.4f, %.4f, %.4f)", v[0],
             v[1], v[2], v[3], (int)v[4], v[5], v[6], v[7], v[8]);
    break;
  case SWARF_GC_CALL_DWELL:
    snprintf(buf, sizeof buf, "DWELL(%.4f)", v[0]);
    break;
  default:
    return;
  }
  canon_line(p, nf, buf);
}

/* ---- blocks ------------------------------------------------------------ */

static int emit(swarf_gcode_parser *p, const char *text, size_t n) {
  char nf[24];
  if (p->canon != NULL) n_field(text, n, nf);
  for (size_t i = 0; i < p->out.ready; i++) {
    swarf_gc_call *c = &p->out.calls[i];
    if (p->canon != NULL) print_call(p, c, nf);
    if (c->kind == SWARF_GC_CALL_TEXT) continue;
    if (p->fn != NULL && p->fn(&c->move, p->user) != 0)
      return set_error(p, SWARF_GCODE_ERR_STOPPED, c->move.column, "stopped by the move callback");
  }
  return SWARF_GCODE_OK;
}

static void apply_assigns(swarf_gcode_parser *p, const swarf_gc_block *b) {
  for (int i = 0; i < b->assign_count; i++) {
    const swarf_gc_assign *a = &b->assigns[i];
    if (a->index > 0)
      swarf_gc_param_set(&p->params, p->state, a->index, a->value);
    else
      swarf_gc_param_set_named(&p->params, a->name, a->value);
  }
}

static int fault_error(swarf_gcode_parser *p, const swarf_gc_fault *f) {
  return set_error(p, f->status, f->column, f->message);
}

/* Starts a block's out list, after the calls held from the last blocks. */
static void out_start(swarf_gcode_parser *p) {
  swarf_gc_out_start(&p->out, &p->held, p->cur_line);
}

/* Keeps the calls the committed block still holds for the next one: the
 * earlier held calls stay if the block did not take them. */
static void out_keep(swarf_gcode_parser *p) {
  if (p->out.pending == 0) swarf_gc_out_reset(&p->held);
  if (p->out.ready < p->out.count) swarf_gc_out_append_held(&p->held, &p->out, p->out.ready);
  if (p->held.overflow) set_error(p, SWARF_GCODE_ERR_MEMORY, 1, "out of memory");
}

/* The end of the program without M2: held calls go out as they are. */
static int release_held(swarf_gcode_parser *p) {
  if (p->held.count == 0 || p->status != SWARF_GCODE_OK) return p->status;
  out_start(p);
  swarf_gc_out_flush(&p->out, p->state);
  swarf_gc_out_reset(&p->held);
  return emit(p, "", 0);
}

/* Read, check, execute on a copy; commit only if all of it succeeded. */
static int run_block(swarf_gcode_parser *p, const char *text, size_t n) {
  swarf_gc_block b;
  swarf_gc_fault f;
  swarf_gc_state *next = p->state == &p->states[0] ? &p->states[1] : &p->states[0];
  swarf_gc_exec ex = {&p->params, &p->out, p->tools, SWARF_GC_NTOOLS};
  int status;
  *next = *p->state;
  out_start(p);
  status = swarf_gc_block_read(text, n, &p->params, &b, &f);
  if (status == SWARF_GCODE_OK) status = swarf_gc_block_check(&b, p->state, &f);
  if (status == SWARF_GCODE_OK) status = swarf_gc_execute(&b, next, &ex, &f);
  if (status != SWARF_GCODE_OK) return fault_error(p, &f);
  p->state = next; /* commit: the copy becomes the state */
  p->params.state = next;
  apply_assigns(p, &b);
  p->ended = next->ended;
  status = emit(p, text, n);
  out_keep(p);
  if (p->ended && p->canon != NULL) {
    canon_line(p, "N.....", "ON_RESET()");
    canon_line(p, "N.....", "ON_RESET()");
  }
  return status;
}

/* The flow's callback for an ordinary line (streamed or stored). */
static int run_line(void *ctx, const char *text, size_t n, long line) {
  swarf_gcode_parser *p = ctx;
  size_t first = skip_blanks(text, n, 0);
  if (p->ended || p->status != SWARF_GCODE_OK) return p->status;
  p->cur_line = line;
  if (first == n || text[first] == '/') return SWARF_GCODE_OK;
  return run_block(p, text, n);
}

/* A line made of `%` alone: opens the program first, closes it later. */
static int percent_line(swarf_gcode_parser *p, size_t at) {
  if (!p->seen_code) {
    p->seen_code = 1;
    p->percent_open = 1;
    return SWARF_GCODE_OK;
  }
  if (p->percent_open) {
    release_held(p);
    p->ended = 1;
    if (p->canon != NULL) {
      canon_line(p, "N.....", "FINISH()");
      canon_line(p, "N.....", "ON_RESET()");
      canon_line(p, "N.....", "ON_RESET()");
    }
    return SWARF_GCODE_OK;
  }
  return set_error(p, SWARF_GCODE_ERR_SYNTAX, (int)at + 1,
                   "Bad character '%' used (the program did not open with a % line)");
}

static int process_line(swarf_gcode_parser *p, const char *text, size_t n) {
  size_t first, rest;
  swarf_gc_fault f;
  long err_line;
  int status;
  p->lines++;
  p->cur_line = p->lines;
  canon_start(p);
  if (n > SWARF_GC_LINE_MAX)
    return set_error(p, SWARF_GCODE_ERR_SYNTAX, 1, "line too long (more than 1 MiB)");
  first = skip_blanks(text, n, 0);
  if (first == n) return SWARF_GCODE_OK;
  rest = skip_blanks(text, n, first + 1);
  if (text[first] == '%' && rest == n) return percent_line(p, first);
  p->seen_code = 1;
  if (text[first] == '/') return SWARF_GCODE_OK;
  status = swarf_gc_flow_line(p->flow, text, n, p->lines, &err_line, &f);
  if (status != SWARF_GCODE_OK && p->status == SWARF_GCODE_OK) {
    p->cur_line = err_line;
    return fault_error(p, &f);
  }
  return p->status;
}

/* Keeps bytes of an unterminated line; refuses to hold more than a line may be. */
static int keep_partial(swarf_gcode_parser *p, const char *s, size_t n) {
  size_t need = p->partial_len + n;
  if (need > SWARF_GC_LINE_MAX) {
    p->cur_line = ++p->lines;
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

/* Without a table, rs274's built-in one: tools 1-3 (inches). */
static void default_tools(swarf_gcode_parser *p) {
  static const double z[3] = {0.511, 0.1, 1.273};
  for (int t = 0; t < SWARF_GC_NTOOLS; t++)
    p->tools[t][0] = NAN, p->tools[t][1] = 0;
  for (int t = 1; t <= 3; t++)
    p->tools[t][0] = z[t - 1] * SWARF_GC_MM_PER_INCH;
}

swarf_gcode_parser *swarf_gcode_parser_new(const char *filename, swarf_gcode_move_fn fn,
                                           void *user) {
  swarf_gcode_parser *p = calloc(1, sizeof *p);
  if (p == NULL) return NULL;
  p->fn = fn;
  p->user = user;
  p->state = &p->states[0];
  swarf_gc_state_init(p->state);
  swarf_gc_params_init(&p->params);
  p->params.state = p->state;
  swarf_gc_out_init(&p->out);
  swarf_gc_out_init(&p->held);
  default_tools(p);
  p->flow = swarf_gc_flow_new(&p->params, run_line, p);
  if (p->flow == NULL) {
    free(p);
    return NULL;
  }
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
  if (p->status == SWARF_GCODE_OK && !p->ended && !p->finished &&
      swarf_gc_flow_open_line(p->flow) > 0) {
    p->cur_line = swarf_gc_flow_open_line(p->flow);
    set_error(p, SWARF_GCODE_ERR_SEMANTIC, 1,
              "The program ended inside an O-word construct opened here");
  }
  release_held(p);
  p->finished = 1;
  return p->status;
}

int swarf_gcode_parser_set_canon(swarf_gcode_parser *p, swarf_gcode_canon_fn fn, void *user) {
  if (p == NULL || p->lines > 0) return SWARF_GCODE_ERR_ARG;
  p->canon = fn;
  p->canon_user = user;
  p->out.want_text = fn != NULL;
  p->held.want_text = fn != NULL;
  return SWARF_GCODE_OK;
}

/* One tool table line: T<n> then words like Z0.5 D0.25; ';' comments. */
static void tool_line(swarf_gcode_parser *p, const char *line) {
  int t = -1;
  double z = 0, d = 0;
  for (const char *s = line; *s && *s != ';'; s++) {
    char c = (char)(*s & ~0x20);
    if (c == 'T') t = atoi(s + 1);
    if (c == 'Z') z = atof(s + 1);
    if (c == 'D') d = atof(s + 1);
  }
  if (t > 0 && t < SWARF_GC_NTOOLS) {
    p->tools[t][0] = z * SWARF_GC_MM_PER_INCH;
    p->tools[t][1] = d * SWARF_GC_MM_PER_INCH;
  }
}

int swarf_gcode_parser_load_tools(swarf_gcode_parser *p, const char *path, swarf_gcode_error *err) {
  char line[512];
  FILE *in;
  if (p == NULL || path == NULL) return SWARF_GCODE_ERR_ARG;
  in = fopen(path, "r");
  if (in == NULL) {
    if (err != NULL) {
      memset(err, 0, sizeof *err);
      snprintf(err->file, sizeof err->file, "%s", path);
      snprintf(err->message, sizeof err->message, "cannot open tool table: %s", strerror(errno));
    }
    return SWARF_GCODE_ERR_ARG;
  }
  for (int t = 0; t < SWARF_GC_NTOOLS; t++)
    p->tools[t][0] = NAN, p->tools[t][1] = 0;
  while (fgets(line, sizeof line, in) != NULL)
    tool_line(p, line);
  fclose(in);
  return SWARF_GCODE_OK;
}

int swarf_gcode_parser_clear_tools(swarf_gcode_parser *p) {
  if (p == NULL || p->lines > 0) return SWARF_GCODE_ERR_ARG;
  for (int t = 0; t < SWARF_GC_NTOOLS; t++)
    p->tools[t][0] = NAN, p->tools[t][1] = 0;
  return SWARF_GCODE_OK;
}

int swarf_gcode_parser_set_tool(swarf_gcode_parser *p, int tool, double length, double diameter) {
  if (p == NULL || p->lines > 0 || tool < 1 || tool >= SWARF_GC_NTOOLS) return SWARF_GCODE_ERR_ARG;
  if (!isfinite(length) || !isfinite(diameter) || diameter < 0) return SWARF_GCODE_ERR_ARG;
  p->tools[tool][0] = length;
  p->tools[tool][1] = diameter;
  return SWARF_GCODE_OK;
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
  swarf_gc_flow_free(p->flow);
  swarf_gc_params_clear(&p->params);
  swarf_gc_out_clear(&p->out);
  swarf_gc_out_clear(&p->held);
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
