/* spec.c -- parsing of the command line's stock and tool specifications.
 *
 *   box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX        (mm)
 *   cylinder:AXIS,RADIUS,START,END           (AXIS x, y or z through the origin; mm)
 *   T<n>=<ball|flat|bull>,D<d>[,R<r>][,L<l>]  (mm)
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
  swarf_error_at(err, NULL, 0, 0, "--stock");
  if (spec != NULL && strncmp(spec, "cylinder:", 9) == 0) return parse_cylinder(spec, out, err);
  memset(out, 0, sizeof *out);
  out->kind = SWARF_SIM_STOCK_BOX;
  return parse_box(spec, out->lo, out->hi, err);
}

static int parse_shape(const char **s, swarf_cutter_shape *shape) {
  static const struct {
    const char *name;
    swarf_cutter_shape shape;
  } shapes[] = {
      {"ball", SWARF_CUTTER_BALL}, {"flat", SWARF_CUTTER_FLAT}, {"bull", SWARF_CUTTER_BULL}};
  for (size_t i = 0; i < sizeof shapes / sizeof shapes[0]; i++) {
    size_t n = strlen(shapes[i].name);
    if (strncmp(*s, shapes[i].name, n) == 0 && ((*s)[n] == ',' || (*s)[n] == '\0')) {
      *shape = shapes[i].shape;
      *s += n;
      return 0;
    }
  }
  return -1;
}

/* Read ",D<d>", ",R<r>", ",L<l>" fields into dims[0..2]. */
static int parse_dims(const char *s, double dims[3], char *bad, size_t badlen) {
  while (*s == ',') {
    const char *key = ++s;
    const char *p = strchr("DRL", toupper((unsigned char)*key));
    double v;
    if (*key == '\0' || p == NULL) {
      snprintf(bad, badlen, "unknown field \"%.20s\" (use D, R, L)", key);
      return -1;
    }
    s++;
    if (read_number(&s, &v) != 0 || (*s != ',' && *s != '\0') || v < 0) {
      snprintf(bad, badlen, "bad value for %c", toupper((unsigned char)*key));
      return -1;
    }
    dims[p - "DRL"] = v;
  }
  if (*s != '\0') {
    snprintf(bad, badlen, "unexpected \"%.20s\"", s);
    return -1;
  }
  return 0;
}

swarf_status swarf_sim_parse_tool(const char *spec, swarf_sim_tool *out, swarf_error *err) {
  static const char usage[] =
      "write --tool T<n>=<ball|flat|bull>,D<diameter>[,R<corner>][,L<length>][,S<stick-out>]"
      "[,N<shank diameter>]";
  char cutter_spec[512];
  double stickout, shank;
  swarf_status st = swarf_sim_split_assembly(spec, cutter_spec, sizeof cutter_spec, &stickout,
                                             &shank, err);
  if (st != SWARF_OK) return st;
  memset(out, 0, sizeof *out);
  out->stickout = stickout;
  out->shank = shank;
  const char *given = spec;
  spec = cutter_spec;
  const char *s = spec, *why = NULL;
  double dims[3] = {0, 0, 0};
  char bad[96];
  long n;
  char *end;
  swarf_cutter_shape shape;
  swarf_error_at(err, NULL, 0, 0, "--tool");
  if (spec == NULL || (*s != 'T' && *s != 't')) goto usage_err;
  errno = 0;
  n = strtol(s + 1, &end, 10);
  if (end == s + 1 || *end != '=' || n < 1 || n > 99999 || errno) goto usage_err;
  s = end + 1;
  if (parse_shape(&s, &shape) != 0) goto usage_err;
  if (parse_dims(s, dims, bad, sizeof bad) != 0) {
    return swarf_error_set(err, SWARF_ERR_TOOL, "--tool: %s in \"%s\"; %s", bad, given, usage);
  }
  if (swarf_cutter_init(&out->cutter, shape, dims[0], dims[1], dims[2], &why) != 0) {
    return swarf_error_set(err, SWARF_ERR_TOOL, "--tool: %s in \"%s\"",
                           why ? why : "impossible cutter", given);
  }
  out->number = (int)n;
  out->length = 0.0;
  return SWARF_OK;
usage_err:
  return swarf_error_set(err, SWARF_ERR_TOOL, "--tool: cannot read \"%s\"; %s", given, usage);
}
