/* machine.c -- machine kinematics: the --machine description and the rigid
 * motion of the cutter in the workpiece frame for each canonical move.
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
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "toolpath_private.h"

static const double deg = 3.14159265358979323846 / 180.0;

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

/* One ",key=value" field at *s (after the comma). */
static int parse_key(swarf_machine *m, int npivot, const char **s, char *msg, size_t msglen,
                     const char *spec) {
  if (npivot > 0 && strncmp(*s, "pivot=", 6) == 0) {
    *s += 6;
    if (read_pivot(s, npivot, m->pivot) == 0) return 0;
    snprintf(msg, msglen, "--machine: pivot needs %d numbers in \"%s\"; %s", npivot, spec, usage);
    return -1;
  }
  if (npivot == 3 && strncmp(*s, "mode=", 5) == 0) {
    const char *v = *s + 5;
    size_t n = strcspn(v, ",");
    if ((n == 3 && !strncmp(v, "tcp", 3)) || (n == 5 && !strncmp(v, "joint", 5))) {
      m->tcp = n == 3;
      *s = v + n;
      return 0;
    }
  }
  snprintf(msg, msglen, "--machine: unknown field \"%.*s\" in \"%s\"; %s", (int)strcspn(*s, ","),
           *s, spec, usage);
  return -1;
}

int swarf_machine_parse(swarf_machine *m, const char *spec, char *msg, size_t msglen) {
  const char *s = spec;
  size_t n;
  int npivot = -1;
  if (m == NULL || spec == NULL) return -1;
  memset(m, 0, sizeof *m);
  m->tcp = 1;
  n = strcspn(s, ",");
  for (size_t i = 0; i < sizeof machines / sizeof machines[0]; i++)
    if (strlen(machines[i].name) == n && strncmp(s, machines[i].name, n) == 0) {
      m->kind = machines[i].kind;
      npivot = machines[i].npivot;
    }
  if (npivot < 0) {
    snprintf(msg, msglen, "--machine: unknown machine \"%.*s\"; %s", (int)n, s, usage);
    return -1;
  }
  if (m->kind == SWARF_MACHINE_XYZA) m->tcp = 0;
  for (s += n; *s == ',';) {
    s++;
    if (parse_key(m, npivot, &s, msg, msglen, spec) != 0) return -1;
  }
  if (*s != '\0') {
    snprintf(msg, msglen, "--machine: unexpected \"%s\" in \"%s\"; %s", s, spec, usage);
    return -1;
  }
  return 0;
}

/* The machine's rotary axes: indices into a move's axes (-1: none). */
static void machine_axes(swarf_machine_kind kind, int ax[2]) {
  ax[0] = kind == SWARF_MACHINE_XYZBC_TRT ? SWARF_AXIS_B : SWARF_AXIS_A;
  ax[1] = kind == SWARF_MACHINE_XYZA ? -1 : SWARF_AXIS_C;
}

/* -2 if the move turns an axis the machine does not have. */
static int check_axes(const swarf_machine *mc, const swarf_move *mv, const int ax[2]) {
  for (int k = SWARF_AXIS_A; k <= SWARF_AXIS_C; k++)
    if (mv->start[k] != mv->end[k] && (mc->kind == SWARF_MACHINE_XYZ || (k != ax[0] && k != ax[1])))
      return -2;
  return 0;
}

static void fill_rigid(const swarf_machine *mc, const swarf_move *mv, const int ax[2],
                       swarf_motion *m) {
  double programmed = m->length, turn_deg = 0.0;
  m->kind = SWARF_MOTION_RIGID;
  m->tcp = mc->kind != SWARF_MACHINE_XYZA && mc->tcp;
  memcpy(m->pivot, mc->pivot, sizeof m->pivot);
  m->e1[mc->kind == SWARF_MACHINE_XYZBC_TRT ? 1 : 0] = 1.0;
  if (ax[1] >= 0) m->e2[2] = 1.0;
  for (int i = 0; i < 2; i++) {
    if (ax[i] < 0) continue;
    m->th0[i] = mv->start[ax[i]] * deg;
    m->th1[i] = mv->end[ax[i]] * deg;
    m->turn += fabs(m->th1[i] - m->th0[i]);
    turn_deg += fabs(mv->end[ax[i]] - mv->start[ax[i]]);
  }
  m->length = swarf_rigid_length(m);
  /* Feed: along the programmed X Y Z path, or in degrees/min for a purely
   * rotary move (LinuxCNC's rule). */
  if (m->rapid)
    m->duration = fmax(programmed, turn_deg) / SWARF_RAPID_RATE * 60.0;
  else if (mv->feed > 0)
    m->duration = (programmed > 0 ? programmed : turn_deg) / mv->feed * 60.0;
}

int swarf_machine_motion(const swarf_machine *mc, const swarf_move *mv, swarf_motion *out) {
  swarf_move flat;
  int ax[2], rc, zero = 1;
  if (mc == NULL || mv == NULL || out == NULL) return -1;
  if (mv->kind != SWARF_MOVE_RAPID && mv->kind != SWARF_MOVE_LINE && mv->kind != SWARF_MOVE_ARC)
    return -1;
  machine_axes(mc->kind, ax);
  if (check_axes(mc, mv, ax) != 0) return -2;
  flat = *mv; /* the X Y Z part of the move */
  for (int k = SWARF_AXIS_A; k <= SWARF_AXIS_C; k++)
    flat.start[k] = flat.end[k] = mv->start[k];
  if ((rc = swarf_motion_from_move(&flat, out)) != 0) return rc;
  if (mc->kind == SWARF_MACHINE_XYZ) return 0;
  for (int i = 0; i < 2; i++)
    if (ax[i] >= 0 && (mv->start[ax[i]] != 0.0 || mv->end[ax[i]] != 0.0)) zero = 0;
  if (!zero) fill_rigid(mc, mv, ax, out);
  return 0;
}
