/* SPDX-License-Identifier: MPL-2.0 */
/* oword.c -- O-word subroutines, loops and conditionals.
 *
 * Lines stream in one at a time. An ordinary line outside any construct
 * goes straight to the block path (memory stays flat). A line that opens a
 * construct (sub, while, do, if, repeat) starts a recording that lasts to
 * its matching end; a finished sub is kept by name, any other construct is
 * then run from the recording with a program counter. Calls run a stored
 * body in a new frame: #1..#30 get the arguments (0 for missing ones) and
 * are restored on return, named locals are fresh; `return [v]`/`endsub [v]`
 * set #<_value>. Names: o123 and o<name> (lower case, blanks removed);
 * LinuxCNC matches the words of one construct by that name.
 *
 * Bounds of ours, so that no program hangs: calls nest at most 50 deep,
 * and the lines run from recordings (loop bodies, sub bodies, calls,
 * control lines: the work, which grows with turns times body and with call
 * trees, unlike a bound on turns or depth) number at most
 * SWARF_GC_MAX_EXECUTED in all, a few seconds of interpreting. Every loop
 * turn runs at least one stored line, so this also bounds the turns.
 * The flow owns its recordings and subs (freed by swarf_gc_flow_free).
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "gcode_private.h"

#define MAX_CALL_DEPTH 50
#define MAX_ARGS 30
#define MAX_NEST 64

typedef enum {
  O_NONE,
  O_SUB,
  O_ENDSUB,
  O_CALL,
  O_RETURN,
  O_DO,
  O_WHILE,
  O_ENDWHILE,
  O_IF,
  O_ELSEIF,
  O_ELSE,
  O_ENDIF,
  O_REPEAT,
  O_ENDREPEAT,
  O_BREAK,
  O_CONTINUE,
  O_NUMBER /* a program number alone ("O1001", "O0001 (NAME)"): rs274 does nothing */
} okind;

typedef struct {
  okind kind;
  char name[SWARF_GC_NAME_MAX];
  size_t args; /* offset of what follows the keyword */
  int column;  /* of the O */
} octl;

typedef struct {
  char *text;
  size_t len;
  long line;
  octl ctl;
  int closes_do; /* a `while` that ends a `do` */
} stored;

typedef struct {
  stored *v;
  size_t n, cap;
} line_list;

typedef struct sub_def {
  char name[SWARF_GC_NAME_MAX];
  line_list body;
  struct sub_def *next;
} sub_def;

typedef struct {
  okind kind;
  char name[SWARF_GC_NAME_MAX];
} open_ctl;

struct swarf_gc_flow {
  swarf_gc_params *ps;
  swarf_gc_line_fn run;
  void *ctx;
  line_list rec; /* the construct being recorded */
  open_ctl open[MAX_NEST];
  int nopen;
  sub_def *subs;
  int depth;         /* calls running */
  long executed;     /* stored lines run so far */
  const long *extra; /* and the parser's moves and turns beyond one a line */
  int running;       /* run_lines calls under way */
  long limit;        /* at most this many (SWARF_GCODE_WORK_LIMIT unless lowered) */
  long *err_line;
  const char *path; /* subroutine files: ':'-separated directories (borrowed) */
};

void swarf_gc_flow_set_limit(swarf_gc_flow *fl, long lines) {
  fl->limit = lines;
}

void swarf_gc_flow_set_extra(swarf_gc_flow *fl, const long *extra) {
  fl->extra = extra;
}

int swarf_gc_flow_running(const swarf_gc_flow *fl) {
  return fl->running > 0;
}

void swarf_gc_flow_set_path(swarf_gc_flow *fl, const char *dirs) {
  fl->path = dirs;
}

swarf_gc_flow *swarf_gc_flow_new(swarf_gc_params *ps, swarf_gc_line_fn run, void *ctx) {
  swarf_gc_flow *fl = calloc(1, sizeof *fl);
  if (fl == NULL) return NULL;
  fl->ps = ps;
  fl->run = run;
  fl->ctx = ctx;
  fl->limit = SWARF_GCODE_WORK_LIMIT;
  return fl;
}

static void list_clear(line_list *l) {
  for (size_t i = 0; i < l->n; i++)
    free(l->v[i].text);
  free(l->v);
  memset(l, 0, sizeof *l);
}

