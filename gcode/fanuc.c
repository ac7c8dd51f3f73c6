/* SPDX-License-Identifier: MPL-2.0 */
/* fanuc.c -- Fanuc and Haas program structure: program numbers, M98/M99
 * subprograms, Haas M97 local subprograms, G65 macro calls, GOTO, IF and
 * WHILE ... DO / END, and `#i = expression` without brackets.
 *
 * A Fanuc or Haas file may hold several programs (O1000 ... M30, then
 * O2000 ... M99) and calls a subprogram that comes after the caller, so the
 * lines are kept as they stream in and run when the program is complete
 * (its closing `%` or the end of the input). Each line runs through the
 * parser's block path (swarf_gc_parser_run_line) after the words this file
 * handles are taken out of it; the block's motion runs first, then the
 * call or return (Fanuc 0i-MF Operator's Manual, "Subprogram": "when a move
 * command and M98 are in one block, the subprogram is called after the
 * move").
 *
 * The rules (quoted in tests/gcode/test_dialects.c):
 *   M98 P<prog> L<n>  calls O<prog> n times (L0: not at all); on Fanuc, a
 *                     P of more than four digits is <n><prog> (M98 P30010 =
 *                     3 times O0010).
 *   M97 P<n> L<k>     (Haas) calls the block N<n> of the running program.
 *   M99               returns after the calling block (after its repeats);
 *                     M99 P<n> returns to the block N<n> of the caller. In
 *                     the main program, M99 P<n> jumps to N<n>; a bare M99
 *                     would run it again from the start: the run stops
 *                     there, with a note.
 *   A call of O9000-O9999 that the file lacks (the builder's macros in the
 *                     control: Renishaw's G65 P9810 probing moves ...) is
 *                     skipped with a note.
 *   G65 P<prog> L<n> args  a macro call: a new set of locals #1-#33, with
 *                     A=#1 B=#2 C=#3 I=#4 J=#5 K=#6 D=#7 E=#8 F=#9 H=#11
 *                     M=#13 Q=#17 R=#18 S=#19 T=#20 U=#21 V=#22 W=#23 X=#24
 *                     Y=#25 Z=#26 (argument specification I); words not
 *                     given are 0 (Fanuc: vacant); the caller's locals are
 *                     back after M99. M98 shares the caller's locals.
 *   GOTO n, IF [c] GOTO n, IF [c] THEN #i = e, WHILE [c] DO m ... END m.
 * Bounds: calls nest at most MAX_DEPTH deep; jumps and repeats together at
 * most MAX_JUMPS, and at most the parser's work limit (SWARF_GCODE_WORK_LIMIT
 * unless lowered) lines run beyond the number
 * the program has, so that no program runs forever or for hours.
 * The store owns its lines (freed by swarf_gc_fanuc_free).
 */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gcode_private.h"

#define MAX_DEPTH 16
#define MAX_JUMPS 10000000L
#define NLOCALS 33

typedef enum { ST_NONE, ST_GOTO, ST_IF, ST_WHILE, ST_DO, ST_END, ST_ASSIGN } stmt_kind;

typedef struct {
  char *text;
  size_t len;
  long line;
  long onum;     /* the program number if the line is an O line, else -1 */
  long nnum;     /* its N word, else -1 */
  size_t pstart; /* first line of its program */
  stmt_kind kind;
  size_t at;  /* after the statement's keyword */
  long loop;  /* WHILE/DO/END: its id m */
  long match; /* WHILE/DO: index of its END; END: of its DO line; -1: none */
} fline;

typedef struct {
  size_t ret;   /* line to go on at after the return */
  size_t start; /* first line of the body (run again on a repeat) */
  long repeats; /* runs left, the current one included */
  size_t prog;  /* its program's first line (for N searches) */
  size_t caller_prog;
  int macro; /* a G65 call: the caller's locals are in `locals` */
  double locals[NLOCALS];
} frame;

struct swarf_gc_fanuc {
  swarf_gcode_parser *p;
  fline *v;
  size_t n, cap;
  frame stack[MAX_DEPTH];
  int depth;
  long jumps;
  char *buf; /* a line rewritten */
  size_t buf_cap;
  size_t *nidx; /* hash of (pstart, N) -> line index + 1 */
  size_t nidx_cap;
};

