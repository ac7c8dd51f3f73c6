/* SPDX-License-Identifier: MPL-2.0 */
/* lexer.c -- one line of program text -> tokens, each with its column.
 *
 * Follows LinuxCNC's reading: blanks (space, tab, CR) mean nothing outside
 * comments, so "X 1 0.5" is X10.5; letters are case-insensitive; `( ... )`
 * is a comment (no nesting) and `;` comments out the rest of the line.
 * A word is a letter and a number: optional sign, digits with at most one
 * point ("1.", ".5", "-.5", "+3"). Numbers are converted here, without the C
 * locale's help, and must stay within SWARF_GC_NUMBER_MAX.
 *
 * A value that is not a plain number (#1, [1+2], -#2, SIN[30]) goes to
 * expr.c; `#n = value` and `#<name> = value` are assignment tokens. An O
 * word here is out of place (oword.c reads control lines before the lexer).
 * The lexer owns nothing: tokens point into the caller's line.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "gcode_private.h"

#define NUMBER_TEXT_MAX 128 /* longest number accepted, blanks removed */

static int is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}
static int is_digit(char c) {
  return c >= '0' && c <= '9';
}
static int is_letter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
static char upper(char c) {
  return (c >= 'a' && c <= 'z') ? (char)(c - 'a' + 'A') : c;
}
static int is_number_char(char c) {
  return is_digit(c) || c == '.' || c == '+' || c == '-';
}

static void skip_blanks(swarf_gc_lexer *lx) {
  while (lx->pos < lx->len && is_blank(lx->line[lx->pos]))
    lx->pos++;
}

static int column_of(size_t pos) {
  return (int)pos + 1;
}

void swarf_gc_lexer_init(swarf_gc_lexer *lx, const char *line, size_t len,
                         const swarf_gc_params *params) {
  lx->line = line;
  lx->len = len;
  lx->pos = 0;
  lx->params = params;
}

void swarf_gc_lexer_skip_blanks(swarf_gc_lexer *lx) {
  skip_blanks(lx);
}

int swarf_gc_lexer_peek(swarf_gc_lexer *lx) {
  skip_blanks(lx);
  return lx->pos < lx->len ? (unsigned char)lx->line[lx->pos] : -1;
}

/* 'x' for a printable character, '\xNN' otherwise. */
static void describe_char(char c, char *out, size_t cap) {
  unsigned char u = (unsigned char)c;
  if (u >= 0x20 && u < 0x7f)
    snprintf(out, cap, "'%c'", c);
  else
    snprintf(out, cap, "'\\x%02X'", u);
}

static int lex_paren_comment(swarf_gc_lexer *lx, swarf_gc_token *tok, swarf_error *f) {
  size_t open = lx->pos;
  for (size_t i = open + 1; i < lx->len; i++) {
    if (lx->line[i] == ')') {
      tok->kind = SWARF_GC_TOKEN_COMMENT;
      tok->column = column_of(open);
      tok->text = lx->line + open + 1;
      tok->text_len = i - open - 1;
      lx->pos = i + 1;
      return SWARF_OK;
    }
    if (lx->line[i] == '(') return SWARF_GC_FAIL(f, SWARF_GCODE_E_NESTED_COMMENT, column_of(i));
  }
  return SWARF_GC_FAIL(f, SWARF_GCODE_E_UNCLOSED_COMMENT, column_of(open));
}

static void lex_semicolon_comment(swarf_gc_lexer *lx, swarf_gc_token *tok) {
  tok->kind = SWARF_GC_TOKEN_COMMENT;
  tok->column = column_of(lx->pos);
  tok->text = lx->line + lx->pos + 1;
  tok->text_len = lx->len - lx->pos - 1;
  while (tok->text_len > 0 && tok->text[tok->text_len - 1] == '\r') /* a CRLF line's end */
    tok->text_len--;
  lx->pos = lx->len;
}

/* Powers of ten that are exact doubles. */
static const double exact_pow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                     1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                     1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

static double scale10(uint64_t mant, long exp10) {
  double m = (double)mant;
  if (exp10 >= 0) return exp10 <= 22 ? m * exact_pow10[exp10] : m * pow(10.0, (double)exp10);
  if (exp10 >= -22) return m / exact_pow10[-exp10];
  return m / 1e22 / pow(10.0, (double)(-exp10 - 22));
}

enum { NUMBER_OK, NUMBER_BAD, NUMBER_RANGE };