void swarf_gc_flow_free(swarf_gc_flow *fl) {
  if (fl == NULL) return;
  list_clear(&fl->rec);
  while (fl->subs != NULL) {
    sub_def *next = fl->subs->next;
    list_clear(&fl->subs->body);
    free(fl->subs);
    fl->subs = next;
  }
  free(fl);
}

long swarf_gc_flow_open_line(const swarf_gc_flow *fl) {
  return fl->nopen > 0 && fl->rec.n > 0 ? fl->rec.v[0].line : 0;
}

/* ---- reading a control line ---------------------------------------------- */

static int read_name(swarf_gc_lexer *lx, char *name, swarf_error *f) {
  size_t n = 0;
  if (swarf_gc_lexer_peek(lx) == '<') return swarf_gc_expr_name(lx, name, f);
  while (swarf_gc_lexer_peek(lx) != -1 && isdigit(lx->line[lx->pos]) && n + 1 < SWARF_GC_NAME_MAX)
    name[n++] = lx->line[lx->pos++];
  name[n] = '\0';
  if (n == 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_O_NAME_MISSING, (int)lx->pos + 1);
  while (n > 1 && name[0] == '0')
    memmove(name, name + 1, n--);
  return SWARF_OK;
}

/* The keyword after the name: all letters up to the next non-letter
 * (blanks mean nothing, as everywhere in a line). */
static okind read_keyword(swarf_gc_lexer *lx) {
  static const struct {
    const char *w;
    okind k;
  } words[] = {{"endsub", O_ENDSUB},    {"endwhile", O_ENDWHILE},
               {"endif", O_ENDIF},      {"endrepeat", O_ENDREPEAT},
               {"elseif", O_ELSEIF},    {"else", O_ELSE},
               {"sub", O_SUB},          {"call", O_CALL},
               {"return", O_RETURN},    {"do", O_DO},
               {"while", O_WHILE},      {"if", O_IF},
               {"repeat", O_REPEAT},    {"break", O_BREAK},
               {"continue", O_CONTINUE}};
  char word[16];
  size_t n = 0;
  while (swarf_gc_lexer_peek(lx) != -1 && isalpha((unsigned char)lx->line[lx->pos])) {
    if (n + 1 < sizeof word) word[n++] = (char)tolower((unsigned char)lx->line[lx->pos]);
    lx->pos++;
  }
  word[n] = '\0';
  for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
    if (strcmp(word, words[i].w) == 0) return words[i].k;
  return O_NONE;
}

/* Nothing but blanks and comments from the lexer's position on. */
static int only_comments(swarf_gc_lexer *lx) {
  for (;;) {
    int c = swarf_gc_lexer_peek(lx);
    if (c == -1 || c == ';') return 1;
    if (c != '(') return 0;
    while (lx->pos < lx->len && lx->line[lx->pos] != ')')
      lx->pos++;
    if (lx->pos == lx->len) return 0;
    lx->pos++;
  }
}

/* The control word of a line, if the line is one ("N10 o100 while [...]"). */
static int read_ctl(const char *text, size_t len, octl *c, swarf_error *f) {
  swarf_gc_lexer lx;
  int ch, status;
  c->kind = O_NONE;
  swarf_gc_lexer_init(&lx, text, len, NULL);
  ch = swarf_gc_lexer_peek(&lx);
  if (ch == 'N' || ch == 'n') { /* a line number first */
    lx.pos++;
    while (swarf_gc_lexer_peek(&lx) != -1 && (isdigit(lx.line[lx.pos]) || lx.line[lx.pos] == '.'))
      lx.pos++;
    ch = swarf_gc_lexer_peek(&lx);
  }
  if (ch != 'O' && ch != 'o') return SWARF_OK;
  c->column = (int)lx.pos + 1;
  lx.pos++;
  status = read_name(&lx, c->name, f);
  if (status != SWARF_OK) return status;
  c->kind = read_keyword(&lx);
  if (c->kind == O_NONE && only_comments(&lx)) c->kind = O_NUMBER;
  if (c->kind == O_NONE)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_O_UNKNOWN_KEYWORD, (int)lx.pos + 1, c->name);
  c->args = lx.pos;
  return SWARF_OK;
}

/* One [expression] after the keyword; `*v` unchanged (and 0 returned as
 * "absent") when there is none. */
