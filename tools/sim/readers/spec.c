/* SPDX-License-Identifier: MPL-2.0 */
/* spec.c -- parsing of the command line's stock and tool specifications.
 *
 *   box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX        (mm)
 *   cylinder:AXIS,RADIUS,START,END           (AXIS x, y or z through the origin; mm)
 *   T<n>=<family>,<fields>   (mm, angles in degrees; engine.h, swarf_cutter_make)
 *
 * Every number must be finite and complete; messages say what to write.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assembly.h"

/* Read one finite number at *s; advances *s. Returns 0 or -1. */
static int read_number(const char **s, double *out) {
  char *end;
  errno = 0;
  *out = strtod(*s, &end);
  if (end == *s || errno == ERANGE || !isfinite(*out)) return -1;
  *s = end;
  return 0;
}

static swarf_status parse_box(const char *spec, double lo[3], double hi[3], swarf_error *err) {
  static const char usage[] = "write --stock box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (mm)";
  const char *s = spec;
  double v[6];
  if (spec == NULL || strncmp(s, "box:", 4) != 0) {
    return swarf_error_set(err, SWARF_ERR_ARG,
                           "--stock: unknown stock \"%s\"; %s, or cylinder:AXIS,RADIUS,START,END",
                           spec ? spec : "", usage);
  }
  s += 4;
  for (int i = 0; i < 6; i++) {
    if (read_number(&s, &v[i]) != 0 || (*s != (i < 5 ? ',' : '\0'))) {
      return swarf_error_set(err, SWARF_ERR_ARG, "--stock: bad number %d in \"%s\"; %s", i + 1,
                             spec, usage);
    }
    s++;
  }
  for (int k = 0; k < 3; k++) {
    if (!(v[k] < v[k + 3])) {
      return swarf_error_set(err, SWARF_ERR_ARG,
                             "--stock: %c min %g is not below %c max %g in \"%s\"", "XYZ"[k], v[k],
                             "XYZ"[k], v[k + 3], spec);
    }
    lo[k] = v[k];
    hi[k] = v[k + 3];
  }
  return 0;
}

static swarf_status parse_cylinder(const char *spec, swarf_sim_stock_spec *out, swarf_error *err) {
  static const char usage[] = "write --stock cylinder:AXIS,RADIUS,START,END (AXIS x, y or z; mm)";
  const char *s = spec + 9, *axes = "xyz",
             *a = *s ? strchr(axes, tolower((unsigned char)*s)) : NULL;
  double v[3];
  if (a == NULL || s[1] != ',') {
    return swarf_error_set(err, SWARF_ERR_ARG, "--stock: bad axis in \"%s\"; %s", spec, usage);
  }
  s += 2;
  for (int i = 0; i < 3; i++) {
    if (read_number(&s, &v[i]) != 0 || (*s != (i < 2 ? ',' : '\0'))) {
      return swarf_error_set(err, SWARF_ERR_ARG, "--stock: bad number %d in \"%s\"; %s", i + 1,
                             spec, usage);
    }
    s++;
  }
  if (!(v[0] > 0) || !(v[1] < v[2])) {
    return swarf_error_set(err, SWARF_ERR_ARG,
                           "--stock: need RADIUS > 0 and START < END in \"%s\"; %s", spec, usage);
  }
  out->kind = SWARF_SIM_STOCK_CYLINDER;
  out->axis = (int)(a - axes);
  out->radius = v[0];
  for (int k = 0; k < 3; k++)
    out->lo[k] = -v[0], out->hi[k] = v[0];
  out->lo[out->axis] = v[1];
  out->hi[out->axis] = v[2];
  return SWARF_OK;
}

swarf_status swarf_sim_parse_stock(const char *spec, swarf_sim_stock_spec *out, swarf_error *err) {
  if (out == NULL) return swarf_error_set(err, SWARF_ERR_ARG, "swarf_sim_parse_stock: out is NULL");
  swarf_error_at(err, NULL, 0, 0, "--stock");
  if (spec != NULL && strncmp(spec, "cylinder:", 9) == 0) return parse_cylinder(spec, out, err);
  memset(out, 0, sizeof *out);
  out->kind = SWARF_SIM_STOCK_BOX;
  return parse_box(spec, out->lo, out->hi, err);
}

/* The families and the letters each takes (engine.h, swarf_cutter_spec). */
static const struct {
  const char *name;
  swarf_cutter_shape shape;
  const char *letters;
} families[] = {{"flat", SWARF_CUTTER_FLAT, "DRL"},
                {"ball", SWARF_CUTTER_BALL, "DRL"},
                {"bull", SWARF_CUTTER_BULL, "DRL"},
                {"vee", SWARF_CUTTER_VEE, "DAL"},
                {"drill", SWARF_CUTTER_DRILL, "DAL"},
                {"spot", SWARF_CUTTER_SPOT, "DAL"},
                {"chamfer", SWARF_CUTTER_CHAMFER, "DATL"},
                {"taper", SWARF_CUTTER_TAPER, "DARL"},
                {"apt", SWARF_CUTTER_APT, "DREFABH"},
                {"lollipop", SWARF_CUTTER_LOLLIPOP, "DKL"},
                {"dovetail", SWARF_CUTTER_DOVETAIL, "DAHKL"},
                {"tslot", SWARF_CUTTER_TSLOT, "DHKL"},
                {"qss", SWARF_CUTTER_QSS, ""}};

