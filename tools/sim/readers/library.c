/* SPDX-License-Identifier: MPL-2.0 */
/* library.c -- tool libraries (`--tool-library FILE`): full assemblies in
 * JSON, read with jansson.
 *
 *   {
 *     "tools": [
 *       { "number": 1, "cutter": "flat,D6", "flutes": 12, "stickout": 30,
 *         "shank": 6, "holder": [ {"diameter": 20, "height": 40},
 *                                 {"diameter": [20, 32], "height": 10} ],
 *         "length": 85.2, "comment": "6 mm end mill in an ER20 collet" }
 *     ]
 *   }
 *
 * "cutter" is a --tool spec without "T<n>=" (any family), "holder" may also
 * be a --holder string ("20x40,20-32x10"); all lengths mm. Unknown keys are
 * refused (a typo would silently drop a holder). jansson only reports places
 * for syntax errors; for the rest, json_place finds the line of the entry (or
 * key) in the text, which jansson has already proved well-formed.
 */
#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assembly.h"
#include "swarf_file.h"

#define LIBRARY_FILE_MAX ((long long)1 << 26) /* 64 MiB of JSON */

/* ---- Where an entry is in the text ----------------------------------------- */

typedef struct {
  const char *s, *end;
  long line;
} json_cursor;

static void skip_blank(json_cursor *c) {
  while (c->s < c->end && strchr(" \t\r\n", *c->s) != NULL)
    if (*c->s++ == '\n') c->line++;
}

/* Past a string at c->s (on its opening quote); copies up to n-1 bytes. */
static void skip_string(json_cursor *c, char *copy, size_t n) {
  size_t k = 0;
  for (c->s++; c->s < c->end && *c->s != '"'; c->s++) {
    if (*c->s == '\\' && c->s + 1 < c->end) c->s++;
    if (k + 1 < n) copy[k++] = *c->s;
  }
  c->s++;
  if (n > 0) copy[k] = '\0';
}

static void skip_scalar(json_cursor *c) {
  while (c->s < c->end && strchr(",]} \t\r\n", *c->s) == NULL)
    c->s++;
}

/* The line of key `key` of element `elem` of the top-level "tools" array
 * (key NULL: of the element itself; a key not there: the element's line). */
static long json_place(const char *text, size_t len, int elem, const char *key) {
  json_cursor c = {text, text + len, 1};
  int depth = 0, index = -1, in_tools = 0;
  long elem_line = 1;
  char word[64], last_key[64] = "";
  while (c.s < c.end) {
    skip_blank(&c);
    if (c.s >= c.end) break;
    const char ch = *c.s;
    if (depth == 2 && in_tools && ch != ',' && ch != ']' && ch != ':') { /* an element starts */
      if (++index == elem) {
        elem_line = c.line;
        if (key == NULL) return elem_line;
      }
    }
    if (ch == '"') {
      skip_string(&c, word, sizeof word);
      skip_blank(&c);
      if (c.s < c.end && *c.s == ':') { /* a key */
        if (depth == 3 && in_tools && index == elem && strcmp(word, key) == 0) return c.line;
        if (depth == 1) snprintf(last_key, sizeof last_key, "%s", word);
        c.s++;
      }
      continue;
    }
    if (ch == '{' || ch == '[') {
      depth++;
      if (depth == 2 && ch == '[' && strcmp(last_key, "tools") == 0) in_tools = 1;
    } else if (ch == '}' || ch == ']') {
      if (depth == 3 && in_tools && index == elem) return elem_line;
      if (depth == 2) in_tools = 0;
      depth--;
    } else if (ch != ',' && ch != ':') {
      skip_scalar(&c);
      continue;
    }
    c.s++;
  }
  return elem_line;
}

/* ---- Reading the entries ---------------------------------------------------- */

typedef struct {
  const char *path;
  const char *text;
  size_t len;
  swarf_error *err;
} library_src;

static swarf_status lib_error(const library_src *src, int elem, const char *key, const char *fmt,
                              ...) __attribute__((format(printf, 4, 5)));