static int read_arg(swarf_gc_lexer *lx, double *v, int *present, swarf_error *f) {
  *present = 0;
  while (swarf_gc_lexer_peek(lx) == '(') { /* comments between arguments */
    while (lx->pos < lx->len && lx->line[lx->pos] != ')')
      lx->pos++;
    if (lx->pos < lx->len) lx->pos++;
  }
  if (swarf_gc_lexer_peek(lx) != '[') return SWARF_OK;
  *present = 1;
  return swarf_gc_expr_value(lx, v, f);
}

static int eval_arg(swarf_gc_flow *fl, const stored *s, double *v, int required, swarf_error *f) {
  swarf_gc_lexer lx;
  int present, status;
  swarf_gc_lexer_init(&lx, s->text, s->len, fl->ps);
  lx.pos = s->ctl.args;
  *v = 0;
  status = read_arg(&lx, v, &present, f);
  if (status == SWARF_OK && required && !present)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_O_EXPRESSION_MISSING, s->ctl.column, s->ctl.name);
  return status;
}

/* ---- recording ---------------------------------------------------------- */

static int list_push(line_list *l, const char *text, size_t len, long line, const octl *c) {
  stored *s;
  if (l->n == l->cap) {
    size_t cap = l->cap ? 2 * l->cap : 64;
    stored *grown = realloc(l->v, cap * sizeof *grown);
    if (grown == NULL) return -1;
    l->v = grown;
    l->cap = cap;
  }
  s = &l->v[l->n];
  s->text = malloc(len + 1);
  if (s->text == NULL) return -1;
  memcpy(s->text, text, len);
  s->text[len] = '\0';
  s->len = len;
  s->line = line;
  s->ctl = *c;
  s->closes_do = 0;
  l->n++;
  return 0;
}

static int opens(okind k) {
  return k == O_SUB || k == O_DO || k == O_WHILE || k == O_IF || k == O_REPEAT;
}

static int closes(okind k) {
  return k == O_ENDSUB || k == O_ENDWHILE || k == O_ENDIF || k == O_ENDREPEAT;
}

/* Tracks nesting while recording; returns 1 when the outer construct closed. */
static int track(swarf_gc_flow *fl, stored *s, swarf_error *f) {
  open_ctl *top = fl->nopen > 0 ? &fl->open[fl->nopen - 1] : NULL;
  okind k = s->ctl.kind;
  if (k == O_WHILE && top != NULL && top->kind == O_DO && strcmp(top->name, s->ctl.name) == 0) {
    s->closes_do = 1;
    fl->nopen--;
    return fl->nopen == 0;
  }
  if (opens(k)) {
    if (k == O_SUB && fl->nopen > 0)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_O_NESTED_SUB, s->ctl.column), -1;
    if (fl->nopen == MAX_NEST)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_O_NESTING_TOO_DEEP, s->ctl.column), -1;
    fl->open[fl->nopen].kind = k;
    strcpy(fl->open[fl->nopen++].name, s->ctl.name);
    return 0;
  }
  if (closes(k)) {
    static const okind opener[] = {
        [O_ENDSUB] = O_SUB, [O_ENDWHILE] = O_WHILE, [O_ENDIF] = O_IF, [O_ENDREPEAT] = O_REPEAT};
    if (top == NULL || top->kind != opener[k] || strcmp(top->name, s->ctl.name) != 0)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_O_CLOSE_MISMATCH, s->ctl.column, s->ctl.name), -1;
    fl->nopen--;
    return fl->nopen == 0;
  }
  return 0;
}

/* ---- running stored lines ------------------------------------------------ */

static int run_lines(swarf_gc_flow *fl, line_list *l, swarf_error *f);

static sub_def *find_sub(swarf_gc_flow *fl, const char *name) {
  for (sub_def *s = fl->subs; s != NULL; s = s->next)
    if (strcmp(s->name, name) == 0) return s;
  return NULL;
}

/* Reads o<name> sub ... o<name> endsub out of an open subroutine file; the
 * stored lines carry `line` (the call's), so that moves and errors point
 * at the program. 1: found, 0: not in the file, -1: out of memory. */
