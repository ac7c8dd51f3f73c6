/* SPDX-License-Identifier: MPL-2.0 */
/* assembly.c -- tool assemblies: the tool table's slots, the S and N fields
 * of --tool, --holder and --fixture specs, and the non-cutting bodies.
 *
 *   --tool T1=flat,D6,L10,S25,N6      S stick-out (tip to holder face), N shank
 *   --holder T1=20x40,20-30x10        pieces stacked upward from the holder face
 *   --fixture box:X0,Y0,Z0,X1,Y1,Z1   a body no part of the tool may enter
 *
 * All mm. Numbers must be finite decimals (no hex, inf or nan).
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assembly.h"

swarf_sim_tool *swarf_sim_tool_slot(swarf_sim_config *cfg, int number, int create) {
  for (int i = 0; i < cfg->ntools; i++)
    if (cfg->tools[i].number == number) return &cfg->tools[i];
  if (!create || cfg->ntools == SWARF_SIM_MAX_TOOLS) return NULL;
  swarf_sim_tool *t = &cfg->tools[cfg->ntools++];
  memset(t, 0, sizeof *t);
  t->number = number;
  return t;
}

void swarf_sim_tool_drop(swarf_sim_config *cfg, int number) {
  for (int i = 0; i < cfg->ntools; i++)
    if (cfg->tools[i].number == number) {
      memmove(&cfg->tools[i], &cfg->tools[i + 1],
              sizeof cfg->tools[0] * (size_t)(cfg->ntools - i - 1));
      cfg->ntools--;
      return;
    }
}

/* A finite decimal number at *s (advanced past it); -1 if there is none. */
static int read_num(const char **s, double *v) {
  const char *p = *s;
  char *end;
  if (*p == '+' || *p == '-') p++;
  if (!isdigit((unsigned char)*p) && *p != '.') return -1;
  if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X')) return -1;
  errno = 0;
  *v = strtod(*s, &end);
  if (end == *s || errno != 0 || !isfinite(*v)) return -1;
  *s = end;
  return 0;
}

/* "T<n>=" at the start of spec: the number, and the text after '='. */
static int read_tool_number(const char *spec, int *number, const char **rest) {
  char *end;
  long n;
  if (spec == NULL || (spec[0] != 'T' && spec[0] != 't') || !isdigit((unsigned char)spec[1]))
    return -1;
  errno = 0;
  n = strtol(spec + 1, &end, 10);
  if (*end != '=' || errno != 0 || n < 1 || n > SWARF_SIM_MAX_TOOL_NUMBER) return -1;
  *number = (int)n;
  *rest = end + 1;
  return 0;
}

static swarf_status spec_error(swarf_error *err, const char *flag, const char *fmt,
                               const char *spec, const char *usage) {
  char what[400];
  snprintf(what, sizeof what, fmt, spec);
  swarf_error_at(err, NULL, 0, 0, flag);
  return swarf_error_set(err, SWARF_ERR_ARG, "%s: %s; %s", flag, what, usage);
}

/* ---- --tool's S and N ----------------------------------------------------- */

swarf_status swarf_sim_split_assembly(const char *spec, char *cutter_spec, size_t len,
                                      double *stickout, double *shank, swarf_error *err) {
  static const char usage[] = "S<stick-out mm> and N<shank diameter mm> take one number each";
  const char *field = spec != NULL ? strchr(spec, ',') : NULL;
  size_t out = 0;
  *stickout = *shank = 0;
  if (spec == NULL || strlen(spec) >= len)
    return spec_error(err, "--tool", "\"%.200s\" is too long", spec ? spec : "", usage);
  out = (size_t)(field != NULL ? field - spec : (ptrdiff_t)strlen(spec));
  memcpy(cutter_spec, spec, out);
  while (field != NULL) {
    const char *next = strchr(field + 1, ',');
    size_t n = next != NULL ? (size_t)(next - field) : strlen(field);
    const char key = (char)toupper((unsigned char)field[1]);
    if (key == 'S' || key == 'N') {
      const char *p = field + 2;
      double v, *dst = key == 'S' ? stickout : shank;
      if (read_num(&p, &v) != 0 || p != field + n || !(v > 0))
        return spec_error(err, "--tool", "bad S or N field in \"%s\"", spec, usage);
      if (*dst != 0) return spec_error(err, "--tool", "S or N given twice in \"%s\"", spec, usage);
      *dst = v;
    } else {
      memcpy(cutter_spec + out, field, n);
      out += n;
    }
    field = next;
  }
  cutter_spec[out] = '\0';
  return SWARF_OK;
}

