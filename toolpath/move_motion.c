/* SPDX-License-Identifier: MPL-2.0 */
/* move_motion.c -- canonical moves become rigid motions (move_motion.h).
 *
 * The xyz machine: t(alpha) follows the programmed straight line or helix
 * exactly (no chords), U = I. Rotary machines (machine.c describes them,
 * toolpath.h gives their directions): a move that turns a rotary axis
 * becomes a RIGID motion whose angles are the move's, interpolated linearly
 * as LinuxCNC does; machine_geometry says which axes turn what.
 */
#include <math.h>
#include <string.h>

#include "move_motion.h"
#include "toolpath_private.h"

static const double deg = 3.14159265358979323846 / 180.0;

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static int is_motion(const swarf_move *mv) {
  return mv->kind == SWARF_MOVE_RAPID || mv->kind == SWARF_MOVE_LINE || mv->kind == SWARF_MOVE_ARC;
}

/* The move turns an axis the machine does not have. */
static swarf_status no_axis(const swarf_move *mv, swarf_error *err) {
  swarf_error_init(err);
  swarf_error_at(err, NULL, mv->line, mv->column, NULL);
  return swarf_error_set(err, SWARF_ERR_MACHINE,
                         "this move turns a rotary axis the machine does not have; choose "
                         "one with --machine (xyza, xyzac-trt, xyzbc-trt, xyzab-tdr, "
                         "xyzbc-hh, xyzbc-ht)");
}

static void fill_common(const swarf_move *mv, swarf_motion *m) {
  memset(m, 0, sizeof *m);
  for (int k = 0; k < 3; k++) {
    m->p0[k] = mv->start[k];
    m->p1[k] = mv->end[k];
  }
  m->tool = mv->tool;
  m->rapid = mv->kind == SWARF_MOVE_RAPID;
  m->line = mv->line;
  m->column = mv->column;
}

static void fill_helix(const swarf_move *mv, swarf_motion *m) {
  double r[3], nr;
  m->kind = SWARF_MOTION_HELIX;
  m->helix = 1;
  memcpy(m->axis, mv->normal, sizeof m->axis);
  /* Keep the centre in the plane of p0 so that p0 - centre is radial. */
  for (int k = 0; k < 3; k++)
    r[k] = m->p0[k] - mv->center[k];
  nr = dot3(r, m->axis);
  for (int k = 0; k < 3; k++)
    m->center[k] = mv->center[k] + nr * m->axis[k];
  for (int k = 0; k < 3; k++)
    r[k] = m->p0[k] - m->center[k];
  m->radius = sqrt(dot3(r, r));
  m->angle = mv->angle;
  m->rise = mv->rise;
  m->length = hypot(m->radius * m->angle, m->rise);
  /* The path is the exact helix; its end replaces the programmed end, which
   * the front end allows to differ by the arc tolerance. */
  swarf_motion_eval(m, 1.0, m->p1, NULL);
}

swarf_status swarf_motion_from_move(const swarf_move *mv, swarf_motion *m, swarf_error *err) {
  double d[3];
  if (mv == NULL || m == NULL || !is_motion(mv)) return SWARF_ERR_ARG;
  for (int k = SWARF_AXIS_A; k <= SWARF_AXIS_C; k++)
    if (mv->start[k] != mv->end[k]) return no_axis(mv, err);
  fill_common(mv, m);
  if (mv->kind == SWARF_MOVE_ARC) {
    fill_helix(mv, m);
  } else {
    m->kind = SWARF_MOTION_LINE;
    for (int k = 0; k < 3; k++)
      d[k] = m->p1[k] - m->p0[k];
    m->length = sqrt(dot3(d, d));
  }
  if (m->rapid)
    m->duration = m->length / SWARF_RAPID_RATE * 60.0;
  else
    m->duration = mv->feed > 0 ? m->length / mv->feed * 60.0 : 0.0;
  return SWARF_OK;
}

/* The machine's rotary axes in the order of e1, e2 (indices into a move's
 * axes, -1: none), their directions (a negative sign: the angle turns the
 * other way, toolpath.h) and how many of them, from e1, are in the head. */