static int read_sub_file(swarf_gc_flow *fl, FILE *in, const char *name, long line) {
  char buf[4096];
  sub_def *sub = NULL;
  swarf_error f;
  while (fgets(buf, sizeof buf, in) != NULL) {
    size_t n = strcspn(buf, "\r\n");
    octl c;
    if (read_ctl(buf, n, &c, &f) != SWARF_OK) c.kind = O_NONE;
    if (sub == NULL) {
      if (c.kind == O_SUB && strcmp(c.name, name) == 0 && (sub = calloc(1, sizeof *sub)) == NULL)
        return -1;
      continue;
    }
    if (list_push(&sub->body, buf, n, line, &c) != 0) break;
    if (c.kind == O_ENDSUB && strcmp(c.name, name) == 0) {
      strcpy(sub->name, name);
      sub->next = fl->subs;
      fl->subs = sub;
      return 1;
    }
  }
  if (sub != NULL) list_clear(&sub->body);
  free(sub);
  return 0;
}

/* A subroutine no line defined: <name>.ngc in the directories of the path
 * (LinuxCNC's SUBROUTINE_PATH), in order. Only a regular file is read (a
 * FIFO or /dev/zero there hung the call): anything else that exists there
 * is an error at the call (*bad set, f filled). */
static sub_def *find_sub_file(swarf_gc_flow *fl, const char *name, long line, int column, int *bad,
                              swarf_error *f) {
  const char *d = fl->path;
  while (d != NULL && *d) {
    size_t n = strcspn(d, ":");
    char path[4096];
    FILE *in;
    struct stat st;
    if (n > 0 && n + strlen(name) + 6 < sizeof path) {
      snprintf(path, sizeof path, "%.*s/%s.ngc", (int)n, d, name);
      if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        *bad = 1;
        SWARF_GC_FAIL(f, SWARF_GCODE_E_O_SUB_FILE, column, name, path,
                      S_ISFIFO(st.st_mode) ? "a FIFO, not a regular file"
                                           : "not a regular file (a device or a folder)");
        return NULL;
      }
      if ((in = fopen(path, "r")) != NULL) {
        int found = read_sub_file(fl, in, name, line);
        fclose(in);
        if (found > 0) return fl->subs;
      }
    }
    d += n + (d[n] == ':');
  }
  return NULL;
}

static int call(swarf_gc_flow *fl, const stored *s, swarf_error *f) {
  double args[MAX_ARGS] = {0}, saved[MAX_ARGS];
  swarf_gc_lexer lx;
  swarf_gc_named *locals;
  sub_def *sub = find_sub(fl, s->ctl.name);
  int bad = 0;
  if (sub == NULL) sub = find_sub_file(fl, s->ctl.name, s->line, s->ctl.column, &bad, f);
  if (bad) return f->status;
  int n = 0, present = 1, status = SWARF_OK;
  if (sub == NULL) return SWARF_GC_FAIL(f, SWARF_GCODE_E_O_UNKNOWN_SUB, s->ctl.column, s->ctl.name);
  if (fl->depth >= MAX_CALL_DEPTH)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_O_CALLS_TOO_DEEP, s->ctl.column, MAX_CALL_DEPTH);
  swarf_gc_lexer_init(&lx, s->text, s->len, fl->ps);
  lx.pos = s->ctl.args;
  while (status == SWARF_OK && present) {
    double v = 0;
    status = read_arg(&lx, &v, &present, f);
    if (present && n < MAX_ARGS) args[n++] = v;
  }
  if (status != SWARF_OK) return status;
  for (int i = 0; i < MAX_ARGS; i++) {
    saved[i] = fl->ps->num[i + 1];
    fl->ps->num[i + 1] = args[i];
  }
  locals = swarf_gc_params_swap_locals(fl->ps, NULL);
  fl->ps->value_returned = 0;
  fl->depth++;
  status = run_lines(fl, &sub->body, f);
  fl->depth--;
  swarf_gc_named_free(swarf_gc_params_swap_locals(fl->ps, locals));
  for (int i = 0; i < MAX_ARGS; i++)
    fl->ps->num[i + 1] = saved[i];
  return status;
}

/* Index of the next line (after `from`) named `name` of one of the kinds. */
static size_t find_fwd(const line_list *l, size_t from, const char *name, okind a, okind b,
                       okind c) {
  for (size_t i = from + 1; i < l->n; i++) {
    okind k = l->v[i].ctl.kind;
    if ((k == a || k == b || k == c) && strcmp(l->v[i].ctl.name, name) == 0) return i;
  }
  return l->n;
}