swarf_gc_fanuc *swarf_gc_fanuc_new(swarf_gcode_parser *p) {
  swarf_gc_fanuc *fa = calloc(1, sizeof *fa);
  if (fa != NULL) fa->p = p;
  return fa;
}

void swarf_gc_fanuc_free(swarf_gc_fanuc *fa) {
  if (fa == NULL) return;
  for (size_t i = 0; i < fa->n; i++)
    free(fa->v[i].text);
  free(fa->v);
  free(fa->buf);
  free(fa->nidx);
  free(fa);
}

/* ---- reading a kept line ----------------------------------------------------- */

static size_t skip(const char *t, size_t n, size_t i) {
  while (i < n && (t[i] == ' ' || t[i] == '\t' || t[i] == '\r'))
    i++;
  return i;
}

/* An unsigned integer at i (blanks inside allowed); -1 if none. */
static long read_int(const char *t, size_t n, size_t *i) {
  long v = -1;
  *i = skip(t, n, *i);
  while (*i < n && isdigit((unsigned char)t[*i])) {
    v = (v < 0 ? 0 : v) * 10 + (t[*i] - '0');
    if (v > 100000000L) v = 100000000L;
    *i = skip(t, n, *i + 1);
  }
  return v;
}

/* Past `/`, `/n` and an N word: where the block's words start. */
static size_t body_start(const char *t, size_t n, long *nnum) {
  size_t i = skip(t, n, 0);
  *nnum = -1;
  if (i < n && t[i] == '/') {
    i = skip(t, n, i + 1);
    if (i < n && t[i] >= '1' && t[i] <= '9') i = skip(t, n, i + 1);
  }
  if (i < n && (t[i] == 'N' || t[i] == 'n')) {
    size_t j = i + 1;
    long v = read_int(t, n, &j);
    if (v >= 0) {
      *nnum = v;
      while (j < n && (t[j] == '.' || isdigit((unsigned char)t[j])))
        j++;
      i = skip(t, n, j);
    }
  }
  return i;
}

/* Only blanks and comments from i on. */
static int rest_empty(const char *t, size_t n, size_t i) {
  for (;;) {
    i = skip(t, n, i);
    if (i >= n || t[i] == ';') return 1;
    if (t[i] != '(') return 0;
    while (i < n && t[i] != ')')
      i++;
    if (i++ >= n) return 0;
  }
}

/* Letters at i, upper-cased, as a keyword (two letters or more). */
static size_t keyword(const char *t, size_t n, size_t i, char *out, size_t cap) {
  size_t k = 0;
  i = skip(t, n, i);
  while (i < n && isalpha((unsigned char)t[i]) && k + 1 < cap) {
    out[k++] = (char)toupper((unsigned char)t[i]);
    i = skip(t, n, i + 1);
  }
  out[k] = '\0';
  return k >= 2 ? i : 0;
}

/* What the line is: a program number, a macro statement, or a block
 * (`lcnc`: a LinuxCNC program with M98: program numbers only). */
static void classify(fline *l, int lcnc) {
  const char *t = l->text;
  size_t n = l->len, i = skip(t, n, 0), j;
  char kw[8];
  l->onum = l->nnum = l->loop = l->match = -1;
  l->kind = ST_NONE;
  if (i < n && (t[i] == 'O' || t[i] == 'o' || t[i] == ':')) {
    j = i + 1;
    long v = read_int(t, n, &j);
    if (v >= 0 && rest_empty(t, n, j)) {
      l->onum = v;
      return;
    }
  }
  i = body_start(t, n, &l->nnum);
  if (lcnc) return;
  if (i < n && t[i] == '#') {
    l->kind = ST_ASSIGN;
    l->at = i;
    return;
  }
  j = keyword(t, n, i, kw, sizeof kw);
  if (j == 0) return;
  l->at = j;
  if (strcmp(kw, "GOTO") == 0) l->kind = ST_GOTO;
  if (strcmp(kw, "IF") == 0) l->kind = ST_IF;
  if (strcmp(kw, "WHILE") == 0 || strcmp(kw, "DO") == 0)
    l->kind = strcmp(kw, "DO") == 0 ? ST_DO : ST_WHILE;
  if (strcmp(kw, "END") == 0) {
    l->kind = ST_END;
    l->loop = read_int(t, n, &j);
  }
  if (l->kind == ST_DO) l->loop = read_int(t, n, &j);
  if (l->kind == ST_WHILE) { /* the id after DO, at the end of the line */
    const char *s = t + l->len;
    size_t k = n;
    while (k > 0 && !isalpha((unsigned char)t[k - 1]))
      k--;
    if (k >= 2 && toupper((unsigned char)t[k - 2]) == 'D' &&
        toupper((unsigned char)t[k - 1]) == 'O')
      l->loop = read_int(t, n, &k);
    (void)s;
  }
}