swarf_status swarf_sim_check_assembly(const swarf_sim_tool *t, const char *what, swarf_error *err) {
  if (!(t->stickout >= 0) || !isfinite(t->stickout) || !(t->shank >= 0) || !isfinite(t->shank))
    return swarf_error_set(err, SWARF_ERR_TOOL, "%s: T%d: stick-out and shank must be >= 0 mm",
                           what, t->number);
  if (t->nholder > 0 && t->stickout == 0)
    return swarf_error_set(err, SWARF_ERR_TOOL,
                           "%s: T%d has a holder but no stick-out: give S<mm> (tip to holder "
                           "face) in its --tool or library entry",
                           what, t->number);
  for (int i = 0; i < t->nholder; i++) {
    const swarf_sim_holder_part *h = &t->holder[i];
    if (!(h->d0 > 0) || !(h->d1 > 0) || !(h->height > 0) || !isfinite(h->d0 + h->d1 + h->height))
      return swarf_error_set(err, SWARF_ERR_TOOL,
                             "%s: T%d: holder piece %d needs diameters and height > 0 mm", what,
                             t->number, i + 1);
  }
  return SWARF_OK;
}

swarf_status swarf_sim_check_tool(const swarf_sim_tool *t, swarf_error *err) {
  if (t == NULL) return swarf_error_set(err, SWARF_ERR_ARG, "no tool");
  return swarf_sim_check_assembly(t, "assembly", err);
}

/* ---- --holder ------------------------------------------------------------- */

/* One piece "<D>x<H>" or "<D1>-<D2>x<H>" at *s. */
static int read_piece(const char **s, swarf_sim_holder_part *h) {
  if (read_num(s, &h->d0) != 0) return -1;
  h->d1 = h->d0;
  if (**s == '-') {
    (*s)++;
    if (read_num(s, &h->d1) != 0) return -1;
  }
  if (**s != 'x' && **s != 'X') return -1;
  (*s)++;
  if (read_num(s, &h->height) != 0) return -1;
  return h->d0 > 0 && h->d1 > 0 && h->height > 0 ? 0 : -1;
}

swarf_status swarf_sim_parse_holder(const char *spec, swarf_sim_tool *out, swarf_error *err) {
  static const char usage[] =
      "write --holder T<n>=<D>x<H>[,<D1>-<D2>x<H>...] (mm: cylinders D x H and cones from D1 "
      "at the bottom to D2 at the top, stacked upward from the holder face)";
  const char *s;
  int number, n = 0;
  if (out == NULL)
    return swarf_error_set(err, SWARF_ERR_ARG, "swarf_sim_parse_holder: out is NULL");
  if (read_tool_number(spec, &number, &s) != 0)
    return spec_error(err, "--holder", "cannot read the tool in \"%s\"", spec ? spec : "", usage);
  for (;;) {
    if (n == SWARF_SIM_MAX_HOLDER)
      return spec_error(err, "--holder", "too many pieces in \"%s\" (at most 8)", spec, usage);
    if (read_piece(&s, &out->holder[n]) != 0)
      return spec_error(err, "--holder", "bad piece in \"%s\" (diameters and heights > 0)", spec,
                        usage);
    n++;
    if (*s == '\0') break;
    if (*s++ != ',') return spec_error(err, "--holder", "unexpected text in \"%s\"", spec, usage);
  }
  out->number = number;
  out->nholder = n;
  return SWARF_OK;
}

/* ---- --fixture ------------------------------------------------------------ */