static size_t find_back(const line_list *l, size_t from, const char *name, okind a) {
  for (size_t i = from; i-- > 0;)
    if (l->v[i].ctl.kind == a && !l->v[i].closes_do && strcmp(l->v[i].ctl.name, name) == 0)
      return i;
  return l->n;
}

enum { DONE_END = 100 }; /* run_lines status: a return/endsub ended the sub */

/* The if chain: where to go from an if or elseif whose test failed. */
static int next_branch(swarf_gc_flow *fl, line_list *l, size_t *pc, swarf_error *f) {
  for (;;) {
    size_t j = find_fwd(l, *pc, l->v[*pc].ctl.name, O_ELSEIF, O_ELSE, O_ENDIF);
    double v;
    int status;
    if (j >= l->n || l->v[j].ctl.kind != O_ELSEIF) {
      *pc = j + 1;
      return SWARF_OK;
    }
    status = eval_arg(fl, &l->v[j], &v, 1, f);
    if (status != SWARF_OK) return status;
    *pc = j;
    if (v != 0) {
      *pc = j + 1;
      return SWARF_OK;
    }
  }
}

/* A do/while, while, repeat or break/continue: sets *pc. */
static int loop_step(swarf_gc_flow *fl, line_list *l, size_t *pc, double *counts, swarf_error *f) {
  const stored *s = &l->v[*pc];
  const char *name = s->ctl.name;
  double v;
  int status;
  size_t j;
  switch (s->ctl.kind) {
  case O_WHILE:
    status = eval_arg(fl, s, &v, 1, f);
    if (status != SWARF_OK) return status;
    if (s->closes_do) {
      j = find_back(l, *pc, name, O_DO);
      *pc = v != 0 ? j + 1 : *pc + 1;
      return SWARF_OK;
    }
    *pc = v != 0 ? *pc + 1 : find_fwd(l, *pc, name, O_ENDWHILE, O_ENDWHILE, O_ENDWHILE) + 1;
    return SWARF_OK;
  case O_ENDWHILE:
    *pc = find_back(l, *pc, name, O_WHILE);
    return SWARF_OK;
  case O_REPEAT:
    status = eval_arg(fl, s, &v, 1, f);
    if (status != SWARF_OK) return status;
    counts[*pc] = floor(v + 0.5);
    *pc = counts[*pc] > 0 ? *pc + 1
                          : find_fwd(l, *pc, name, O_ENDREPEAT, O_ENDREPEAT, O_ENDREPEAT) + 1;
    return SWARF_OK;
  case O_ENDREPEAT:
    j = find_back(l, *pc, name, O_REPEAT);
    *pc = j < l->n && --counts[j] > 0 ? j + 1 : *pc + 1;
    return SWARF_OK;
  case O_BREAK:
    j = find_fwd(l, *pc, name, O_ENDWHILE, O_ENDREPEAT, O_WHILE);
    *pc = j + 1;
    return SWARF_OK;
  default: /* O_CONTINUE */
    j = find_fwd(l, *pc, name, O_ENDWHILE, O_ENDREPEAT, O_WHILE);
    *pc = j;
    return SWARF_OK;
  }
}

