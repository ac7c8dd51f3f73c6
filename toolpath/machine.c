/* SPDX-License-Identifier: MPL-2.0 */
/* machine.c -- machine kinematics: the --machine description (the rigid
 * motion of the cutter for a canonical move is move_motion.c's).
 *
 * Table machines (the workpiece turns, the spindle keeps its orientation):
 * xyza (a rotary table about X, identity kinematics: program coordinates are
 * joint positions), xyzac-trt and xyzbc-trt (a tilting table, A about X or B
 * about Y, carrying a rotary table C about Z), xyzab-tdr (a cradle tilting
 * about Y (B) carrying a rotary table about X (A)). Head machines (the
 * spindle tilts): xyzbc-hh (C about Z carrying B about Y, both in the head)
 * and xyzbc-ht (B about Y in the head, C about Z in the table). Every 5-axis
 * machine runs in tool-centre-point mode (program X Y Z = tip in the
 * workpiece frame) or in joint mode. toolpath.h gives each one's directions
 * (LinuxCNC's kinematics modules'). Values only; the caller owns every struct.
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
  int npivot; /* numbers after pivot= (0: no pivot key) */
  int first;  /* the coordinate the first of them sets: 0 X, 1 Y */
  int head;   /* 1: head=L and, in joint mode, needs it */
} machines[] = {{"xyz", SWARF_MACHINE_XYZ, 0, 0, 0},
                {"xyza", SWARF_MACHINE_XYZA, 2, 1, 0},
                {"xyzac-trt", SWARF_MACHINE_XYZAC_TRT, 3, 0, 0},
                {"xyzbc-trt", SWARF_MACHINE_XYZBC_TRT, 3, 0, 0},
                {"xyzab-tdr", SWARF_MACHINE_XYZAB_TDR, 3, 0, 0},
                {"xyzbc-hh", SWARF_MACHINE_XYZBC_HH, 0, 0, 1},
                {"xyzbc-ht", SWARF_MACHINE_XYZBC_HT, 2, 0, 1}};

static const char usage[] =
    "write --machine xyz, xyza[,pivot=Y,Z], xyzac-trt|xyzbc-trt|xyzab-tdr[,mode=tcp|joint]"
    "[,pivot=X,Y,Z], xyzbc-hh[,mode=tcp|joint][,head=L] or "
    "xyzbc-ht[,mode=tcp|joint][,pivot=X,Y][,head=L]";

/* Read n comma-separated finite numbers at *s into v[0..n-1]. */
static int read_numbers(const char **s, int n, double *v) {
  for (int i = 0; i < n; i++) {
    char *end;
    if (i > 0 && *(*s)++ != ',') return -1;
    errno = 0;
    v[i] = strtod(*s, &end);
    if (end == *s || errno || !isfinite(v[i])) return -1;
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

/* One ",key=value" field at *s (after the comma) for machines[i]. */
static swarf_status parse_key(swarf_machine *m, size_t i, const char **s, const char *spec,
                              swarf_error *err) {
  int npivot = machines[i].npivot;
  if (npivot > 0 && strncmp(*s, "pivot=", 6) == 0) {
    *s += 6;
    if (read_numbers(s, npivot, m->pivot + machines[i].first) == 0) return SWARF_OK;
    return refuse(err, "--machine: pivot needs %d numbers in \"%s\"; %s", npivot, spec, usage);
  }
  if (machines[i].head && strncmp(*s, "head=", 5) == 0) {
    *s += 5;
    if (read_numbers(s, 1, &m->head) == 0) return SWARF_OK;
    return refuse(err, "--machine: head needs one number (mm) in \"%s\"; %s", spec, usage);
  }
  if (m->kind != SWARF_MACHINE_XYZ && m->kind != SWARF_MACHINE_XYZA &&
      strncmp(*s, "mode=", 5) == 0) {
    const char *v = *s + 5;
    size_t n = strcspn(v, ",");
    if ((n == 3 && !strncmp(v, "tcp", 3)) || (n == 5 && !strncmp(v, "joint", 5))) {
      m->tcp = n == 3;
      *s = v + n;
      return SWARF_OK;
    }
  }
  return refuse(err, "--machine: unknown field \"%.*s\" in \"%s\"; %s", (int)strcspn(*s, ","), *s,
                spec, usage);
}

swarf_status swarf_machine_parse(swarf_machine *m, const char *spec, swarf_error *err) {
  const char *s = spec;
  size_t n, which = 0;
  int found = 0, head_given = 0;
  if (m == NULL || spec == NULL) return refuse(err, "--machine: no machine given; %s", usage);
  memset(m, 0, sizeof *m);
  m->tcp = 1;
  n = strcspn(s, ",");
  for (size_t i = 0; i < sizeof machines / sizeof machines[0]; i++)
    if (strlen(machines[i].name) == n && strncmp(s, machines[i].name, n) == 0) {
      m->kind = machines[i].kind;
      which = i;
      found = 1;
    }
  if (!found) return refuse(err, "--machine: unknown machine \"%.*s\"; %s", (int)n, s, usage);
  if (m->kind == SWARF_MACHINE_XYZA) m->tcp = 0;
  for (s += n; *s == ',';) {
    s++;
    head_given |= strncmp(s, "head=", 5) == 0;
    if (parse_key(m, which, &s, spec, err) != SWARF_OK) return SWARF_ERR_ARG;
  }
  if (*s != '\0') return refuse(err, "--machine: unexpected \"%s\" in \"%s\"; %s", s, spec, usage);
  if (machines[which].head && !m->tcp && !head_given)
    return refuse(err,
                  "--machine: %s in joint mode needs head=L (the head's pivot, mm above the "
                  "tip at zero angles) in \"%s\"",
                  machines[which].name, spec);
  return SWARF_OK;
}