int swarf_gc_fanuc_store(swarf_gc_fanuc *fa, const char *text, size_t len, long line,
                         swarf_error *f) {
  fline *l;
  if (fa->n == fa->cap) {
    size_t cap = fa->cap ? 2 * fa->cap : 256;
    fline *grown = realloc(fa->v, cap * sizeof *grown);
    if (grown == NULL) return SWARF_GC_FAIL(f, SWARF_GCODE_E_OUT_OF_MEMORY, 1);
    fa->v = grown;
    fa->cap = cap;
  }
  l = &fa->v[fa->n];
  if ((l->text = malloc(len + 1)) == NULL) return SWARF_GC_FAIL(f, SWARF_GCODE_E_OUT_OF_MEMORY, 1);
  memcpy(l->text, text, len);
  l->text[len] = '\0';
  l->len = len;
  l->line = line;
  classify(l, fa->p->state->dialect == SWARF_GCODE_DIALECT_LINUXCNC);
  fa->n++;
  return SWARF_OK;
}

/* ---- indexes: programs, N numbers, loops ------------------------------------- */

static size_t hash(size_t prog, long nnum, size_t cap) {
  return (size_t)((prog * 2654435761u) ^ ((size_t)nnum * 40503u)) & (cap - 1);
}

/* Each line's program (the first O line's is the main one, from line 0),
 * the N index, the WHILE/DO and END pairs. */
static int index_lines(swarf_gc_fanuc *fa) {
  size_t prog = 0, open[64];
  int nopen = 0, seen_o = 0;
  fa->nidx_cap = 16;
  while (fa->nidx_cap < 2 * fa->n + 2)
    fa->nidx_cap *= 2;
  fa->nidx = calloc(fa->nidx_cap, sizeof *fa->nidx);
  if (fa->nidx == NULL) return -1;
  for (size_t i = 0; i < fa->n; i++) {
    fline *l = &fa->v[i];
    if (l->onum >= 0) {
      if (seen_o) prog = i, nopen = 0;
      seen_o = 1;
    }
    l->pstart = prog;
    if (l->nnum >= 0) {
      size_t h = hash(prog, l->nnum, fa->nidx_cap);
      while (fa->nidx[h] != 0 &&
             !(fa->v[fa->nidx[h] - 1].pstart == prog && fa->v[fa->nidx[h] - 1].nnum == l->nnum))
        h = (h + 1) & (fa->nidx_cap - 1);
      if (fa->nidx[h] == 0) fa->nidx[h] = i + 1;
    }
    if ((l->kind == ST_WHILE || l->kind == ST_DO) && nopen < 64) open[nopen++] = i;
    if (l->kind == ST_END)
      for (int k = nopen; k-- > 0;)
        if (fa->v[open[k]].loop == l->loop) {
          l->match = (long)open[k];
          fa->v[open[k]].match = (long)i;
          nopen = k;
          break;
        }
  }
  return 0;
}

/* The line N<nnum> of the program starting at `prog`, or fa->n. */
static size_t find_n(const swarf_gc_fanuc *fa, size_t prog, long nnum) {
  size_t h = hash(prog, nnum, fa->nidx_cap);
  while (fa->nidx[h] != 0) {
    const fline *l = &fa->v[fa->nidx[h] - 1];
    if (l->pstart == prog && l->nnum == nnum) return fa->nidx[h] - 1;
    h = (h + 1) & (fa->nidx_cap - 1);
  }
  return fa->n;
}

