/* SPDX-License-Identifier: MPL-2.0 */
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
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gcode_private.h"
#include "swarf_file.h"

#define READ_CHUNK (64 * 1024)

static int is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

/* Where the value of a word that goes on at j ends: digits, signs, points,
 * parameter signs and whole [..] or <..> groups. */
static size_t value_end(const char *t, size_t n, size_t j) {
  int depth = 0;
  for (; j < n; j++) {
    char c = t[j];
    if (c == '[' || c == '<')
      depth++;
    else if ((c == ']' || c == '>') && depth > 0)
      depth--;
    else if (depth == 0 && !isdigit((unsigned char)c) && !strchr(".+-#", c))
      break;
  }
  return j;
}

/* The word that starts at `column` of a line, as written: a letter (or a
 * function name) and its value, a parameter, a comment, or the one
 * character there. "" when the column is past the line or not printable. */
static void word_at(const char *text, size_t n, int column, char *out, size_t size) {
  size_t i = column > 0 ? (size_t)column - 1 : n, j, k = 0;
  out[0] = '\0';
  if (text == NULL || i >= n || !isprint((unsigned char)text[i])) return;
  j = i + 1;
  if (text[i] == '(') {
    while (j < n && text[j] != ')')
      j++;
    j += j < n;
  } else if (isalnum((unsigned char)text[i]) || strchr("#[.", text[i])) {
    j = i;
    while (j < n && isalpha((unsigned char)text[j]))
      j++;
    j = value_end(text, n, j);
  }
  for (; i < j && k + 1 < size && isprint((unsigned char)text[i]); i++)
    out[k++] = text[i];
  out[k] = '\0';
}

/* The parser stops on fault `f` at the current line; `text` (may be NULL) is
 * that line, for the word. */
static swarf_status fail(swarf_gcode_parser *p, const swarf_error *f, const char *text, size_t n) {
  p->status = f->status;
  p->error.status = f->status;
  p->error.code = f->code;
  p->error.line = p->cur_line;
  p->error.column = f->column;
  snprintf(p->error.message, sizeof p->error.message, "%s", f->message);
  word_at(text, n, f->column, p->error.word, sizeof p->error.word);
  return p->status;
}

