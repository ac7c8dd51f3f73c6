/* SPDX-License-Identifier: MPL-2.0 */
/* block.c -- the words of one line, read into a block.
 *
 * Reads every token the lexer gives: each letter may appear once (G and M
 * excepted), G and M codes are filed under their modal group (two codes of
 * one group are an error, as in LinuxCNC), N must come first; parameter
 * settings and the last comment are kept for the interpreter. Codes and
 * letters LinuxCNC knows but this version does not handle are refused here
 * with a "not supported yet" message at their column. The block is plain
 * data owned by the caller; reading it changes no state.
 */
#include <math.h>
#include <string.h>

#include "gcode_private.h"

#define G80 800

/* Letters that are words in LinuxCNC but not in this version, and why. */
static const char *later_letter(char letter, int dialect) {
  switch (letter) {
  case 'E':
    if (dialect == SWARF_GCODE_DIALECT_FANUC || dialect == SWARF_GCODE_DIALECT_HAAS) return NULL;
    return "the E word (G76 threading, M66 waits) is not supported: remove it";
  case 'U':
    return "the U axis is not supported (swarf's machines move X, Y, Z and the rotary A, B, "
           "C): post the program for such a machine, or remove the U words";
  case 'V':
    return "the V axis is not supported (swarf's machines move X, Y, Z and the rotary A, B, "
           "C): post the program for such a machine, or remove the V words";
  case 'W':
    return "the W axis is not supported (swarf's machines move X, Y, Z and the rotary A, B, "
           "C): post the program for such a machine, or remove the W words";
  default:
    return NULL;
  }
}

/* The value in tenths if it is a whole number of tenths, else -1. */
static int tenths_of(double value) {
  double t = value * 10.0;
  double r = floor(t + 0.5);
  if (value < 0 || value > 100000.0 || fabs(t - r) > 1e-3) return -1;
  return (int)r;
}

/* An empty block: absent words read as 0. Word texts and parameter
 * settings are not cleared (the block is large; they are read only when
 * present). */
static void init_block(swarf_gc_block *b) {
  for (int i = 0; i < 26; i++) {
    b->words[i].present = 0;
    b->words[i].value = 0;
    b->words[i].column = 0;
    b->words[i].text[0] = '\0';
  }
  for (int i = 0; i < SWARF_GC_NGROUPS; i++)
    b->g[i].code = -1;
  for (int i = 0; i < SWARF_GC_NMGROUPS; i++)
    b->m[i].code = -1;
  b->letters = 0;
  b->m_count = b->word_count = b->assign_count = 0;
  b->comment = NULL;
  b->comment_len = 0;
  b->motion = -1;
  b->motion_column = 0;
}

static void set_code_word(swarf_gc_code_word *cw, int code, const swarf_gc_token *t) {
  cw->code = code;
  cw->column = t->column;
  memcpy(cw->text, t->word, sizeof cw->text);
}

/* G80 next to another motion code gives way to it, as in LinuxCNC's read_g
 * ("G0 G80 X1" is G0 X1): CAM preambles write such lines. */
static int add_g(swarf_gc_block *b, const swarf_gc_token *t, int dialect, swarf_error *f) {
  int code = tenths_of(t->value);
  const swarf_gc_code *c = code < 0 ? NULL : swarf_gc_dialect_g(dialect, code);
  if (c == NULL && code >= 0) c = swarf_gc_g_code(code);
  if (c == NULL) return SWARF_GC_FAIL(f, SWARF_GCODE_E_UNKNOWN_G_CODE, t->column, t->word);
  if (c->later != NULL)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_CODE_NOT_SUPPORTED, t->column, t->word, c->later);
  if (code == G80 && b->g[c->group].code >= 0) return SWARF_OK;
  if (b->g[c->group].code >= 0 && b->g[c->group].code != G80)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_G_MODAL_GROUP, t->column, b->g[c->group].text, t->word);
  set_code_word(&b->g[c->group], code, t);
  return SWARF_OK;
}