static int parse_family(const char **s) {
  for (size_t i = 0; i < sizeof families / sizeof families[0]; i++) {
    size_t n = strlen(families[i].name);
    if (strncmp(*s, families[i].name, n) == 0 && ((*s)[n] == ',' || (*s)[n] == '\0')) {
      *s += n;
      return (int)i;
    }
  }
  return -1;
}

static double *field(swarf_cutter_spec *sp, char letter) {
  switch (letter) {
  case 'D':
    return &sp->d;
  case 'R':
    return &sp->r;
  case 'L':
    return &sp->length;
  case 'A':
    return &sp->angle;
  case 'T':
    return &sp->tip;
  case 'E':
    return &sp->e;
  case 'F':
    return &sp->f;
  case 'B':
    return &sp->beta;
  case 'H':
    return &sp->h;
  case 'K':
    return &sp->neck;
  default:
    return NULL;
  }
}

/* ",X<number>" fields with the family's letters (each at most once). */
static int parse_fields(const char *s, int fam, swarf_cutter_spec *sp, char *bad, size_t badlen) {
  const char *letters = families[fam].letters;
  char seen[16] = "";
  while (*s == ',') {
    const char *key = ++s;
    char k = (char)toupper((unsigned char)*key);
    double v;
    if (*key == '\0' || strchr(letters, k) == NULL || k == '\0') {
      snprintf(bad, badlen, "unknown field \"%.20s\" for %s (use %s)", key, families[fam].name,
               letters);
      return -1;
    }
    if (strchr(seen, k) != NULL) {
      snprintf(bad, badlen, "%c given twice", k);
      return -1;
    }
    strncat(seen, &k, 1);
    s++;
    if (read_number(&s, &v) != 0 || (*s != ',' && *s != '\0')) {
      snprintf(bad, badlen, "bad value for %c (a number)", k);
      return -1;
    }
    *field(sp, k) = v;
  }
  if (*s != '\0') {
    snprintf(bad, badlen, "unexpected \"%.20s\"", s);
    return -1;
  }
  return 0;
}

/* qss,a,b,e,f: four numbers. */
static int parse_qss(const char *s, swarf_cutter_spec *sp, char *bad, size_t badlen) {
  double *dst[4] = {&sp->qa, &sp->qb, &sp->qe, &sp->qf};
  for (int i = 0; i < 4; i++) {
    if (*s++ != ',' || read_number(&s, dst[i]) != 0 || (*s != ',' && *s != '\0') ||
        (i == 3 && *s != '\0')) {
      snprintf(bad, badlen,
               "qss takes four numbers a,b,e,f (h = a(x^2+y^2) + b z^2 + e z + f, mm)");
      return -1;
    }
  }
  return 0;
}

#define TOOL_USAGE                                                                                 \
  "write --tool T<n>=<family>,<fields>: flat|ball|bull,D,R,L; vee|drill|spot,D,A,L; "              \
  "chamfer,D,A,T,L; taper,D,A,R,L; apt,D,R,E,F,A,B,H; lollipop,D,K,L; dovetail,D,A,H,K,L; "        \
  "tslot,D,H,K,L; qss,a,b,e,f (swarf simulate --help)"

swarf_status swarf_sim_parse_tool(const char *spec, swarf_sim_tool *out, swarf_error *err) {
  if (out == NULL) return swarf_error_set(err, SWARF_ERR_ARG, "swarf_sim_parse_tool: out is NULL");
  char cutter_spec[512];
  double stickout, shank;
  swarf_status st =
      swarf_sim_split_assembly(spec, cutter_spec, sizeof cutter_spec, &stickout, &shank, err);
  if (st != SWARF_OK) return st;
  memset(out, 0, sizeof *out);
  out->stickout = stickout;
  out->shank = shank;
  const char *given = spec;
  spec = cutter_spec;
  const char *s = spec;
  char bad[160];
  long n;
  char *end;
  int fam;
  swarf_cutter_spec sp;
  swarf_error sub;
  swarf_error_at(err, NULL, 0, 0, "--tool");
  if (spec == NULL || (*s != 'T' && *s != 't')) goto usage_err;
  errno = 0;
  n = strtol(s + 1, &end, 10);
  if (end == s + 1 || *end != '=' || n < 1 || n > 99999 || errno) goto usage_err;
  s = end + 1;
  if ((fam = parse_family(&s)) < 0) goto usage_err;
  swarf_cutter_spec_init(&sp);
  sp.shape = families[fam].shape;
  if ((sp.shape == SWARF_CUTTER_QSS ? parse_qss(s, &sp, bad, sizeof bad)
                                    : parse_fields(s, fam, &sp, bad, sizeof bad)) != 0)
    return swarf_error_set(err, SWARF_ERR_TOOL, "--tool: %s in \"%s\"; %s", bad, given, TOOL_USAGE);
  swarf_error_init(&sub);
  if (swarf_cutter_make(&out->cutter, &sp, &sub) != SWARF_OK)
    return swarf_error_set(err, SWARF_ERR_TOOL, "--tool: %s in \"%s\"", sub.message, given);
  out->number = (int)n;
  out->length = 0.0;
  return SWARF_OK;
usage_err:
  return swarf_error_set(err, SWARF_ERR_TOOL, "--tool: cannot read \"%s\"; %s", given, TOOL_USAGE);
}
