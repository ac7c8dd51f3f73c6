/* SPDX-License-Identifier: MPL-2.0 */
/* setup.c -- the machine a program runs on: its length unit, parameters
 * (offsets, homes) and where the controlled point is at the start.
 *
 * Everything here happens before the first line: the committed state is
 * changed in place and the program's current point is recomputed from the
 * start's machine position after every call, so the calls may come in any
 * order (the unit first: it is the unit of the parameters).
 */
#include <math.h>
#include <string.h>

#include "gcode_private.h"

/* The calls below are refused once the program has started. */
static swarf_status check_setup(const swarf_gcode_parser *p, swarf_error *err) {
  if (p == NULL) return SWARF_GC_ERROR(SWARF_GCODE_E_SETUP_NO_PARSER, err);
  if (p->lines > 0 || p->partial_len > 0) return SWARF_GC_ERROR(SWARF_GCODE_E_SETUP_STARTED, err);
  return SWARF_OK;
}

/* The program's current point follows from the start and the offsets. */
static void apply_setup(swarf_gcode_parser *p) {
  swarf_gc_state *st = p->state;
  if (p->g92_restore) {
    memcpy(st->g92, st->g92_saved, sizeof st->g92);
    st->g92_on = 1;
  }
  swarf_gc_from_machine(st, p->start, st->pos);
}

swarf_status swarf_gcode_parser_set_units(swarf_gcode_parser *p, swarf_gcode_units u,
                                          swarf_error *err) {
  swarf_status s = check_setup(p, err);
  if (s != SWARF_OK) return s;
  if (u != SWARF_GCODE_UNITS_MM && u != SWARF_GCODE_UNITS_INCH)
    return SWARF_GC_ERROR(SWARF_GCODE_E_UNITS_VALUE, err);
  if (p->params_set) return SWARF_GC_ERROR(SWARF_GCODE_E_UNITS_AFTER_PARAMS, err);
  p->state->modal.units = u == SWARF_GCODE_UNITS_INCH ? 200 : 210;
  p->params.length_unit = u == SWARF_GCODE_UNITS_INCH ? SWARF_GC_MM_PER_INCH : 1.0;
  apply_setup(p);
  return SWARF_OK;
}

/* The parameters the interpreter computes from its state. */
static int computed(int index) {
  return (index >= 5021 && index <= 5029) || index == 5400 || (index >= 5420 && index <= 5428);
}

static swarf_status set_special(swarf_gcode_parser *p, int index, double value, swarf_error *err) {
  static const int systems[9] = {540, 550, 560, 570, 580, 590, 591, 592, 593};
  if (index == 5220) {
    int k = (int)value;
    if (value != k || k < 1 || k > 9)
      return SWARF_GC_ERROR(SWARF_GCODE_E_SYSTEM_PARAM_VALUE, err, value);
    p->state->modal.coord_system = systems[k - 1];
    return SWARF_OK;
  }
  if (value != 0 && value != 1) return SWARF_GC_ERROR(SWARF_GCODE_E_G92_PARAM_VALUE, err, value);
  p->g92_restore = value == 1;
  if (value == 0) {
    memset(p->state->g92, 0, sizeof p->state->g92);
    p->state->g92_on = 0;
  }
  return SWARF_OK;
}

swarf_status swarf_gcode_parser_set_param(swarf_gcode_parser *p, int index, double value,
                                          swarf_error *err) {
  swarf_status s = check_setup(p, err);
  if (s != SWARF_OK) return s;
  if (index < 1 || index >= SWARF_GC_NPARAMS)
    return SWARF_GC_ERROR(SWARF_GCODE_E_PARAM_NOT_FOUND, err, index, SWARF_GC_NPARAMS - 1);
  if (!isfinite(value) || fabs(value) > SWARF_GC_NUMBER_MAX)
    return SWARF_GC_ERROR(SWARF_GCODE_E_PARAM_VALUE, err, index, value);
  if (computed(index)) return SWARF_GC_ERROR(SWARF_GCODE_E_PARAM_COMPUTED, err, index);
  if (index == 5210 || index == 5220) {
    s = set_special(p, index, value, err);
    if (s != SWARF_OK) return s;
    p->params.num[index] = value;
  } else {
    swarf_gc_param_set(&p->params, p->state, index, value);
  }
  p->params_set = 1;
  apply_setup(p);
  return SWARF_OK;
}

swarf_status swarf_gcode_parser_set_start(swarf_gcode_parser *p, const double machine[SWARF_NAXES],
                                          swarf_error *err) {
  swarf_status s = check_setup(p, err);
  if (s != SWARF_OK) return s;
  if (machine == NULL) return SWARF_GC_ERROR(SWARF_GCODE_E_START_MISSING, err);
  for (int i = 0; i < SWARF_NAXES; i++)
    if (!isfinite(machine[i]) || fabs(machine[i]) > SWARF_GC_NUMBER_MAX)
      return SWARF_GC_ERROR(SWARF_GCODE_E_START_NOT_FINITE, err);
  memcpy(p->start, machine, sizeof p->start);
  apply_setup(p);
  return SWARF_OK;
}

swarf_status swarf_gcode_parser_work_system(const swarf_gcode_parser *p, int system,
                                            double origin[SWARF_NAXES], double *rotation) {
  if (p == NULL || system < 1 || system > SWARF_GC_NSYSTEMS) return SWARF_ERR_ARG;
  if (origin != NULL) memcpy(origin, p->state->systems[system - 1], SWARF_NAXES * sizeof *origin);
  if (rotation != NULL) *rotation = p->state->rotations[system - 1];
  return SWARF_OK;
}

long swarf_gcode_parser_units_line(const swarf_gcode_parser *p) {
  return p != NULL ? p->state->units_line : 0;
}