static int add_m(swarf_gc_block *b, const swarf_gc_token *t, int dialect, swarf_error *f) {
  int code = tenths_of(t->value);
  const swarf_gc_code *c = (code < 0 || code % 10 != 0) ? NULL : swarf_gc_dialect_m(dialect, code);
  if (c == NULL && code >= 0 && code % 10 == 0) c = swarf_gc_m_code(code);
  if (c != NULL && c->group == SWARF_GC_MGROUP_VENDOR) { /* any number: the builder's */
  } else if (t->value > 199.0 && !(t->value >= 400.0 && t->value < 500.0))
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_M_CODE_RANGE, t->column, t->word);
  if (c == NULL) return SWARF_GC_FAIL(f, SWARF_GCODE_E_UNKNOWN_M_CODE, t->column, t->word);
  if (c->later != NULL)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_CODE_NOT_SUPPORTED, t->column, t->word, c->later);
  if (b->m[c->group].code >= 0)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_M_MODAL_GROUP, t->column, b->m[c->group].text, t->word);
  if (++b->m_count > SWARF_GC_MAX_M_PER_LINE)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_TOO_MANY_M_CODES, t->column, t->word, b->m_count);
  set_code_word(&b->m[c->group], c->code != 0 && c->code != code ? c->code : code, t);
  return SWARF_OK;
}

static int add_other(swarf_gc_block *b, const swarf_gc_token *t, int dialect, swarf_error *f) {
  swarf_gc_word *w = &b->words[t->letter - 'A'];
  const char *later = later_letter(t->letter, dialect);
  if (later != NULL)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_LETTER_NOT_SUPPORTED, t->column, t->word, later);
  if (t->letter == 'N' && b->word_count > 0)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_LINE_NUMBER_NOT_FIRST, t->column, t->word);
  if (w->present)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_MULTIPLE_WORDS, t->column, t->letter, w->text, t->word);
  w->present = 1;
  b->letters |= SWARF_GC_LETTER(t->letter);
  w->value = t->value;
  w->column = t->column;
  memcpy(w->text, t->word, sizeof w->text);
  return SWARF_OK;
}

static int add_word(swarf_gc_block *b, const swarf_gc_token *t, int dialect, swarf_error *f) {
  int status;
  if (t->letter == 'G')
    status = add_g(b, t, dialect, f);
  else if (t->letter == 'M')
    status = add_m(b, t, dialect, f);
  else
    status = add_other(b, t, dialect, f);
  b->word_count++;
  return status;
}

static int add_assign(swarf_gc_block *b, const swarf_gc_token *t, swarf_error *f) {
  swarf_gc_assign *a;
  if (b->assign_count == SWARF_GC_MAX_ASSIGN)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_TOO_MANY_ASSIGNMENTS, t->column, SWARF_GC_MAX_ASSIGN);
  a = &b->assigns[b->assign_count++];
  a->index = t->index;
  memcpy(a->name, t->name, sizeof a->name);
  a->value = t->value;
  return SWARF_OK;
}

int swarf_gc_block_read(const char *line, size_t len, const swarf_gc_params *ps, swarf_gc_block *b,
                        swarf_error *f) {
  swarf_gc_lexer lx;
  swarf_gc_token t;
  int dialect = ps != NULL && ps->state != NULL ? ps->state->dialect : 0;
  init_block(b);
  swarf_gc_lexer_init(&lx, line, len, ps);
  for (;;) {
    int status = swarf_gc_lexer_next(&lx, &t, f);
    if (status != SWARF_OK) return status;
    if (t.kind == SWARF_GC_TOKEN_END) return SWARF_OK;
    if (t.kind == SWARF_GC_TOKEN_WORD) status = add_word(b, &t, dialect, f);
    if (t.kind == SWARF_GC_TOKEN_ASSIGN) status = add_assign(b, &t, f);
    if (t.kind == SWARF_GC_TOKEN_COMMENT) {
      b->comment = t.text;
      b->comment_len = t.text_len;
    }
    if (status != SWARF_OK) return status;
  }
}

int swarf_gc_block_has_axis(const swarf_gc_block *b) {
  return (b->letters & (SWARF_GC_LETTER('X') | SWARF_GC_LETTER('Y') | SWARF_GC_LETTER('Z') |
                        SWARF_GC_LETTER('A') | SWARF_GC_LETTER('B') | SWARF_GC_LETTER('C'))) != 0;
}