static size_t find_o(const swarf_gc_fanuc *fa, long onum) {
  for (size_t i = 0; i < fa->n; i++)
    if (fa->v[i].onum == onum) return i;
  return fa->n;
}

static size_t current_prog(const swarf_gc_fanuc *fa) {
  return fa->depth > 0 ? fa->stack[fa->depth - 1].prog : 0;
}

static int count_jump(swarf_gc_fanuc *fa, int column, swarf_error *f) {
  if (++fa->jumps > MAX_JUMPS)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_LOOP_LIMIT, column, MAX_JUMPS);
  return SWARF_OK;
}

/* ---- macro statements ---------------------------------------------------------- */

/* A value (number, #i, [expression]) at `at` of line l. */
static int value_at(swarf_gc_fanuc *fa, const fline *l, size_t *at, double *v, swarf_error *f) {
  swarf_gc_lexer lx;
  int status;
  swarf_gc_lexer_init(&lx, l->text, l->len, &fa->p->params);
  lx.pos = *at;
  if (swarf_gc_lexer_peek(&lx) == -1)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_MACRO_SYNTAX, (int)*at + 1, "a value is missing");
  status = swarf_gc_expr_value(&lx, v, f);
  *at = lx.pos;
  return status;
}

static char *buffer(swarf_gc_fanuc *fa, size_t need) {
  if (need > fa->buf_cap) {
    char *grown = realloc(fa->buf, need);
    if (grown == NULL) return NULL;
    fa->buf = grown;
    fa->buf_cap = need;
  }
  return fa->buf;
}

/* `#i = e` from `at` (Fanuc needs no brackets on the right): run as
 * LinuxCNC's `#i=[e]`; #3000 = n stops the program with the macro alarm. */
static int assign(swarf_gc_fanuc *fa, const fline *l, size_t at, swarf_error *f) {
  const char *t = l->text, *eq = memchr(t + at, '=', l->len - at);
  size_t e, end, k = 0;
  char *b;
  if (eq == NULL)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_MACRO_SYNTAX, (int)at + 1, "'=' is missing");
  e = (size_t)(eq - t) + 1;
  end = e;
  while (end < l->len && t[end] != '(' && t[end] != ';')
    end++;
  {
    size_t j = at + 1, v;
    long idx = read_int(t, l->len, &j);
    v = skip(t, l->len, j);
    if (idx == 3000 && v < l->len && t[v] == '=') {
      double x;
      int status = value_at(fa, l, &e, &x, f);
      if (status != SWARF_OK) return status;
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_ALARM, (int)at + 1, x, t + end);
    }
  }
  if ((b = buffer(fa, l->len + 4)) == NULL) return SWARF_GC_FAIL(f, SWARF_GCODE_E_OUT_OF_MEMORY, 1);
  for (size_t i = 0; i < e; i++)
    b[k++] = i < at ? ' ' : t[i];
  b[k++] = '[';
  memcpy(b + k, t + e, end - e), k += end - e;
  b[k++] = ']';
  memcpy(b + k, t + end, l->len - end), k += l->len - end;
  return swarf_gc_parser_run_line(fa->p, b, k, l->line);
}

