/* SPDX-License-Identifier: MPL-2.0 */
/* expr.c -- values of words: numbers, #parameters, [expressions], functions.
 *
 * LinuxCNC's read_real_value and read_real_expression, over the lexer's
 * line: blanks mean nothing, letters are case-insensitive. Binary operators
 * by precedence (all left-associative): ** ; * / MOD ; + - ; EQ NE GT GE
 * LT LE ; AND OR XOR. Functions: ABS ACOS ASIN ATAN[y]/[x] COS EXP FIX FUP
 * LN ROUND SIN SQRT TAN (degrees) and EXISTS[#<name>]. A parameter is #n
 * (n a value, 1..5601) or #<name>; reading an unset named parameter is an
 * error. Nothing is owned or changed here; values come from lx->params.
 */
#include <ctype.h>
#include <math.h>
#include <string.h>

#include "gcode_private.h"

#define DEG (3.14159265358979323846 / 180.0)
#define MAX_DEPTH 64 /* nesting of brackets and parameters */

static int col(const swarf_gc_lexer *lx) {
  return (int)lx->pos + 1;
}

static int peek(swarf_gc_lexer *lx) {
  return swarf_gc_lexer_peek(lx);
}

/* Matches `word` (upper case) at the position, blanks between letters
 * allowed; advances only on a match. */
static int match(swarf_gc_lexer *lx, const char *word) {
  size_t save = lx->pos;
  for (const char *w = word; *w; w++) {
    swarf_gc_lexer_skip_blanks(lx);
    if (lx->pos >= lx->len || toupper((unsigned char)lx->line[lx->pos]) != *w) {
      lx->pos = save;
      return 0;
    }
    lx->pos++;
  }
  return 1;
}

/* The character c, or error `code` (its message takes no argument). */
static int expect(swarf_gc_lexer *lx, char c, int code, swarf_error *f) {
  if (peek(lx) != c) return swarf_gc_fail_code(f, code, col(lx));
  lx->pos++;
  return SWARF_OK;
}

static int value(swarf_gc_lexer *lx, double *v, int depth, swarf_error *f);
static int expression(swarf_gc_lexer *lx, double *v, int depth, swarf_error *f);

int swarf_gc_expr_name(swarf_gc_lexer *lx, char name[SWARF_GC_NAME_MAX], swarf_error *f) {
  size_t n = 0;
  int at = col(lx);
  lx->pos++; /* '<' */
  for (; lx->pos < lx->len && lx->line[lx->pos] != '>'; lx->pos++) {
    char c = lx->line[lx->pos];
    if (c == ' ' || c == '\t' || c == '\r') continue;
    if (n + 1 >= SWARF_GC_NAME_MAX) return SWARF_GC_FAIL(f, SWARF_GCODE_E_NAME_TOO_LONG, at);
    name[n++] = (char)tolower((unsigned char)c);
  }
  if (lx->pos >= lx->len) return SWARF_GC_FAIL(f, SWARF_GCODE_E_NAME_NOT_TERMINATED, at);
  lx->pos++;
  name[n] = '\0';
  if (n == 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_NAME_EMPTY, at);
  return SWARF_OK;
}

/* After '#': a name or an index value. */
static int param_ref(swarf_gc_lexer *lx, int *index, char name[SWARF_GC_NAME_MAX], int depth,
                     swarf_error *f) {
  double v;
  int at = col(lx), status;
  *index = 0;
  name[0] = '\0';
  if (peek(lx) == '<') return swarf_gc_expr_name(lx, name, f);
  status = value(lx, &v, depth + 1, f);
  if (status != SWARF_OK) return status;
  if (fabs(v - floor(v + 0.5)) > 1e-4) return SWARF_GC_FAIL(f, SWARF_GCODE_E_INDEX_NOT_INTEGER, at);
  if (fabs(v) < 0.5 && lx->params != NULL && lx->params->state != NULL &&
      swarf_gc_fanuc_like(lx->params->state)) {
    *index = -1; /* Fanuc's #0: always vacant, read as 0 here */
    return SWARF_OK;
  }
  if (v < 1 || v >= SWARF_GC_NPARAMS) return SWARF_GC_FAIL(f, SWARF_GCODE_E_PARAMETER_RANGE, at);
  *index = (int)floor(v + 0.5);
  return SWARF_OK;
}

