/* machine.c -- machine kinematics: the --machine description (the rigid
 * motion of the cutter for a canonical move is move_motion.c's).
 *
 * Table machines only (the workpiece turns, the spindle keeps its
 * orientation): xyza (a rotary table about X, identity kinematics: program
 * coordinates are joint positions), xyzac-trt and xyzbc-trt (a tilting table,
 * A about X or B about Y, carrying a rotary table C about Z), in
 * tool-centre-point mode (program X Y Z = tip in the workpiece frame) or in
 * joint mode. A table axis turns the workpiece by +angle about its axis
 * (right-hand rule). Values only; the caller owns every struct.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "toolpath_private.h"

static const struct {
  const char *name;
  swarf_machine_kind kind;
  int npivot; /* numbers after pivot= */
} machines[] = {{"xyz", SWARF_MACHINE_XYZ, 0},
                {"xyza", SWARF_MACHINE_XYZA, 2},
                {"xyzac-trt", SWARF_MACHINE_XYZAC_TRT, 3},
                {"xyzbc-trt", SWARF_MACHINE_XYZBC_TRT, 3}};

static const char usage[] =
    "write --machine xyz, xyza[,pivot=Y,Z] or xyzac-trt|xyzbc-trt[,mode=tcp|joint][,pivot=X,Y,Z]";

/* Read npivot comma-separated finite numbers at *s into the pivot. */
static int read_pivot(const char **s, int npivot, double pivot[3]) {
  for (int i = 0; i < npivot; i++) {
    char *end;
    if (i > 0 && *(*s)++ != ',') return -1;
    errno = 0;
    pivot[npivot == 2 ? i + 1 : i] = strtod(*s, &end);
    if (end == *s || errno || !isfinite(pivot[npivot == 2 ? i + 1 : i])) return -1;
    *s = end;
  }
  return 0;
}

/* --machine is wrong: err gets the reason. */
static swarf_status refuse(swarf_error *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static swarf_status refuse(swarf_error *err, const char *fmt, ...) {
  va_list ap;
  if (err == NULL) return SWARF_ERR_ARG;
  swarf_error_init(err);
  swarf_error_at(err, NULL, 0, 0, "--machine");
  err->status = SWARF_ERR_ARG;
  va_start(ap, fmt);
  vsnprintf(err->message, sizeof err->message, fmt, ap);
  va_end(ap);
  return SWARF_ERR_ARG;
}

/* One ",key=value" field at *s (after the comma). */
static swarf_status parse_key(swarf_machine *m, int npivot, const char **s, const char *spec,
                              swarf_error *err) {
  if (npivot > 0 && strncmp(*s, "pivot=", 6) == 0) {
    *s += 6;
    if (read_pivot(s, npivot, m->pivot) == 0) return SWARF_OK;
    return refuse(err, "--machine: pivot needs %d numbers in \"%s\"; %s", npivot, spec, usage);
  }
  if (npivot == 3 && strncmp(*s, "mode=", 5) == 0) {
    const char *v = *s + 5;
    size_t n = strcspn(v, ",");
    if ((n == 3 && !strncmp(v, "tcp", 3)) || (n == 5 && !strncmp(v, "joint", 5))) {
      m->tcp = n == 3;
      *s = v + n;
      return SWARF_OK;
    }
  }
  return refuse(err, "--machine: unknown field \"%.*s\" in \"%s\"; %s", (int)strcspn(*s, ","),
                *s, spec, usage);
}

swarf_status swarf_machine_parse(swarf_machine *m, const char *spec, swarf_error *err) {
  const char *s = spec;
  size_t n;
  int npivot = -1;
  if (m == NULL || spec == NULL) return refuse(err, "--machine: no machine given; %s", usage);
  memset(m, 0, sizeof *m);
  m->tcp = 1;
  n = strcspn(s, ",");
  for (size_t i = 0; i < sizeof machines / sizeof machines[0]; i++)
    if (strlen(machines[i].name) == n && strncmp(s, machines[i].name, n) == 0) {
      m->kind = machines[i].kind;
      npivot = machines[i].npivot;
    }
  if (npivot < 0) return refuse(err, "--machine: unknown machine \"%.*s\"; %s", (int)n, s, usage);
  if (m->kind == SWARF_MACHINE_XYZA) m->tcp = 0;
  for (s += n; *s == ',';) {
    s++;
    if (parse_key(m, npivot, &s, spec, err) != SWARF_OK) return SWARF_ERR_ARG;
  }
  if (*s != '\0') return refuse(err, "--machine: unexpected \"%s\" in \"%s\"; %s", s, spec, usage);
  return SWARF_OK;
}