/* The same for an identity whose message takes no argument. */
static swarf_status fail_code(swarf_gcode_parser *p, int code, int column) {
  swarf_error f;
  swarf_gc_fail_code(&f, code, column);
  return fail(p, &f, NULL, 0);
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
    if (c->print == SWARF_GC_PRINT_NONE) return;
    snprintf(buf, sizeof buf, "%s(%.4f, %.4f, %.4f, %.4f, %.4f, %.4f)",
             c->print == SWARF_GC_PRINT_PROBE ? "STRAIGHT_PROBE"
             : c->kind == SWARF_GC_CALL_FEED  ? "STRAIGHT_FEED"
                                              : "STRAIGHT_TRAVERSE",
             v[0], v[1], v[2], v[3], v[4], v[5]);
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

/* Moves and arc turns beyond one a line, run by stored lines, count toward
 * the work bound (a loop of helixes or pecks is as much work as its moves). */
static void charge_work(swarf_gcode_parser *p, long units) {
  if (units > 1 && (p->fanuc_running || swarf_gc_flow_running(p->flow))) p->work_extra += units - 1;
}

static swarf_status emit(swarf_gcode_parser *p, const char *text, size_t n) {
  char nf[24];
  long units = 0;
  if (p->canon != NULL) n_field(text, n, nf);
  for (size_t i = 0; i < p->out.ready; i++) {
    swarf_gc_call *c = &p->out.calls[i];
    if (p->canon != NULL) print_call(p, c, nf);
    if (c->kind == SWARF_GC_CALL_TEXT) continue;
    units +=
        1 + (c->move.kind == SWARF_MOVE_ARC ? (long)(fabs(c->move.angle) / 6.283185307179586) : 0);
    if (p->fn != NULL && p->fn(&c->move, p->user) != 0) {
      swarf_error f;
      SWARF_GC_FAIL(&f, SWARF_GCODE_E_STOPPED, c->move.column);
      return fail(p, &f, text, n);
    }
  }
  charge_work(p, units);
  return SWARF_OK;
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

/* Starts a block's out list, after the calls held from the last blocks. */
static void out_start(swarf_gcode_parser *p) {
  swarf_gc_out_start(&p->out, &p->held, p->cur_line);
}

/* Keeps the calls the committed block still holds for the next one: the
 * earlier held calls stay if the block did not take them. */
static void out_keep(swarf_gcode_parser *p) {
  if (p->out.pending == 0) swarf_gc_out_reset(&p->held);
  if (p->out.ready < p->out.count) swarf_gc_out_append_held(&p->held, &p->out, p->out.ready);
  if (p->held.overflow) fail_code(p, SWARF_GCODE_E_OUT_OF_MEMORY, 1);
}

/* The end of the program without M2: held calls go out as they are. */
static swarf_status release_held(swarf_gcode_parser *p) {
  if (p->held.count == 0 || p->status != SWARF_OK) return p->status;
  out_start(p);
  swarf_gc_out_flush(&p->out, p->state);
  swarf_gc_out_reset(&p->held);
  return emit(p, "", 0);
}

/* LinuxCNC 2.9 reads M98 P<n> too (the block path does not know it): at
 * the first M98 of the streamed program (not inside a construct), the
 * line and the rest of the program are kept whole, as a Fanuc program is,
 * and run at the end (its O<n> ... M99 may come after M2). 1: switched. */
static int m98_switch(swarf_gcode_parser *p, const swarf_error *f, const char *text, size_t n) {
  char word[SWARF_GC_WORD_TEXT];
  swarf_error g;
  if (f->code != SWARF_GCODE_E_UNKNOWN_M_CODE || p->fanuc != NULL ||
      p->state->dialect != SWARF_GCODE_DIALECT_LINUXCNC || p->cur_line != p->lines ||
      swarf_gc_flow_open_line(p->flow) != 0)
    return 0;
  word_at(text, n, f->column, word, sizeof word);
  if (strtod(word + 1, NULL) != 98.0) return 0;
  if ((p->fanuc = swarf_gc_fanuc_new(p)) == NULL)
    return fail_code(p, SWARF_GCODE_E_OUT_OF_MEMORY, 1), 1;
  if (swarf_gc_fanuc_store(p->fanuc, text, n, p->lines, &g) != SWARF_OK) fail(p, &g, text, n);
  return 1;
}

/* Read, check, execute on a copy; commit only if all of it succeeded. */
static swarf_status run_block(swarf_gcode_parser *p, const char *text, size_t n) {
  swarf_gc_block b;
  swarf_error f;
  swarf_gc_state *next = p->state == &p->states[0] ? &p->states[1] : &p->states[0];
  swarf_gc_exec ex = {&p->params, &p->out, p->tools, SWARF_GC_NTOOLS, &p->notes, p->ext};
  int status;
  *next = *p->state;
  p->notes.n = 0;
  out_start(p);
  status = swarf_gc_block_read(text, n, &p->params, &b, &f);
  if (status == SWARF_OK) status = swarf_gc_block_check(&b, p->state, &f);
  if (status == SWARF_OK) status = swarf_gc_execute(&b, next, &ex, &f);
  if (status != SWARF_OK && m98_switch(p, &f, text, n)) return p->status;
  if (status != SWARF_OK) return fail(p, &f, text, n);
  p->state = next; /* commit: the copy becomes the state */
  p->params.state = next;
  apply_assigns(p, &b);
  p->ended = next->ended;
  for (int i = 0; i < p->notes.n && p->note_fn != NULL; i++)
    p->note_fn(p->cur_line, p->notes.column[i], p->notes.text[i], p->note_user);
  status = emit(p, text, n);
  out_keep(p);
  if (p->ended && p->canon != NULL) {
    canon_line(p, "N.....", "ON_RESET()");
    canon_line(p, "N.....", "ON_RESET()");
  }
  return status;
}

/* The flow's callback for an ordinary line (streamed or stored). A line
 * that starts with `/` is skipped when the block delete switch is on and
 * runs without its `/` when it is off, as rs274 does (Fanuc's `/1`..`/9`
 * name switches of one panel: all are this switch here). */
int swarf_gc_parser_run_line(void *ctx, const char *text, size_t n, long line) {
  swarf_gcode_parser *p = ctx;
  size_t first = skip_blanks(text, n, 0);
  if (p->ended || p->status != SWARF_OK) return p->status;
  p->cur_line = line;
  if (first == n) return SWARF_OK;
  if (text[first] == '/') {
    char *copy;
    if (p->block_delete) return SWARF_OK;
    if (text == p->scratch) {
      p->scratch[first] = ' ';
      copy = p->scratch;
    } else if ((copy = swarf_gc_scratch(p, text, n)) == NULL)
      return fail_code(p, SWARF_GCODE_E_OUT_OF_MEMORY, 1);
    copy[first] = ' ';
    if (swarf_gc_fanuc_like(p->state) && first + 1 < n && copy[first + 1] >= '1' &&
        copy[first + 1] <= '9')
      copy[first + 1] = ' ';
    return run_block(p, copy, n);
  }
  return run_block(p, text, n);
}

static int run_line(void *ctx, const char *text, size_t n, long line) {
  return swarf_gc_parser_run_line(ctx, text, n, line);
}

int swarf_gc_parser_flow_line(swarf_gcode_parser *p, const char *text, size_t len, long line) {
  swarf_error f;
  long err_line = line;
  int status = swarf_gc_flow_line(p->flow, text, len, line, &err_line, &f);
  if (status != SWARF_OK && p->status == SWARF_OK) {
    p->cur_line = err_line;
    return err_line == line ? fail(p, &f, text, len) : fail(p, &f, NULL, 0);
  }
  return p->status;
}

/* Runs a Fanuc or Haas program kept whole (at its closing `%` or the end). */
static swarf_status run_fanuc(swarf_gcode_parser *p) {
  swarf_error f;
  long err_line = 0;
  int status;
  swarf_gc_fanuc *fa = p->fanuc;
  p->fanuc = NULL; /* runs once */
  p->fanuc_running = 1;
  status = swarf_gc_fanuc_run(fa, &err_line, &f);
  p->fanuc_running = 0;
  swarf_gc_fanuc_free(fa);
  if (status != SWARF_OK && p->status == SWARF_OK) {
    p->cur_line = err_line;
    return fail(p, &f, NULL, 0);
  }
  return p->status;
}

/* A line made of `%` alone: opens the program first, closes it later. */
static swarf_status percent_line(swarf_gcode_parser *p, const char *text, size_t n, size_t at) {
  swarf_error f;
  if (!p->seen_code) {
    p->seen_code = 1;
    p->percent_open = 1;
    return SWARF_OK;
  }
  if (p->percent_open) {
    if (p->fanuc != NULL && run_fanuc(p) != SWARF_OK) return p->status;
    release_held(p);
    p->ended = 1;
    if (p->canon != NULL) {
      canon_line(p, "N.....", "FINISH()");
      canon_line(p, "N.....", "ON_RESET()");
      canon_line(p, "N.....", "ON_RESET()");
    }
    return SWARF_OK;
  }
  /* Errors come in file order: a kept program's own come before this line's. */
  if (p->fanuc != NULL && run_fanuc(p) != SWARF_OK) return p->status;
  p->cur_line = p->lines;
  swarf_gc_fail_code(&f, SWARF_GCODE_E_PERCENT_NOT_OPEN, (int)at + 1);
  return fail(p, &f, text, n);
}

/* grbl's $H: the homing cycle takes the machine to its home, the start
 * position (swarf_gcode_parser_set_start), Z first; the work offsets stay
 * (grbl keeps them). A file of several jobs, each `$H` then G10 L20, so sets
 * each job's origin from the same place, as on the machine. */
static swarf_status grbl_home(swarf_gcode_parser *p, const char *text, size_t n, size_t at) {
  swarf_gc_state *next = p->state == &p->states[0] ? &p->states[1] : &p->states[0];
  swarf_gc_exec ex = {&p->params, &p->out, p->tools, SWARF_GC_NTOOLS, &p->notes, p->ext};
  *next = *p->state;
  p->notes.n = 0;
  out_start(p);
  swarf_gc_home_cycle(next, &ex, p->start, (int)at + 1);
  swarf_gc_note(&p->notes, (int)at + 1,
                "$H: homed (Z first) to machine X%.3f Y%.3f Z%.3f, the start position (--start)",
                p->start[0], p->start[1], p->start[2]);
  p->state = next;
  p->params.state = next;
  for (int i = 0; i < p->notes.n && p->note_fn != NULL; i++)
    p->note_fn(p->cur_line, p->notes.column[i], p->notes.text[i], p->note_user);
  swarf_status status = emit(p, text, n);
  out_keep(p);
  return status;
}

/* `$H` alone on its line (spaces and a comment after it allowed). */
static int is_home(const char *text, size_t n, size_t first) {
  size_t i = first + 2;
  if (first + 1 >= n || text[first] != '$' || (text[first + 1] != 'H' && text[first + 1] != 'h'))
    return 0;
  while (i < n && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r'))
    i++;
  return i == n || text[i] == ';' || text[i] == '(';
}

/* grbl reads lines one by one: `$H` homes, other `$` lines are settings and
 * commands for the controller (ignored here, with a note), `%` lines are
 * stripped by the senders (ignored), and there are no parameters,
 * expressions or O words (outside comments). */
static swarf_status grbl_line(swarf_gcode_parser *p, const char *text, size_t n, size_t first,
                              size_t rest) {
  int depth = 0;
  swarf_error f;
  if (is_home(text, n, first)) return grbl_home(p, text, n, first);
  if (text[first] == '$' || (text[first] == '%' && rest == n)) {
    swarf_gc_parser_note(p, (int)first + 1, "%s line ignored (grbl %s)",
                         text[first] == '$' ? "$" : "%",
                         text[first] == '$' ? "setting or system command" : "program marker");
    return SWARF_OK;
  }
  p->seen_code = 1;
  for (size_t i = first; i < n; i++) {
    char c = text[i];
    if (c == ';' && depth == 0) break;
    if (c == '(') depth = 1;
    if (c == ')') depth = 0;
    if (depth == 0 && (c == '#' || c == '[' || c == 'O' || c == 'o')) {
      SWARF_GC_FAIL(&f, SWARF_GCODE_E_DIALECT_PARAMETERS, (int)i + 1, c);
      return fail(p, &f, text, n);
    }
  }
  return swarf_gc_parser_run_line(p, text, n, p->lines);
}

static swarf_status process_line(swarf_gcode_parser *p, const char *text, size_t n) {
  size_t first, rest;
  swarf_error f;
  long err_line;
  int status;
  p->lines++;
  p->cur_line = p->lines;
  canon_start(p);
  if (n > SWARF_GC_LINE_MAX) return fail_code(p, SWARF_GCODE_E_LINE_TOO_LONG, 1);
  first = skip_blanks(text, n, 0);
  if (first == n) return SWARF_OK;
  rest = skip_blanks(text, n, first + 1);
  if (p->state->dialect == SWARF_GCODE_DIALECT_GRBL) return grbl_line(p, text, n, first, rest);
  /* A LinuxCNC program kept for M98: rs274 seeks the O<n> past a `%`. */
  if (text[first] == '%' && rest == n && p->fanuc != NULL && !p->percent_open &&
      p->state->dialect == SWARF_GCODE_DIALECT_LINUXCNC)
    return SWARF_OK;
  if (text[first] == '%' && rest == n) return percent_line(p, text, n, first);
  p->seen_code = 1;
  if (p->fanuc != NULL) {
    status = swarf_gc_fanuc_store(p->fanuc, text, n, p->lines, &f);
    return status == SWARF_OK ? SWARF_OK : fail(p, &f, text, n);
  }
  if (text[first] == '/' && p->block_delete) return SWARF_OK;
  status = swarf_gc_flow_line(p->flow, text, n, p->lines, &err_line, &f);
  if (status != SWARF_OK && p->status == SWARF_OK) {
    p->cur_line = err_line;
    return err_line == p->lines ? fail(p, &f, text, n) : fail(p, &f, NULL, 0);
  }
  return p->status;
}

/* Keeps bytes of an unterminated line; refuses to hold more than a line may be. */
static swarf_status keep_partial(swarf_gcode_parser *p, const char *s, size_t n) {
  size_t need = p->partial_len + n;
  if (need > SWARF_GC_LINE_MAX) {
    p->cur_line = ++p->lines;
    return fail_code(p, SWARF_GCODE_E_LINE_TOO_LONG, 1);
  }
  if (need > p->partial_cap) {
    size_t cap = p->partial_cap ? p->partial_cap : 256;
    char *grown;
    while (cap < need)
      cap *= 2;
    grown = realloc(p->partial, cap);
    if (grown == NULL) return fail_code(p, SWARF_GCODE_E_OUT_OF_MEMORY, 1);
    p->partial = grown;
    p->partial_cap = cap;
  }
  memcpy(p->partial + p->partial_len, s, n);
  p->partial_len = need;
  return SWARF_OK;
}

/* A whole line has arrived: its head may wait in `partial`. */
static swarf_status complete_line(swarf_gcode_parser *p, const char *s, size_t n) {
  swarf_status status;
  p->bytes += (long long)(p->partial_len + n + 1); /* before its moves: they count it read */
  if (p->partial_len == 0) return process_line(p, s, n);
  status = keep_partial(p, s, n);
  if (status == SWARF_OK) status = process_line(p, p->partial, p->partial_len);
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

swarf_status swarf_gcode_parser_new(const char *filename, swarf_gcode_move_fn fn, void *user,
                                    swarf_gcode_parser **out) {
  swarf_gcode_parser *p;
  if (out == NULL) return SWARF_ERR_ARG;
  *out = p = calloc(1, sizeof *p);
  if (p == NULL) return SWARF_ERR_MEMORY;
  p->fn = fn;
  p->user = user;
  p->state = &p->states[0];
  swarf_gc_state_init(p->state);
  swarf_gc_params_init(&p->params);
  p->params.state = p->state;
  swarf_gc_out_init(&p->out);
  swarf_gc_out_init(&p->held);
  default_tools(p);
  p->work_limit = SWARF_GCODE_WORK_LIMIT;
  p->flow = swarf_gc_flow_new(&p->params, run_line, p);
  if (p->flow != NULL) swarf_gc_flow_set_extra(p->flow, &p->work_extra);
  if (p->flow == NULL) {
    free(p);
    *out = NULL;
    return SWARF_ERR_MEMORY;
  }
  snprintf(p->error.file, sizeof p->error.file, "%s", filename ? filename : "");
  return SWARF_OK;
}

swarf_status swarf_gcode_parser_feed(swarf_gcode_parser *p, const char *buf, size_t len) {
  const char *s = buf, *end = buf + len;
  if (p == NULL || (buf == NULL && len > 0)) return SWARF_ERR_ARG;
  if (p->status != SWARF_OK) return p->status;
  if (p->finished) return SWARF_ERR_STATE;
  while (s < end && !p->ended && p->status == SWARF_OK) {
    const char *nl = memchr(s, '\n', (size_t)(end - s));
    if (nl == NULL) return keep_partial(p, s, (size_t)(end - s));
    complete_line(p, s, (size_t)(nl - s));
    s = nl + 1;
  }
  return p->status;
}

swarf_status swarf_gcode_parser_finish(swarf_gcode_parser *p) {
  if (p == NULL) return SWARF_ERR_ARG;
  if (p->status == SWARF_OK && !p->ended && !p->finished && p->partial_len > 0) {
    p->bytes += (long long)p->partial_len;
    process_line(p, p->partial, p->partial_len);
    p->partial_len = 0;
  }
  if (p->status == SWARF_OK && !p->ended && !p->finished && p->fanuc != NULL) run_fanuc(p);
  if (p->status == SWARF_OK && !p->ended && !p->finished && swarf_gc_flow_open_line(p->flow) > 0) {
    p->cur_line = swarf_gc_flow_open_line(p->flow);
    fail_code(p, SWARF_GCODE_E_O_OPEN_AT_END, 1);
  }
  if (p->status == SWARF_OK && !p->ended && !p->finished && !p->fragment &&
      p->state->dialect == SWARF_GCODE_DIALECT_LINUXCNC) {
    /* rs274 reads past the last line and stops there: the program must end. */
    p->cur_line = p->lines > 0 ? p->lines : 1;
    fail_code(p, p->percent_open ? SWARF_GCODE_E_NO_CLOSING_PERCENT : SWARF_GCODE_E_NO_PROGRAM_END,
              1);
  }
  release_held(p);
  p->finished = 1;
  return p->status;
}

swarf_status swarf_gcode_parser_set_canon(swarf_gcode_parser *p, swarf_gcode_canon_fn fn,
                                          void *user) {
  if (p == NULL) return SWARF_ERR_ARG;
  if (p->lines > 0) return SWARF_ERR_STATE;
  p->canon = fn;
  p->canon_user = user;
  p->out.want_text = fn != NULL;
  p->held.want_text = fn != NULL;
  return SWARF_OK;
}

/* *err (may be NULL), cleared, names a file of the caller's, no line. */
static swarf_error *file_at(swarf_error *err, const char *path) {
  swarf_error_init(err);
  swarf_error_at(err, path, 0, 0, NULL);
  return err;
}

swarf_status swarf_gcode_parser_clear_tools(swarf_gcode_parser *p) {
  if (p == NULL) return SWARF_ERR_ARG;
  if (p->lines > 0) return SWARF_ERR_STATE;
  for (int t = 0; t < SWARF_GC_NTOOLS; t++)
    p->tools[t][0] = NAN, p->tools[t][1] = 0;
  return SWARF_OK;
}

swarf_status swarf_gcode_parser_set_tool(swarf_gcode_parser *p, int tool, double length,
                                         double diameter) {
  if (p == NULL || tool < 1 || tool >= SWARF_GC_NTOOLS) return SWARF_ERR_ARG;
  if (!isfinite(length) || !isfinite(diameter) || diameter < 0) return SWARF_ERR_ARG;
  if (p->lines > 0) return SWARF_ERR_STATE;
  p->tools[tool][0] = length;
  p->tools[tool][1] = diameter;
  return SWARF_OK;
}

const swarf_error *swarf_gcode_parser_error(const swarf_gcode_parser *p) {
  return (p != NULL && p->status != SWARF_OK) ? &p->error : NULL;
}

long swarf_gcode_parser_lines(const swarf_gcode_parser *p) {
  return p ? p->lines : 0;
}

long long swarf_gcode_parser_bytes(const swarf_gcode_parser *p) {
  return p ? p->bytes : 0;
}

int swarf_gcode_parser_ended(const swarf_gcode_parser *p) {
  return p ? p->ended : 0;
}

void swarf_gcode_parser_free(swarf_gcode_parser *p) {
  if (p == NULL) return;
  swarf_gc_flow_free(p->flow);
  swarf_gc_fanuc_free(p->fanuc);
  free(p->subpath);
  free(p->scratch);
  swarf_gc_params_clear(&p->params);
  swarf_gc_out_clear(&p->out);
  swarf_gc_out_clear(&p->held);
  free(p->partial);
  free(p);
}

static swarf_status stream_file(FILE *in, swarf_gcode_parser *p, const char *path,
                                swarf_error *err) {
  char *chunk = malloc(READ_CHUNK);
  swarf_status status = SWARF_OK;
  size_t got;
  if (chunk == NULL) return SWARF_GC_ERROR(SWARF_GCODE_E_OUT_OF_MEMORY, file_at(err, path));
  while (status == SWARF_OK && !p->ended && (got = fread(chunk, 1, READ_CHUNK, in)) > 0)
    status = swarf_gcode_parser_feed(p, chunk, got);
  free(chunk);
  if (status == SWARF_OK && ferror(in))
    return SWARF_GC_ERROR(SWARF_GCODE_E_FILE_READ, file_at(err, path));
  return status;
}

swarf_status swarf_gcode_parse_file(const char *path, swarf_gcode_move_fn fn, void *user,
                                    swarf_error *err) {
  swarf_gcode_parser *p;
  swarf_error why;
  FILE *in;
  swarf_status status;
  if (path == NULL) return SWARF_GC_ERROR(SWARF_GCODE_E_NO_FILE_NAME, file_at(err, ""));
  in = swarf_file_open_input(path, "program", 0, &why); /* regular files only */
  if (in == NULL) return SWARF_GC_ERROR(SWARF_GCODE_E_FILE_OPEN, file_at(err, path), why.message);
  if (swarf_gcode_parser_new(path, fn, user, &p) != SWARF_OK) {
    fclose(in);
    return SWARF_GC_ERROR(SWARF_GCODE_E_OUT_OF_MEMORY, file_at(err, path));
  }
  status = stream_file(in, p, path, err);
  fclose(in);
  if (status == SWARF_OK) status = swarf_gcode_parser_finish(p);
  if (status != SWARF_OK && err != NULL && swarf_gcode_parser_error(p) != NULL)
    *err = *swarf_gcode_parser_error(p);
  swarf_gcode_parser_free(p);
  return status;
}