int swarf_gc_expr_param_ref(swarf_gc_lexer *lx, int *index, char name[SWARF_GC_NAME_MAX],
                            swarf_error *f) {
  int at, status;
  lx->pos++; /* '#' */
  at = col(lx);
  status = param_ref(lx, index, name, 0, f);
  if (status == SWARF_OK && *index < 0) /* #0 cannot be set */
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_PARAMETER_RANGE, at);
  return status;
}

static int parameter(swarf_gc_lexer *lx, double *v, int depth, swarf_error *f) {
  char name[SWARF_GC_NAME_MAX];
  int index, at = col(lx), status;
  if (lx->params == NULL) return SWARF_GC_FAIL(f, SWARF_GCODE_E_PARAMETER_NOT_ALLOWED, at);
  lx->pos++;
  status = param_ref(lx, &index, name, depth, f);
  if (status != SWARF_OK) return status;
  if (index != 0) {
    *v = index > 0 ? swarf_gc_param_get(lx->params, index) : 0.0;
    return SWARF_OK;
  }
  if (swarf_gc_param_named(lx->params, name, v) != 0)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_NAMED_UNDEFINED, at, name);
  return SWARF_OK;
}

static int exists(swarf_gc_lexer *lx, double *v, swarf_error *f) {
  char name[SWARF_GC_NAME_MAX];
  double ignored;
  int index, status = expect(lx, '[', SWARF_GCODE_E_LEFT_BRACKET_MISSING, f);
  if (status == SWARF_OK && peek(lx) != '#')
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_HASH_EXPECTED, col(lx));
  if (status == SWARF_OK) {
    lx->pos++;
    status = param_ref(lx, &index, name, 1, f);
  }
  if (status == SWARF_OK) status = expect(lx, ']', SWARF_GCODE_E_RIGHT_BRACKET_MISSING, f);
  if (status != SWARF_OK) return status;
  *v = index > 0 || (lx->params && swarf_gc_param_named(lx->params, name, &ignored) == 0);
  return SWARF_OK;
}

typedef enum {
  F_ABS,
  F_ACOS,
  F_ASIN,
  F_COS,
  F_EXP,
  F_FIX,
  F_FUP,
  F_LN,
  F_ROUND,
  F_SIN,
  F_SQRT,
  F_TAN,
  F_ATAN,
  F_EXISTS,
  F_NONE
} func_id;

static func_id function_name(swarf_gc_lexer *lx) {
  static const char *names[] = {"ABS", "ACOS",  "ASIN", "COS",  "EXP", "FIX",  "FUP",
                                "LN",  "ROUND", "SIN",  "SQRT", "TAN", "ATAN", "EXISTS"};
  /* Longest names first where one is a prefix of another: none are, but
   * ATAN must not be read as A... (axes are not functions). */
  int c = peek(lx);
  c = c >= 0 ? toupper(c) : c; /* only the names that start with the next letter */
  for (int i = F_EXISTS; i >= 0; i--)
    if (names[i][0] == c && match(lx, names[i])) return (func_id)i;
  return F_NONE;
}