/* Converts "[+-]digits[.digits]" (at least one digit) to a double. Keeps 19
 * significant digits, which is far beyond a double's precision. */
static int number_value(const char *s, size_t n, double *out) {
  size_t i = 0;
  int negative = 0, seen_digit = 0, seen_point = 0, kept = 0;
  uint64_t mant = 0;
  long exp10 = 0;
  if (i < n && (s[i] == '+' || s[i] == '-')) negative = s[i++] == '-';
  for (; i < n; i++) {
    char c = s[i];
    if (c == '.' && !seen_point) {
      seen_point = 1;
      continue;
    }
    if (!is_digit(c)) return NUMBER_BAD;
    seen_digit = 1;
    if (mant == 0 && c == '0') {
      exp10 -= seen_point;
      continue;
    }
    if (kept < 19) {
      mant = mant * 10 + (uint64_t)(c - '0');
      kept++;
      exp10 -= seen_point;
    } else if (!seen_point)
      exp10++;
  }
  if (!seen_digit) return NUMBER_BAD;
  if (mant != 0 && kept + exp10 > 10) return NUMBER_RANGE;
  *out = scale10(mant, exp10);
  if (*out > SWARF_GC_NUMBER_MAX) return NUMBER_RANGE;
  if (negative) *out = -*out;
  return NUMBER_OK;
}

/* Gathers the characters of the number after a letter, blanks removed. */
static size_t gather_number(swarf_gc_lexer *lx, char *buf, size_t *len) {
  size_t total = 0, n = 0, pos = lx->pos;
  for (; pos < lx->len; pos++) {
    char c = lx->line[pos];
    if (is_blank(c)) continue;
    if (!is_number_char(c)) break;
    if (n < NUMBER_TEXT_MAX) buf[n++] = c;
    total++;
  }
  lx->pos = pos;
  *len = n;
  return total;
}

static void word_text(char *out, char letter, const char *num, size_t len) {
  size_t keep = len < SWARF_GC_WORD_TEXT - 5 ? len : SWARF_GC_WORD_TEXT - 5;
  out[0] = letter;
  memcpy(out + 1, num, keep);
  strcpy(out + 1 + keep, keep < len ? "..." : "");
}

static int number_status(int status, int column, const char *word, swarf_error *f) {
  switch (status) {
  case NUMBER_BAD:
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_BAD_NUMBER, column, word);
  case NUMBER_RANGE:
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_NUMBER_RANGE, column, word, SWARF_GC_NUMBER_MAX);
  }
  return SWARF_OK;
}

/* A number inside an expression: a sign only first, then digits and one
 * point (blanks skipped), so that "1-2" stays an operation. */
static size_t gather_operand(swarf_gc_lexer *lx, char *buf, size_t *len) {
  size_t total = 0;
  *len = 0;
  for (;;) {
    char c;
    skip_blanks(lx);
    if (lx->pos >= lx->len) break;
    c = lx->line[lx->pos];
    if (!(is_digit(c) || c == '.' || (total == 0 && (c == '+' || c == '-')))) break;
    if (*len < NUMBER_TEXT_MAX) buf[(*len)++] = c;
    total++;
    lx->pos++;
  }
  return total;
}

int swarf_gc_lexer_number(swarf_gc_lexer *lx, double *v, swarf_error *f) {
  char buf[NUMBER_TEXT_MAX], word[SWARF_GC_WORD_TEXT];
  size_t len, total;
  int column = column_of(lx->pos);
  total = gather_operand(lx, buf, &len);
  word_text(word, ' ', buf, len);
  if (total == 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_NUMBER_CONVERSION, column, word + 1);
  if (total > NUMBER_TEXT_MAX) return SWARF_GC_FAIL(f, SWARF_GCODE_E_NUMBER_TOO_LONG, column);
  return number_status(number_value(buf, len, v), column, word + 1, f);
}

/* The text of a word from `from` to the lexer's position, blanks removed. */
static void raw_text(const swarf_gc_lexer *lx, size_t from, char *out) {
  size_t n = 0;
  for (size_t i = from; i < lx->pos && n + 4 < SWARF_GC_WORD_TEXT; i++)
    if (!is_blank(lx->line[i])) out[n++] = upper(lx->line[i]);
  if (n + 4 >= SWARF_GC_WORD_TEXT)
    strcpy(out + n, "...");
  else
    out[n] = '\0';
}