static swarf_status lib_error(const library_src *src, int elem, const char *key, const char *fmt,
                              ...) {
  char what[400];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  swarf_error_at(src->err, src->path, elem >= 0 ? json_place(src->text, src->len, elem, key) : 1, 0,
                 key != NULL ? key : "");
  return swarf_error_set(src->err, SWARF_ERR_TOOL, "%s", what);
}

/* A number > 0 (or >= 0 with zero_ok) under key, or 0 when absent. */
static swarf_status get_length(const library_src *src, json_t *tool, int elem, const char *key,
                               double *out) {
  json_t *v = json_object_get(tool, key);
  *out = 0;
  if (v == NULL) return SWARF_OK;
  if (!json_is_number(v) || !isfinite(json_number_value(v)))
    return lib_error(src, elem, key, "\"%s\" must be a number (mm)", key);
  *out = json_number_value(v);
  if (!(*out > 0) && strcmp(key, "length") != 0)
    return lib_error(src, elem, key, "\"%s\" must be > 0 mm", key);
  return SWARF_OK;
}

/* One holder piece {"diameter": D or [D1, D2], "height": H}. */
static swarf_status get_piece(const library_src *src, json_t *p, int elem,
                              swarf_sim_holder_part *h) {
  json_t *d = json_is_object(p) ? json_object_get(p, "diameter") : NULL;
  json_t *ht = json_is_object(p) ? json_object_get(p, "height") : NULL;
  const char *key;
  json_t *v;
  if (d != NULL && json_is_array(d) && json_array_size(d) == 2) {
    h->d0 = json_is_number(json_array_get(d, 0)) ? json_number_value(json_array_get(d, 0)) : -1;
    h->d1 = json_is_number(json_array_get(d, 1)) ? json_number_value(json_array_get(d, 1)) : -1;
  } else {
    h->d0 = h->d1 = d != NULL && json_is_number(d) ? json_number_value(d) : -1;
  }
  h->height = ht != NULL && json_is_number(ht) ? json_number_value(ht) : -1;
  if (json_is_object(p)) {
    json_object_foreach(p, key, v) {
      if (strcmp(key, "diameter") != 0 && strcmp(key, "height") != 0)
        return lib_error(src, elem, "holder",
                         "unknown key \"%s\" in a holder piece (diameter, height)", key);
    }
  }
  if (!(h->d0 > 0) || !(h->d1 > 0) || !(h->height > 0) || !isfinite(h->d0 + h->d1 + h->height))
    return lib_error(
        src, elem, "holder",
        "a holder piece is {\"diameter\": D or [BOTTOM, TOP], \"height\": H}, all > 0 mm");
  return SWARF_OK;
}

static swarf_status get_holder(const library_src *src, json_t *tool, int elem, int number,
                               swarf_sim_tool *t) {
  json_t *h = json_object_get(tool, "holder"), *p;
  size_t i;
  if (h == NULL) return SWARF_OK;
  if (json_is_string(h)) {
    char spec[512];
    swarf_sim_tool tmp;
    swarf_error e;
    snprintf(spec, sizeof spec, "T%d=%s", number, json_string_value(h));
    if (swarf_sim_parse_holder(spec, &tmp, &e) != SWARF_OK)
      return lib_error(src, elem, "holder", "\"holder\": %s", e.message);
    t->nholder = tmp.nholder;
    memcpy(t->holder, tmp.holder, sizeof t->holder);
    return SWARF_OK;
  }
  if (!json_is_array(h) || json_array_size(h) == 0 || json_array_size(h) > SWARF_SIM_MAX_HOLDER)
    return lib_error(src, elem, "holder",
                     "\"holder\" is a list of 1 to %d pieces, or a --holder string",
                     SWARF_SIM_MAX_HOLDER);
  json_array_foreach(h, i, p) {
    swarf_status s = get_piece(src, p, elem, &t->holder[i]);
    if (s != SWARF_OK) return s;
  }
  t->nholder = (int)json_array_size(h);
  return SWARF_OK;
}