static int apply(func_id id, double x, int at, double *v, swarf_error *f) {
  switch (id) {
  case F_ABS:
    *v = fabs(x);
    break;
  case F_ACOS:
  case F_ASIN:
    if (x < -1 || x > 1)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_ARGUMENT_RANGE, at, id == F_ACOS ? "acos" : "asin");
    *v = (id == F_ACOS ? acos(x) : asin(x)) / DEG;
    break;
  case F_COS:
    *v = cos(x * DEG);
    break;
  case F_EXP:
    *v = exp(x);
    break;
  case F_FIX:
    *v = floor(x);
    break;
  case F_FUP:
    *v = ceil(x);
    break;
  case F_LN:
    if (x <= 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_LN_ARGUMENT, at);
    *v = log(x);
    break;
  case F_ROUND:
    *v = floor(x + 0.5);
    break;
  case F_SIN:
    *v = sin(x * DEG);
    break;
  case F_SQRT:
    if (x < 0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_SQRT_ARGUMENT, at);
    *v = sqrt(x);
    break;
  case F_TAN:
    *v = tan(x * DEG);
    break;
  default:
    *v = x;
    break;
  }
  if (!isfinite(*v)) return SWARF_GC_FAIL(f, SWARF_GCODE_E_NOT_A_NUMBER, at);
  return SWARF_OK;
}

static int function(swarf_gc_lexer *lx, double *v, int depth, swarf_error *f) {
  int at = col(lx), status;
  double x, y;
  func_id id = function_name(lx);
  char c = (char)peek(lx);
  if (id == F_NONE)
    return SWARF_GC_FAIL(f, SWARF_GCODE_E_UNKNOWN_WORD_START, at, (char)tolower((unsigned char)c));
  if (id == F_EXISTS) return exists(lx, v, f);
  if (peek(lx) != '[') return SWARF_GC_FAIL(f, SWARF_GCODE_E_LEFT_BRACKET_MISSING, col(lx));
  status = expression(lx, &x, depth + 1, f);
  if (status != SWARF_OK) return status;
  if (id != F_ATAN) return apply(id, x, at, v, f);
  if (peek(lx) != '/') return SWARF_GC_FAIL(f, SWARF_GCODE_E_ATAN_SLASH_MISSING, col(lx));
  lx->pos++;
  if (peek(lx) != '[') return SWARF_GC_FAIL(f, SWARF_GCODE_E_ATAN_BRACKET_MISSING, col(lx));
  status = expression(lx, &y, depth + 1, f);
  if (status == SWARF_OK) *v = atan2(x, y) / DEG;
  return status;
}

static int value(swarf_gc_lexer *lx, double *v, int depth, swarf_error *f) {
  int c = peek(lx);
  if (depth > MAX_DEPTH) return SWARF_GC_FAIL(f, SWARF_GCODE_E_EXPRESSION_TOO_DEEP, col(lx));
  if (c == '[') return expression(lx, v, depth, f);
  if (c == '#') return parameter(lx, v, depth, f);
  if (c == '+' || c == '-') {
    size_t save = lx->pos;
    int next;
    lx->pos++;
    next = peek(lx);
    if (next != -1 && next != '.' && !isdigit(next)) {
      int status = value(lx, v, depth + 1, f);
      if (c == '-') *v = -*v;
      return status;
    }
    lx->pos = save;
  }
  if (c != -1 && isalpha(c)) return function(lx, v, depth, f);
  return swarf_gc_lexer_number(lx, v, f);
}

enum {
  OP_NONE,
  OP_POW,
  OP_MUL,
  OP_DIV,
  OP_MOD,
  OP_ADD,
  OP_SUB,
  OP_EQ,
  OP_NE,
  OP_GT,
  OP_GE,
  OP_LT,
  OP_LE,
  OP_AND,
  OP_OR,
  OP_XOR
};

static int precedence(int op) {
  static const int p[] = {0, 6, 5, 5, 5, 4, 4, 3, 3, 3, 3, 3, 3, 2, 2, 2};
  return p[op];
}