swarf_status swarf_sim_parse_fixture(const char *spec, swarf_sim_fixture *out, swarf_error *err) {
  static const char usage[] =
      "write --fixture box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (mm) or --fixture stl:FILE";
  const char *s = spec;
  double v[6];
  if (out == NULL)
    return swarf_error_set(err, SWARF_ERR_ARG, "swarf_sim_parse_fixture: out is NULL");
  if (spec != NULL && strncmp(spec, "stl:", 4) == 0) {
    if (spec[4] == '\0') return spec_error(err, "--fixture", "no file in \"%s\"", spec, usage);
    memset(out, 0, sizeof *out);
    out->stl = spec + 4;
    return SWARF_OK;
  }
  if (spec == NULL || strncmp(spec, "box:", 4) != 0)
    return spec_error(err, "--fixture", "unknown fixture \"%s\"", spec ? spec : "", usage);
  s += 4;
  for (int i = 0; i < 6; i++) {
    if (read_num(&s, &v[i]) != 0 || *s != (i < 5 ? ',' : '\0'))
      return spec_error(err, "--fixture", "bad number in \"%s\"", spec, usage);
    s++;
  }
  for (int k = 0; k < 3; k++) {
    if (!(v[k] < v[k + 3]))
      return spec_error(err, "--fixture", "a minimum is not below its maximum in \"%s\"", spec,
                        usage);
    out->lo[k] = v[k];
    out->hi[k] = v[k + 3];
  }
  out->stl = NULL;
  return SWARF_OK;
}

/* ---- Putting descriptions into the table ---------------------------------- */

swarf_status swarf_sim_config_put_tool(swarf_sim_config *cfg, const swarf_sim_tool *t,
                                       swarf_error *err) {
  swarf_sim_tool *dst = swarf_sim_tool_slot(cfg, t->number, 0);
  if (dst == NULL) {
    if ((dst = swarf_sim_tool_slot(cfg, t->number, 1)) == NULL)
      return swarf_error_set(err, SWARF_ERR_ARG, "--tool: too many tools (at most %d)",
                             SWARF_SIM_MAX_TOOLS);
    *dst = *t;
    return SWARF_OK;
  }
  dst->cutter = t->cutter;
  if (t->stickout > 0) dst->stickout = t->stickout;
  if (t->shank > 0) dst->shank = t->shank;
  if (t->length != 0) dst->length = t->length;
  if (t->nholder > 0) {
    dst->nholder = t->nholder;
    memcpy(dst->holder, t->holder, sizeof t->holder);
  }
  return SWARF_OK;
}

swarf_status swarf_sim_config_put_holder(swarf_sim_config *cfg, const swarf_sim_tool *t,
                                         swarf_error *err) {
  swarf_sim_tool *dst = swarf_sim_tool_slot(cfg, t->number, 0);
  if (dst == NULL) {
    swarf_error_at(err, NULL, 0, 0, "--holder");
    return swarf_error_set(err, SWARF_ERR_ARG,
                           "--holder: T%d is not a tool; describe it with --tool T%d=... (or in "
                           "a tool table or library)",
                           t->number, t->number);
  }
  dst->nholder = t->nholder;
  memcpy(dst->holder, t->holder, sizeof t->holder);
  return SWARF_OK;
}

/* ---- The non-cutting bodies ----------------------------------------------- */

int swarf_sim_tool_parts(const swarf_sim_tool *t, swarf_sim_part parts[SWARF_SIM_MAX_PARTS]) {
  int n = 0;
  double z = t->stickout;
  if (!(t->stickout > 0)) return 0;
  if (t->stickout > t->cutter.length) {
    double d = t->shank > 0 ? t->shank : t->cutter.diameter;
    parts[n++] = (swarf_sim_part){SWARF_ALARM_SHANK, t->cutter.length, t->stickout, d, d};
  }
  for (int i = 0; i < t->nholder; i++) {
    const swarf_sim_holder_part *h = &t->holder[i];
    parts[n++] = (swarf_sim_part){SWARF_ALARM_HOLDER, z, z + h->height, h->d0, h->d1};
    z += h->height;
  }
  return n;
}