/* Runs the statement of line *pc and sets *pc to the next line. */
static int statement(swarf_gc_fanuc *fa, size_t *pc, swarf_error *f) {
  const fline *l = &fa->v[*pc];
  size_t at = l->at;
  double v = 0;
  int status = SWARF_OK, col = (int)l->at;
  char kw[8];
  switch (l->kind) {
  case ST_ASSIGN:
    status = assign(fa, l, at, f);
    ++*pc;
    return status;
  case ST_GOTO:
  goto_n : {
    size_t to;
    status = value_at(fa, l, &at, &v, f);
    if (status == SWARF_OK) status = count_jump(fa, col, f);
    if (status != SWARF_OK) return status;
    to = find_n(fa, current_prog(fa), (long)floor(v + 0.5));
    if (to >= fa->n)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_NO_SEQUENCE, col, "GOTO", (long)floor(v + 0.5));
    *pc = to;
    return SWARF_OK;
  }
  case ST_IF:
    status = value_at(fa, l, &at, &v, f);
    if (status != SWARF_OK) return status;
    at = keyword(l->text, l->len, at, kw, sizeof kw);
    if (at != 0 && strcmp(kw, "GOTO") == 0) {
      if (v != 0) goto goto_n;
      ++*pc;
      return SWARF_OK;
    }
    if (at == 0 || strcmp(kw, "THEN") != 0)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_MACRO_SYNTAX, col, "IF [...] needs GOTO or THEN");
    ++*pc;
    at = skip(l->text, l->len, at);
    return v != 0 ? assign(fa, l, at, f) : SWARF_OK;
  case ST_WHILE:
  case ST_DO:
    if (l->match < 0)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_DO_WITHOUT_END, col, (int)l->loop, (int)l->loop);
    if (l->kind == ST_WHILE && (status = value_at(fa, l, &at, &v, f)) != SWARF_OK) return status;
    *pc = (l->kind == ST_DO || v != 0) ? *pc + 1 : (size_t)l->match + 1;
    return SWARF_OK;
  default: /* ST_END */
    if (l->match < 0)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_END_WITHOUT_DO, col, (int)l->loop, (int)l->loop);
    if ((status = count_jump(fa, col, f)) != SWARF_OK) return status;
    *pc = (size_t)l->match;
    return SWARF_OK;
  }
}

/* ---- calls and returns ----------------------------------------------------------- */

typedef struct {
  int code; /* 98 97 99 (M) or 65 (G65); 0: none */
  int column;
  int has_p, has_l;
  double p, l;
  double args[NLOCALS + 1]; /* G65: by local number */
} flow_words;

/* The local a G65 argument letter goes to (argument specification I), 0: none. */
static int arg_local(char letter) {
  static const char *letters = "ABCIJKDEFGHLMNOPQRSTUVWXYZ";
  static const int locals[] = {1, 2, 3, 4,  5,  6,  7,  8,  9,  0,  11, 0,  13,
                               0, 0, 0, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26};
  const char *s = strchr(letters, letter);
  return s ? locals[s - letters] : 0;
}

/* A cheap look for the codes this file handles, before lexing the line. */
static int may_have_flow(const char *t, size_t n) {
  for (size_t i = 0; i + 2 < n; i++) {
    char c = (char)toupper((unsigned char)t[i]);
    size_t j;
    if (c != 'M' && c != 'G') continue;
    j = skip(t, n, i + 1);
    while (j < n && t[j] == '0')
      j = skip(t, n, j + 1);
    if (j + 1 < n && c == 'M' && t[j] == '9' && (t[j + 1] >= '7' && t[j + 1] <= '9')) return 1;
    if (j + 1 < n && c == 'G' && t[j] == '6' && t[j + 1] == '5') return 1;
  }
  return 0;
}

/* Takes M98/M97/M99/G65 and their words out of the line: `b` gets a copy
 * with them blanked (the G65 arguments too), the rest of the block. */
static int take_flow(swarf_gc_fanuc *fa, const fline *l, char *b, flow_words *w, swarf_error *f) {
  swarf_gc_lexer lx;
  swarf_gc_token t;
  size_t spans[64][2];
  int kinds[64], nspan = 0, haas = fa->p->state->dialect == SWARF_GCODE_DIALECT_HAAS;
  int lcnc = fa->p->state->dialect == SWARF_GCODE_DIALECT_LINUXCNC;
  memset(w, 0, sizeof *w);
  swarf_gc_lexer_init(&lx, l->text, l->len, &fa->p->params);
  for (;;) {
    size_t from = lx.pos;
    int status = swarf_gc_lexer_next(&lx, &t, f), kind = -1;
    double v = t.value;
    if (status != SWARF_OK) return status;
    if (t.kind == SWARF_GC_TOKEN_END) break;
    if (t.kind != SWARF_GC_TOKEN_WORD || nspan == 64) continue;
    if ((t.letter == 'M' && (v == 98 || v == 99 || (v == 97 && haas))) ||
        (t.letter == 'G' && v == 65 && !lcnc)) {
      w->code = (int)v;
      w->column = t.column;
      kind = 0;
    } else if (t.letter == 'P' || t.letter == 'L') {
      *(t.letter == 'P' ? &w->p : &w->l) = v;
      *(t.letter == 'P' ? &w->has_p : &w->has_l) = 1;
      kind = 1;
    } else if (arg_local(t.letter) > 0 && !lcnc) {
      w->args[arg_local(t.letter)] = v;
      kind = 2;
    }
    if (kind >= 0) spans[nspan][0] = from, spans[nspan][1] = lx.pos, kinds[nspan++] = kind;
  }
  memcpy(b, l->text, l->len);
  for (int i = 0; w->code != 0 && i < nspan; i++)
    if (kinds[i] < 2 || w->code == 65) memset(b + spans[i][0], ' ', spans[i][1] - spans[i][0]);
  return SWARF_OK;
}