/* Reads an operator if one is next (advances), else OP_NONE. */
static int read_op(swarf_gc_lexer *lx) {
  static const struct {
    const char *text;
    int op;
  } words[] = {{"MOD", OP_MOD}, {"EQ", OP_EQ}, {"NE", OP_NE},   {"GT", OP_GT}, {"GE", OP_GE},
               {"LT", OP_LT},   {"LE", OP_LE}, {"AND", OP_AND}, {"OR", OP_OR}, {"XOR", OP_XOR}};
  int c = peek(lx);
  if (c == '*') return lx->pos++, match(lx, "*") ? OP_POW : OP_MUL;
  if (c == '/') return lx->pos++, OP_DIV;
  if (c == '+') return lx->pos++, OP_ADD;
  if (c == '-') return lx->pos++, OP_SUB;
  c = c >= 0 ? toupper(c) : c; /* only the words that start with the next letter */
  for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
    if (words[i].text[0] == c && match(lx, words[i].text)) return words[i].op;
  return OP_NONE;
}

static int binary(int op, double a, double b, int at, double *v, swarf_error *f) {
  switch (op) {
  case OP_POW:
    if (a < 0 && floor(b) != b) return SWARF_GC_FAIL(f, SWARF_GCODE_E_NEGATIVE_POWER, at);
    *v = pow(a, b);
    break;
  case OP_MUL:
    *v = a * b;
    break;
  case OP_DIV:
  case OP_MOD:
    if (b == 0.0) return SWARF_GC_FAIL(f, SWARF_GCODE_E_DIVIDE_BY_ZERO, at);
    if (op == OP_DIV)
      *v = a / b;
    else {
      *v = fmod(a, b);
      if (*v < 0) *v += fabs(b);
    }
    break;
  case OP_ADD:
    *v = a + b;
    break;
  case OP_SUB:
    *v = a - b;
    break;
  case OP_EQ:
    *v = a == b;
    break;
  case OP_NE:
    *v = a != b;
    break;
  case OP_GT:
    *v = a > b;
    break;
  case OP_GE:
    *v = a >= b;
    break;
  case OP_LT:
    *v = a < b;
    break;
  case OP_LE:
    *v = a <= b;
    break;
  case OP_AND:
    *v = a != 0 && b != 0;
    break;
  case OP_OR:
    *v = a != 0 || b != 0;
    break;
  default:
    *v = (a != 0) != (b != 0);
    break;
  }
  if (!isfinite(*v)) return SWARF_GC_FAIL(f, SWARF_GCODE_E_NOT_A_NUMBER, at);
  return SWARF_OK;
}

/* Precedence climbing: operands of operators binding at least `min`. */
static int climb(swarf_gc_lexer *lx, double *lhs, int min, int depth, swarf_error *f) {
  for (;;) {
    size_t save = lx->pos;
    int at, op, status;
    swarf_gc_lexer_skip_blanks(lx);
    at = col(lx);
    op = read_op(lx);
    double rhs;
    if (op == OP_NONE || precedence(op) < min) {
      lx->pos = save;
      return SWARF_OK;
    }
    status = value(lx, &rhs, depth + 1, f);
    if (status == SWARF_OK) status = climb(lx, &rhs, precedence(op) + 1, depth + 1, f);
    if (status == SWARF_OK) status = binary(op, *lhs, rhs, at, lhs, f);
    if (status != SWARF_OK) return status;
  }
}

static int expression(swarf_gc_lexer *lx, double *v, int depth, swarf_error *f) {
  int status;
  lx->pos++; /* '[' */
  status = value(lx, v, depth + 1, f);
  if (status == SWARF_OK) status = climb(lx, v, 2, depth, f);
  if (status == SWARF_OK && peek(lx) != ']') {
    int c = peek(lx);
    return c == -1 ? SWARF_GC_FAIL(f, SWARF_GCODE_E_UNCLOSED_EXPRESSION, col(lx))
                   : SWARF_GC_FAIL(f, SWARF_GCODE_E_UNKNOWN_OPERATION, col(lx), (char)c);
  }
  if (status == SWARF_OK) lx->pos++;
  return status;
}

int swarf_gc_expr_value(swarf_gc_lexer *lx, double *v, swarf_error *f) {
  return value(lx, v, 0, f);
}