static int is_value_start(int c) {
  return c == '#' || c == '[' || is_letter((char)c);
}

/* A value that is not a plain number: expr.c reads it. */
static int lex_expr_word(swarf_gc_lexer *lx, swarf_gc_token *tok, size_t from, char letter,
                         int column, swarf_error *f) {
  int status = swarf_gc_expr_value(lx, &tok->value, f);
  if (status != SWARF_OK) return status;
  raw_text(lx, from, tok->word);
  if (!isfinite(tok->value) || fabs(tok->value) > SWARF_GC_NUMBER_MAX)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_NUMBER_RANGE, column, tok->word, SWARF_GC_NUMBER_MAX);
  tok->kind = SWARF_GC_TOKEN_WORD;
  tok->letter = letter;
  tok->column = column;
  return SWARF_OK;
}

static int lex_word(swarf_gc_lexer *lx, swarf_gc_token *tok, swarf_error *f) {
  char buf[NUMBER_TEXT_MAX];
  size_t len, total, from = lx->pos;
  int column = column_of(lx->pos), next;
  char letter = upper(lx->line[lx->pos++]);
  if (letter == 'O') return SWARF_GC_FAIL(f, SWARF_GCODE_E_O_WORD_NOT_FIRST, column);
  next = swarf_gc_lexer_peek(lx);
  if (next != -1 && is_value_start(next)) return lex_expr_word(lx, tok, from, letter, column, f);
  if (next == '-' || next == '+') {
    size_t save = lx->pos;
    int after;
    lx->pos++;
    after = swarf_gc_lexer_peek(lx);
    lx->pos = save;
    if (after != -1 && is_value_start(after))
      return lex_expr_word(lx, tok, from, letter, column, f);
  }
  total = gather_number(lx, buf, &len);
  word_text(tok->word, letter, buf, len);
  if (total > NUMBER_TEXT_MAX)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_WORD_NUMBER_TOO_LONG, column, tok->word);
  if (number_status(number_value(buf, len, &tok->value), column, tok->word, f) != SWARF_OK)
    return f->status;
  tok->kind = SWARF_GC_TOKEN_WORD;
  tok->letter = letter;
  tok->column = column;
  return SWARF_OK;
}

/* #n = value or #<name> = value. */
static int lex_assign(swarf_gc_lexer *lx, swarf_gc_token *tok, swarf_error *f) {
  int column = column_of(lx->pos), status;
  if (lx->params == NULL) return SWARF_GC_FAIL(f, SWARF_GCODE_E_PARAMETER_NOT_ALLOWED, column);
  status = swarf_gc_expr_param_ref(lx, &tok->index, tok->name, f);
  if (status != SWARF_OK) return status;
  if (swarf_gc_lexer_peek(lx) != '=')
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_EQUAL_SIGN_MISSING, column_of(lx->pos));
  lx->pos++;
  status = swarf_gc_expr_value(lx, &tok->value, f);
  if (status != SWARF_OK) return status;
  if (tok->index >= 5400 && tok->index <= 5428)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_PARAMETER_READ_ONLY, column, tok->index);
  tok->kind = SWARF_GC_TOKEN_ASSIGN;
  tok->column = column;
  return SWARF_OK;
}

static int lex_bad_char(swarf_gc_lexer *lx, swarf_error *f) {
  char c = lx->line[lx->pos], shown[8];
  int column = column_of(lx->pos);
  describe_char(c, shown, sizeof shown);
  return SWARF_GC_FAIL(f, SWARF_GCODE_E_BAD_CHARACTER, column, shown);
}

int swarf_gc_lexer_next(swarf_gc_lexer *lx, swarf_gc_token *tok, swarf_error *f) {
  char c;
  tok->text = NULL;
  tok->text_len = 0;
  tok->word[0] = '\0';
  skip_blanks(lx);
  if (lx->pos >= lx->len) {
    tok->kind = SWARF_GC_TOKEN_END;
    tok->column = column_of(lx->pos);
    return SWARF_OK;
  }
  c = lx->line[lx->pos];
  if (c == '(') return lex_paren_comment(lx, tok, f);
  if (c == ';') {
    lex_semicolon_comment(lx, tok);
    return SWARF_OK;
  }
  if (is_letter(c)) return lex_word(lx, tok, f);
  if (c == '#') return lex_assign(lx, tok, f);
  return lex_bad_char(lx, f);
}
