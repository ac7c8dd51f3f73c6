/* SPDX-License-Identifier: MPL-2.0 */
/* move_motion.h -- canonical moves of the G-code front end become rigid
 * motions of the cutter: the one place where toolpath meets gcode.
 *
 * Role: a swarf_move (gcode.h: machine-frame positions in mm, rotary axes in
 * degrees, feed in mm/min) becomes a swarf_motion (toolpath.h: mm, radians,
 * seconds) on a given machine. Library swarf_move_motion (it links
 * swarf_toolpath and swarf_gcode; swarf_toolpath and swarf_engine do not
 * know G-code).
 *
 * Values only, no state: thread-safe. The caller owns every struct.
 */
#ifndef SWARF_MOVE_MOTION_H
#define SWARF_MOVE_MOTION_H

#include "gcode.h"
#include "swarf_status.h"
#include "toolpath.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fill `out` from a motion move (RAPID, LINE or ARC) of a 3-axis machine.
 * SWARF_ERR_ARG when the move makes no motion (dwell, tool change);
 * SWARF_ERR_MACHINE when it turns a rotary axis (the xyz machine has none):
 * *err (may be NULL) then says so at the move's line and column. */
SWARF_API swarf_status swarf_motion_from_move(const swarf_move *move, swarf_motion *out,
                                              swarf_error *err);

/* The rigid motion of the cutter in the workpiece frame for `move` on machine
 * `mc`. Straight moves that turn a rotary axis become RIGID motions; the rest
 * as swarf_motion_from_move. SWARF_ERR_ARG for moves without motion;
 * SWARF_ERR_MACHINE when the machine does not have an axis the move turns
 * (or an arc turns one), with *err (may be NULL) at the move's line and
 * column (no file: the caller's). */
SWARF_API swarf_status swarf_machine_motion(const swarf_machine *mc, const swarf_move *move,
                                            swarf_motion *out, swarf_error *err);

#ifdef __cplusplus
}
#endif
#endif