/* The cutter: "T<n>=" + "cutter" (+ ",L<flutes>") through the --tool parser. */
static swarf_status get_cutter(const library_src *src, json_t *tool, int elem, int number,
                               swarf_sim_tool *t) {
  json_t *c = json_object_get(tool, "cutter");
  char spec[512];
  double flutes;
  swarf_error e;
  swarf_status s = get_length(src, tool, elem, "flutes", &flutes);
  if (s != SWARF_OK) return s;
  if (c == NULL || !json_is_string(c))
    return lib_error(src, elem, "cutter",
                     "each tool needs \"cutter\": a --tool spec without T<n>=, e.g. \"flat,D6\"");
  int n = snprintf(spec, sizeof spec, "T%d=%s", number, json_string_value(c));
  if (flutes > 0) n += snprintf(spec + n, sizeof spec - (size_t)n, ",L%.17g", flutes);
  if (n >= (int)sizeof spec) return lib_error(src, elem, "cutter", "\"cutter\" is too long");
  if (swarf_sim_parse_tool(spec, t, &e) != SWARF_OK)
    return lib_error(src, elem, "cutter", "\"cutter\": %s", e.message);
  return SWARF_OK;
}

static const char *const known_keys[] = {"number", "cutter", "flutes",  "stickout", "shank",
                                         "holder", "length", "comment", NULL};

static swarf_status check_keys(const library_src *src, json_t *tool, int elem) {
  const char *key;
  json_t *v;
  json_object_foreach(tool, key, v) {
    int known = 0;
    for (int i = 0; known_keys[i] != NULL; i++)
      known |= strcmp(key, known_keys[i]) == 0;
    if (!known)
      return lib_error(src, elem, key,
                       "unknown key \"%s\" (a tool has number, cutter, flutes, stickout, shank, "
                       "holder, length, comment)",
                       key);
  }
  return SWARF_OK;
}

/* One entry of "tools" into cfg. */
static swarf_status read_tool(const library_src *src, json_t *tool, int elem,
                              swarf_sim_config *cfg) {
  json_t *num = json_is_object(tool) ? json_object_get(tool, "number") : NULL;
  swarf_sim_tool t;
  double stickout, shank, length;
  swarf_status s;
  memset(&t, 0, sizeof t);
  if (!json_is_object(tool))
    return lib_error(src, elem, NULL, "each entry of \"tools\" is an object");
  if ((s = check_keys(src, tool, elem)) != SWARF_OK) return s;
  if (num == NULL || !json_is_integer(num) || json_integer_value(num) < 1 ||
      json_integer_value(num) > SWARF_SIM_MAX_TOOL_NUMBER)
    return lib_error(src, elem, "number", "each tool needs \"number\": 1 to %d",
                     SWARF_SIM_MAX_TOOL_NUMBER);
  int number = (int)json_integer_value(num);
  if ((s = get_cutter(src, tool, elem, number, &t)) != SWARF_OK) return s;
  if (t.stickout > 0 || t.shank > 0)
    return lib_error(src, elem, "cutter",
                     "give the stick-out and shank as \"stickout\" and \"shank\"");
  if ((s = get_length(src, tool, elem, "stickout", &stickout)) != SWARF_OK ||
      (s = get_length(src, tool, elem, "shank", &shank)) != SWARF_OK ||
      (s = get_length(src, tool, elem, "length", &length)) != SWARF_OK ||
      (s = get_holder(src, tool, elem, number, &t)) != SWARF_OK)
    return s;
  if (json_object_get(tool, "comment") != NULL && !json_is_string(json_object_get(tool, "comment")))
    return lib_error(src, elem, "comment", "\"comment\" must be a string");
  t.stickout = stickout;
  t.shank = shank;
  t.length = length;
  swarf_error e;
  if (swarf_sim_check_assembly(&t, "library", &e) != SWARF_OK)
    return lib_error(src, elem, NULL, "%s", e.message);
  swarf_sim_tool *dst = swarf_sim_tool_slot(cfg, number, 0);
  if (dst != NULL && json_object_get(tool, "length") == NULL) t.length = dst->length;
  if (dst == NULL && (dst = swarf_sim_tool_slot(cfg, number, 1)) == NULL)
    return lib_error(src, elem, NULL, "too many tools (at most %d)", SWARF_SIM_MAX_TOOLS);
  *dst = t;
  return SWARF_OK;
}

