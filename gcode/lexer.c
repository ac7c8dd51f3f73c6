/* lexer.c -- one line of program text -> tokens, each with its column.
 *
 * Follows LinuxCNC's reading: blanks (space, tab, CR) mean nothing outside
 * comments, so "X 1 0.5" is X10.5; letters are case-insensitive; `( ... )`
 * is a comment (no nesting) and `;` comments out the rest of the line.
 * A word is a letter and a number: optional sign, digits with at most one
 * point ("1.", ".5", "-.5", "+3"). Numbers are converted here, without the C
 * locale's help, and must stay within SWARF_GC_NUMBER_MAX.
 *
 * A word's value is a separate step so that parameters (#1) and expressions
 * ([1+2]) can be added as further value kinds; today they are refused, at
 * their column. The lexer owns nothing: tokens point into the caller's line.
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

void swarf_gc_lexer_init(swarf_gc_lexer *lx, const char *line, size_t len) {
  lx->line = line;
  lx->len = len;
  lx->pos = 0;
}

/* 'x' for a printable character, '\xNN' otherwise. */
static void describe_char(char c, char *out, size_t cap) {
  unsigned char u = (unsigned char)c;
  if (u >= 0x20 && u < 0x7f)
    snprintf(out, cap, "'%c'", c);
  else
    snprintf(out, cap, "'\\x%02X'", u);
}

static int lex_paren_comment(swarf_gc_lexer *lx, swarf_gc_token *tok, swarf_gc_fault *f) {
  size_t open = lx->pos;
  for (size_t i = open + 1; i < lx->len; i++) {
    if (lx->line[i] == ')') {
      tok->kind = SWARF_GC_TOKEN_COMMENT;
      tok->column = column_of(open);
      tok->text = lx->line + open + 1;
      tok->text_len = i - open - 1;
      lx->pos = i + 1;
      return SWARF_GCODE_OK;
    }
    if (lx->line[i] == '(')
      return swarf_gc_fail(f, SWARF_GCODE_ERR_SYNTAX, column_of(i), "Nested comment found");
  }
  return swarf_gc_fail(f, SWARF_GCODE_ERR_SYNTAX, column_of(open), "Unclosed comment found");
}

static void lex_semicolon_comment(swarf_gc_lexer *lx, swarf_gc_token *tok) {
  tok->kind = SWARF_GC_TOKEN_COMMENT;
  tok->column = column_of(lx->pos);
  tok->text = lx->line + lx->pos + 1;
  tok->text_len = lx->len - lx->pos - 1;
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
  size_t total = 0;
  *len = 0;
  for (;;) {
    skip_blanks(lx);
    if (lx->pos >= lx->len || !is_number_char(lx->line[lx->pos])) break;
    if (*len < NUMBER_TEXT_MAX) buf[(*len)++] = lx->line[lx->pos];
    total++;
    lx->pos++;
  }
  return total;
}

static void word_text(char *out, char letter, const char *num, size_t len) {
  size_t keep = len < SWARF_GC_WORD_TEXT - 5 ? len : SWARF_GC_WORD_TEXT - 5;
  out[0] = letter;
  memcpy(out + 1, num, keep);
  strcpy(out + 1 + keep, keep < len ? "..." : "");
}

static int refuse_value(swarf_gc_lexer *lx, char letter, swarf_gc_fault *f) {
  char c = lx->line[lx->pos];
  const char *what = c == '#' ? "parameters (#)" : "expressions ([...])";
  return swarf_gc_fail(f, SWARF_GCODE_ERR_SYNTAX, column_of(lx->pos),
                       "%s are not supported yet (in the value of a %c word)", what, letter);
}

static int lex_word(swarf_gc_lexer *lx, swarf_gc_token *tok, swarf_gc_fault *f) {
  char buf[NUMBER_TEXT_MAX];
  size_t len, total;
  int column = column_of(lx->pos);
  char letter = upper(lx->line[lx->pos++]);
  if (letter == 'O')
    return swarf_gc_fail(f, SWARF_GCODE_ERR_SYNTAX, column,
                         "O-words (subroutines and flow control) are not supported yet");
  total = gather_number(lx, buf, &len);
  if (total == 0 && lx->pos < lx->len && (lx->line[lx->pos] == '#' || lx->line[lx->pos] == '['))
    return refuse_value(lx, letter, f);
  word_text(tok->word, letter, buf, len);
  if (total > NUMBER_TEXT_MAX)
    return swarf_gc_fail(f, SWARF_GCODE_ERR_SYNTAX, column, "number too long in word \"%s\"",
                         tok->word);
  switch (number_value(buf, len, &tok->value)) {
  case NUMBER_BAD:
    return swarf_gc_fail(f, SWARF_GCODE_ERR_SYNTAX, column, "bad number format in word \"%s\"",
                         tok->word);
  case NUMBER_RANGE:
    return swarf_gc_fail(f, SWARF_GCODE_ERR_SYNTAX, column,
                         "number out of range in word \"%s\" (magnitude above %g)", tok->word,
                         SWARF_GC_NUMBER_MAX);
  }
  tok->kind = SWARF_GC_TOKEN_WORD;
  tok->letter = letter;
  tok->value_kind = SWARF_GC_VALUE_NUMBER;
  tok->column = column;
  return SWARF_GCODE_OK;
}

static int lex_bad_char(swarf_gc_lexer *lx, swarf_gc_fault *f) {
  char c = lx->line[lx->pos], shown[8];
  int column = column_of(lx->pos);
  if (c == '#')
    return swarf_gc_fail(f, SWARF_GCODE_ERR_SYNTAX, column, "parameters (#) are not supported yet");
  if (c == '[')
    return swarf_gc_fail(f, SWARF_GCODE_ERR_SYNTAX, column,
                         "expressions ([...]) are not supported yet");
  describe_char(c, shown, sizeof shown);
  return swarf_gc_fail(f, SWARF_GCODE_ERR_SYNTAX, column, "Bad character %s used", shown);
}

int swarf_gc_lexer_next(swarf_gc_lexer *lx, swarf_gc_token *tok, swarf_gc_fault *f) {
  char c;
  tok->text = NULL;
  tok->text_len = 0;
  tok->word[0] = '\0';
  skip_blanks(lx);
  if (lx->pos >= lx->len) {
    tok->kind = SWARF_GC_TOKEN_END;
    tok->column = column_of(lx->pos);
    return SWARF_GCODE_OK;
  }
  c = lx->line[lx->pos];
  if (c == '(') return lex_paren_comment(lx, tok, f);
  if (c == ';') {
    lex_semicolon_comment(lx, tok);
    return SWARF_GCODE_OK;
  }
  if (is_letter(c)) return lex_word(lx, tok, f);
  return lex_bad_char(lx, f);
}