typedef struct {
  int ax[2];
  int dir1, sign1, dir2, sign2; /* e1 = sign1 * unit(dir1), e2 likewise */
  int nhead;
} geometry;

static geometry machine_geometry(swarf_machine_kind kind) {
  switch (kind) {
  case SWARF_MACHINE_XYZA:
    return (geometry){{SWARF_AXIS_A, -1}, 0, 1, 0, 0, 0};
  case SWARF_MACHINE_XYZAC_TRT:
    return (geometry){{SWARF_AXIS_A, SWARF_AXIS_C}, 0, 1, 2, 1, 0};
  case SWARF_MACHINE_XYZBC_TRT:
    return (geometry){{SWARF_AXIS_B, SWARF_AXIS_C}, 1, 1, 2, 1, 0};
  /* R = Ry(-B) Rx(-A) */
  case SWARF_MACHINE_XYZAB_TDR:
    return (geometry){{SWARF_AXIS_B, SWARF_AXIS_A}, 1, -1, 0, -1, 0};
  /* R = H = Ry(B) Rz(-C): the cutter's orientation Rz(C) Ry(-B) */
  case SWARF_MACHINE_XYZBC_HH:
    return (geometry){{SWARF_AXIS_B, SWARF_AXIS_C}, 1, 1, 2, -1, 2};
  /* H = Ry(B) (head), T = Rz(-C) (table) */
  case SWARF_MACHINE_XYZBC_HT:
    return (geometry){{SWARF_AXIS_B, SWARF_AXIS_C}, 1, 1, 2, -1, 1};
  default:
    return (geometry){{-1, -1}, 0, 0, 0, 0, 0};
  }
}

/* Whether the move turns an axis the machine does not have. */
static int lacks_axis(const swarf_machine *mc, const swarf_move *mv, const int ax[2]) {
  for (int k = SWARF_AXIS_A; k <= SWARF_AXIS_C; k++)
    if (mv->start[k] != mv->end[k] && (mc->kind == SWARF_MACHINE_XYZ || (k != ax[0] && k != ax[1])))
      return 1;
  return 0;
}

static void fill_rigid(const swarf_machine *mc, const swarf_move *mv, const geometry *g,
                       swarf_motion *m) {
  double programmed = m->length, turn_deg = 0.0;
  const int *ax = g->ax;
  m->kind = SWARF_MOTION_RIGID;
  m->tcp = mc->kind != SWARF_MACHINE_XYZA && mc->tcp;
  memcpy(m->pivot, mc->pivot, sizeof m->pivot);
  m->e1[g->dir1] = g->sign1;
  if (ax[1] >= 0) m->e2[g->dir2] = g->sign2;
  m->nhead = g->nhead;
  if (g->nhead > 0) m->head[2] = mc->head;
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

swarf_status swarf_machine_motion(const swarf_machine *mc, const swarf_move *mv, swarf_motion *out,
                                  swarf_error *err) {
  swarf_move flat;
  swarf_status rc;
  geometry g;
  int zero = 1;
  if (mc == NULL || mv == NULL || out == NULL || !is_motion(mv)) return SWARF_ERR_ARG;
  g = machine_geometry(mc->kind);
  if (lacks_axis(mc, mv, g.ax)) return no_axis(mv, err);
  flat = *mv; /* the X Y Z part of the move */
  for (int k = SWARF_AXIS_A; k <= SWARF_AXIS_C; k++)
    flat.start[k] = flat.end[k] = mv->start[k];
  if ((rc = swarf_motion_from_move(&flat, out, err)) != SWARF_OK) return rc;
  if (mc->kind == SWARF_MACHINE_XYZ) return SWARF_OK;
  for (int i = 0; i < 2; i++)
    if (g.ax[i] >= 0 && (mv->start[g.ax[i]] != 0.0 || mv->end[g.ax[i]] != 0.0)) zero = 0;
  if (!zero) fill_rigid(mc, mv, &g, out);
  return SWARF_OK;
}