/* Each tool number once in the library. */
static swarf_status check_numbers(const library_src *src, json_t *tools) {
  size_t i, j;
  json_t *a, *b;
  json_array_foreach(tools, i, a) {
    for (j = 0; j < i; j++) {
      b = json_array_get(tools, j);
      json_t *na = json_object_get(a, "number"), *nb = json_object_get(b, "number");
      if (json_is_integer(na) && json_is_integer(nb) &&
          json_integer_value(na) == json_integer_value(nb))
        return lib_error(src, (int)i, "number", "T%lld is already in the library (line %ld)",
                         (long long)json_integer_value(na),
                         json_place(src->text, src->len, (int)j, "number"));
    }
  }
  return SWARF_OK;
}

static char *read_all(const char *path, size_t *len, swarf_error *err) {
  swarf_error why;
  FILE *f = swarf_file_open_input(path, "tool library", LIBRARY_FILE_MAX, &why);
  char *buf = NULL;
  size_t cap = 0, n = 0, got;
  if (f == NULL) { /* missing, not a regular file (a device, a FIFO) or too large */
    swarf_error_at(err, path, 0, 0, "--tool-library");
    swarf_error_set(err, why.status, "cannot open the tool library: %.400s", why.message);
    return NULL;
  }
  do {
    if (n + 4096 > cap) {
      char *p = realloc(buf, cap = 2 * cap + 8192);
      if (p == NULL) {
        free(buf);
        fclose(f);
        swarf_error_set(err, SWARF_ERR_MEMORY, "out of memory reading %s", path);
        return NULL;
      }
      buf = p;
    }
    got = fread(buf + n, 1, cap - n - 1, f);
    n += got;
  } while (got > 0);
  fclose(f);
  buf[n] = '\0';
  *len = n;
  return buf;
}

swarf_status swarf_sim_config_load_tool_library(swarf_sim_config *cfg, const char *path,
                                                swarf_error *err) {
  size_t len = 0;
  json_error_t je;
  swarf_status s = SWARF_OK;
  if (cfg == NULL || path == NULL) return swarf_error_set(err, SWARF_ERR_ARG, "no config or path");
  char *text = read_all(path, &len, err);
  if (text == NULL) return err != NULL ? err->status : SWARF_ERR_OPEN;
  library_src src = {path, text, len, err};
  json_t *root = json_loadb(text, len, JSON_REJECT_DUPLICATES, &je);
  if (root == NULL) {
    swarf_error_at(err, path, je.line > 0 ? je.line : 1, je.column > 0 ? je.column : 0, "");
    s = swarf_error_set(err, SWARF_ERR_FORMAT, "not valid JSON: %s", je.text);
  } else {
    json_t *tools = json_object_get(root, "tools");
    const char *key;
    json_t *v;
    if (!json_is_object(root) || !json_is_array(tools)) {
      s = lib_error(&src, -1, NULL, "a tool library is an object {\"tools\": [ ... ]}");
    } else {
      json_object_foreach(root, key, v) {
        if (s == SWARF_OK && strcmp(key, "tools") != 0 && strcmp(key, "comment") != 0)
          s = lib_error(&src, -1, NULL, "unknown key \"%s\" at the top (tools, comment)", key);
      }
    }
    if (s == SWARF_OK) s = check_numbers(&src, tools);
    for (size_t i = 0; s == SWARF_OK && i < json_array_size(tools); i++)
      s = read_tool(&src, json_array_get(tools, i), (int)i, cfg);
    json_decref(root);
  }
  free(text);
  return s;
}