static int run_lines(swarf_gc_flow *fl, line_list *l, swarf_error *f) {
  double *counts = calloc(l->n ? l->n : 1, sizeof *counts);
  size_t pc = 0;
  int status = SWARF_OK;
  double v;
  if (counts == NULL) return SWARF_GC_FAIL(f, SWARF_GCODE_E_OUT_OF_MEMORY, 1);
  fl->running++;
  while (status == SWARF_OK && pc < l->n) {
    stored *s = &l->v[pc];
    *fl->err_line = s->line;
    if (++fl->executed + (fl->extra != NULL ? *fl->extra : 0) > fl->limit) {
      status = SWARF_GC_FAIL(f, SWARF_GCODE_E_O_WORK_LIMIT,
                             s->ctl.kind != O_NONE ? s->ctl.column : 1, fl->limit);
      break;
    }
    switch (s->ctl.kind) {
    case O_NONE: /* the line's own moves and turns may take it over: stop at it */
      status = fl->run(fl->ctx, s->text, s->len, s->line);
      if (status == SWARF_OK && fl->executed + (fl->extra != NULL ? *fl->extra : 0) > fl->limit)
        status = SWARF_GC_FAIL(f, SWARF_GCODE_E_O_WORK_LIMIT, 1, fl->limit);
      pc++;
      break;
    case O_CALL:
      status = call(fl, s, f);
      pc++;
      break;
    case O_RETURN:
    case O_ENDSUB:
      status = eval_arg(fl, s, &v, 0, f);
      if (status == SWARF_OK && fl->depth > 0) {
        fl->ps->value = v;
        fl->ps->value_returned = 1;
        status = DONE_END;
      } else if (status == SWARF_OK)
        status = SWARF_GC_FAIL(f, SWARF_GCODE_E_O_RETURN_OUTSIDE, s->ctl.column, s->ctl.name);
      break;
    case O_SUB:
      status = SWARF_GC_FAIL(f, SWARF_GCODE_E_O_NESTED_SUB, s->ctl.column);
      break;
    case O_IF:
      status = eval_arg(fl, s, &v, 1, f);
      if (status == SWARF_OK && v != 0)
        pc++;
      else if (status == SWARF_OK)
        status = next_branch(fl, l, &pc, f);
      break;
    case O_ELSEIF:
    case O_ELSE: /* the branch before was taken */
      pc = find_fwd(l, pc, s->ctl.name, O_ENDIF, O_ENDIF, O_ENDIF) + 1;
      break;
    case O_ENDIF:
    case O_DO:
    case O_NUMBER:
      pc++;
      break;
    default:
      status = loop_step(fl, l, &pc, counts, f);
      break;
    }
  }
  free(counts);
  fl->running--;
  if (status == DONE_END) return fl->depth > 0 ? SWARF_OK : status;
  return status;
}

/* ---- the streaming entry -------------------------------------------------- */

static int finish_recording(swarf_gc_flow *fl, swarf_error *f) {
  int status = SWARF_OK;
  if (fl->rec.v[0].ctl.kind == O_SUB) {
    sub_def *sub = calloc(1, sizeof *sub);
    if (sub == NULL) return SWARF_GC_FAIL(f, SWARF_GCODE_E_OUT_OF_MEMORY, 1);
    strcpy(sub->name, fl->rec.v[0].ctl.name);
    sub->body = fl->rec;
    /* The body without the sub line; the endsub stays (it returns). */
    free(sub->body.v[0].text);
    memmove(sub->body.v, sub->body.v + 1, (sub->body.n - 1) * sizeof *sub->body.v);
    sub->body.n--;
    sub->next = fl->subs;
    fl->subs = sub;
    memset(&fl->rec, 0, sizeof fl->rec);
    return SWARF_OK;
  }
  status = run_lines(fl, &fl->rec, f);
  list_clear(&fl->rec);
  return status;
}

int swarf_gc_flow_line(swarf_gc_flow *fl, const char *text, size_t len, long line, long *err_line,
                       swarf_error *f) {
  octl c;
  int status = read_ctl(text, len, &c, f), closed;
  fl->err_line = err_line;
  *err_line = line;
  if (status != SWARF_OK) return status;
  if (fl->nopen == 0 && c.kind == O_NONE) return fl->run(fl->ctx, text, len, line);
  if (fl->nopen == 0 && c.kind == O_NUMBER) return SWARF_OK;
  if (fl->nopen == 0 && !opens(c.kind)) {
    line_list one = {0};
    if (list_push(&one, text, len, line, &c) != 0)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_OUT_OF_MEMORY, 1);
    if (c.kind == O_CALL)
      status = call(fl, &one.v[0], f);
    else
      status = SWARF_GC_FAIL(f, SWARF_GCODE_E_O_NOT_OPEN, c.column, c.name);
    list_clear(&one);
    return status;
  }
  if (list_push(&fl->rec, text, len, line, &c) != 0)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_OUT_OF_MEMORY, 1);
  if (c.kind == O_NONE) return SWARF_OK;
  closed = track(fl, &fl->rec.v[fl->rec.n - 1], f);
  if (closed < 0) return f->status;
  return closed ? finish_recording(fl, f) : SWARF_OK;
}
