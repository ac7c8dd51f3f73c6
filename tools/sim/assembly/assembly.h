/* SPDX-License-Identifier: MPL-2.0 */
/* assembly.h -- tool assemblies inside the driver (private to tools/sim).
 *
 * Role: the tool table of a config (slots by T number), the assembly fields
 * of --tool specs (S stick-out, N shank), and the non-cutting bodies of a
 * tool (shank, holder pieces) as the collision check uses them. Units mm.
 * Plain functions on caller-owned values: thread-safe for distinct values.
 */
#ifndef SWARF_SIM_ASSEMBLY_H
#define SWARF_SIM_ASSEMBLY_H

#include "swarf_sim.h"

#define SWARF_SIM_MAX_TOOL_NUMBER 999 /* the G-code interpreter's tool numbers */

/* The tool numbered `number` in cfg; with create, a new zeroed slot (NULL
 * when the table is full); without, NULL when absent. */
swarf_sim_tool *swarf_sim_tool_slot(swarf_sim_config *cfg, int number, int create);
/* Removes tool `number` (if there). */
void swarf_sim_tool_drop(swarf_sim_config *cfg, int number);

/* Splits the assembly fields ",S<mm>" and ",N<mm>" off a --tool spec
 * "T<n>=<family>,..." (any field after the family): the rest goes to
 * cutter_spec (same order), S and N (0 when absent) to the tool. */
swarf_status swarf_sim_split_assembly(const char *spec, char *cutter_spec, size_t len,
                                      double *stickout, double *shank, swarf_error *err);

/* Checks the assembly fields of t (S, N, holder): finite, positive; a
 * holder needs a stick-out. `what` names the source in messages. */
swarf_status swarf_sim_check_assembly(const swarf_sim_tool *t, const char *what, swarf_error *err);

/* A non-cutting body of a tool: a cylinder or cone frustum about the tool
 * axis from z0 to z1 above the tip (tool frame), diameters d0 at z0 and d1
 * at z1. */
typedef struct {
  swarf_alarm_kind kind; /* SWARF_ALARM_SHANK or SWARF_ALARM_HOLDER */
  double z0, z1, d0, d1;
} swarf_sim_part;

#define SWARF_SIM_MAX_PARTS (1 + SWARF_SIM_MAX_HOLDER)

/* The non-cutting bodies of t, bottom to top: the shank (when S exceeds the
 * flute length) and the holder's pieces. Returns how many (0 without S). */
int swarf_sim_tool_parts(const swarf_sim_tool *t, swarf_sim_part parts[SWARF_SIM_MAX_PARTS]);

/* ---- Collisions (collide.c) --------------------------------------------- */

/* The collision check's state in a handle. */
typedef struct {
  long last_line[2]; /* SHANK, HOLDER: the line last reported (once per line) */
  long fixture_line[SWARF_SIM_MAX_FIXTURES][3]; /* per fixture and part (cutter, shank, holder) */
  swarf_stock *fixture[SWARF_SIM_MAX_FIXTURES]; /* each fixture as a level set */
  swarf_stock_cut *clear;           /* scratch: the sweeps clearing material for a part */
  long checked;                     /* part checks that reached a grid's box */
  long measured[SWARF_ALARM_KINDS]; /* depths measured, per swarf_alarm_kind */
} swarf_sim_collide;

/* The motion m with the tool carried dz along its axis (a body dz above the
 * tip); -1 when the machine cannot express it (a RIGID motion in TCP mode). */
int swarf_sim_shift_motion(const swarf_motion *m, double dz, swarf_motion *out);

#endif