static int push(swarf_gc_fanuc *fa, size_t ret, size_t start, long repeats, size_t prog, int macro,
                const flow_words *w, int column, swarf_error *f) {
  frame *fr;
  if (fa->depth == MAX_DEPTH)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_CALLS_TOO_DEEP, column, MAX_DEPTH);
  fr = &fa->stack[fa->depth++];
  fr->ret = ret;
  fr->start = start;
  fr->repeats = repeats;
  fr->caller_prog = current_prog(fa);
  fr->prog = prog;
  fr->macro = macro;
  if (macro) {
    double *num = fa->p->params.num;
    memcpy(fr->locals, num + 1, sizeof fr->locals);
    for (int i = 1; i <= NLOCALS; i++)
      num[i] = w->args[i];
  }
  return count_jump(fa, column, f);
}

/* M99: the next line after the running body (or its next repeat). */
static int ret(swarf_gc_fanuc *fa, size_t *pc, const flow_words *w, swarf_error *f) {
  frame *fr;
  if (fa->depth == 0) {
    size_t to;
    if (!w->has_p) {
      swarf_gc_parser_note(fa->p, w->column,
                           "M99 in the main program: the controller would run it again from "
                           "the start; the simulation stops here");
      *pc = fa->n;
      return SWARF_OK;
    }
    to = find_n(fa, 0, (long)floor(w->p + 0.5));
    if (to >= fa->n)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_NO_SEQUENCE, w->column, "M99", (long)w->p);
    *pc = to;
    return count_jump(fa, w->column, f);
  }
  fr = &fa->stack[fa->depth - 1];
  if (--fr->repeats > 0) {
    *pc = fr->start;
    return count_jump(fa, w->column, f);
  }
  if (fr->macro) memcpy(fa->p->params.num + 1, fr->locals, sizeof fr->locals);
  *pc = fr->ret;
  fa->depth--;
  if (w->has_p) {
    size_t to = find_n(fa, fr->caller_prog, (long)floor(w->p + 0.5));
    if (to >= fa->n)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_NO_SEQUENCE, w->column, "M99", (long)w->p);
    *pc = to;
  }
  return SWARF_OK;
}

static int call(swarf_gc_fanuc *fa, size_t *pc, const flow_words *w, swarf_error *f) {
  const char *name = w->code == 98 ? "M98" : w->code == 97 ? "M97" : "G65";
  long target, repeats = w->has_l ? (long)floor(w->l + 0.5) : 1;
  size_t to;
  if (!w->has_p) return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_P_MISSING, w->column, name);
  target = (long)floor(w->p + 0.5);
  if (w->code == 98 && fa->p->state->dialect == SWARF_GCODE_DIALECT_FANUC && target > 9999 &&
      !w->has_l)
    repeats = target / 10000, target %= 10000;
  if (w->code == 97) {
    to = find_n(fa, current_prog(fa), target);
    if (to >= fa->n)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_NO_SEQUENCE, w->column, name, target);
  } else {
    to = find_o(fa, target);
    if (to >= fa->n && target >= 9000 && target <= 9999) {
      /* O9000-O9999 are the machine builder's macros, kept in the control
       * (probing cycles: G65 P9810 ...): not in the file, the call makes
       * no motion here. */
      swarf_gc_parser_note(fa->p, w->column,
                           "%s P%ld: O%ld is a macro of the control's memory, not in this file: "
                           "skipped (no motion)",
                           name, target, target);
      ++*pc;
      return SWARF_OK;
    }
    if (to >= fa->n)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_FANUC_NO_PROGRAM, w->column, name, target);
  }
  if (repeats <= 0) {
    ++*pc;
    return SWARF_OK;
  }
  {
    size_t prog = w->code == 97 ? current_prog(fa) : fa->v[to].pstart;
    size_t start = w->code == 97 ? to : to + 1;
    int status = push(fa, *pc + 1, start, repeats, prog, w->code == 65, w, w->column, f);
    *pc = start;
    return status;
  }
}

/* ---- running ---------------------------------------------------------------------- */

/* A line through the block path; in a LinuxCNC program through its O-word
 * flow (subs, loops, ifs), which hands ordinary lines to the block path. */
static int run_text(swarf_gc_fanuc *fa, const char *text, size_t len, long line) {
  if (fa->p->state->dialect == SWARF_GCODE_DIALECT_LINUXCNC)
    return swarf_gc_parser_flow_line(fa->p, text, len, line);
  return swarf_gc_parser_run_line(fa->p, text, len, line);
}

/* A block: its motion first, then its call or return. */
static int block(swarf_gc_fanuc *fa, size_t *pc, swarf_error *f) {
  const fline *l = &fa->v[*pc];
  flow_words w;
  char *b;
  int status;
  if (!may_have_flow(l->text, l->len)) {
    ++*pc;
    return run_text(fa, l->text, l->len, l->line);
  }
  fa->p->cur_line = l->line;
  if ((b = buffer(fa, l->len + 1)) == NULL) return SWARF_GC_FAIL(f, SWARF_GCODE_E_OUT_OF_MEMORY, 1);
  status = take_flow(fa, l, b, &w, f);
  if (status != SWARF_OK) return status;
  if (w.code == 0 || !rest_empty(b, l->len, body_start(b, l->len, &(long){0}))) {
    status = run_text(fa, b, l->len, l->line);
    if (status != SWARF_OK || w.code == 0) {
      ++*pc;
      return status;
    }
  }
  if (fa->p->ended) return SWARF_OK;
  if (w.code == 99) return ret(fa, pc, &w, f);
  return call(fa, pc, &w, f);
}

int swarf_gc_fanuc_run(swarf_gc_fanuc *fa, long *err_line, swarf_error *f) {
  size_t pc = 0;
  long run = 0;
  int status = SWARF_OK;
  if (fa->n == 0) return SWARF_OK;
  if (index_lines(fa) != 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_OUT_OF_MEMORY, 1);
  while (status == SWARF_OK && pc < fa->n && !fa->p->ended && fa->p->status == SWARF_OK) {
    const fline *l = &fa->v[pc];
    *err_line = l->line;
    fa->p->cur_line = l->line;
    if (++run + fa->p->work_extra > (long)fa->n + fa->p->work_limit) {
      status = SWARF_GC_FAIL(f, SWARF_GCODE_E_O_WORK_LIMIT, 1, fa->p->work_limit);
      break;
    }
    if (l->onum >= 0) {
      if (l->pstart == current_prog(fa)) { /* the running program's own number */
        pc++;
        continue;
      }
      if (fa->depth == 0) break; /* the main program ends where the next one starts */
      swarf_gc_parser_note(fa->p, 1, "O%ld starts before an M99 ended the subprogram: returned",
                           l->onum);
      flow_words none;
      memset(&none, 0, sizeof none);
      status = ret(fa, &pc, &none, f);
      continue;
    }
    if (l->kind != ST_NONE) {
      int skipped = 0;
      size_t i = skip(l->text, l->len, 0);
      if (i < l->len && l->text[i] == '/' && fa->p->block_delete) skipped = 1;
      status = skipped ? (pc++, SWARF_OK) : statement(fa, &pc, f);
    } else
      status = block(fa, &pc, f);
  }
  if (fa->p->status != SWARF_OK) return fa->p->status;
  return status;
}
