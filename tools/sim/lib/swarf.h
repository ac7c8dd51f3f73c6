/* SPDX-License-Identifier: MPL-2.0 */
/* swarf.h -- libswarf, all of it: the one header an embedding program needs.
 *
 * Role: a CNC milling simulation engine as a library. A G-code program (or a
 * list of rigid motions) streams through the interpreter, each move becomes
 * the exact volume swept by the cutter, and the volume is removed from an
 * OpenVDB level-set stock, which can be measured, sampled and written as
 * .vdb, STL or PNG. Start with swarf_sim.h (the simulation handle); the
 * stages below it are public too:
 *
 *   swarf_version.h  SWARF_VERSION_* and swarf_version()
 *   swarf_status.h   the status type every call returns, the error record
 *   gcode.h          the streaming RS274/NGC interpreter (canonical moves)
 *   toolpath.h       rigid motions of the cutter; machines
 *   move_motion.h    G-code moves -> rigid motions
 *   engine.h         cutters, characteristic curves, swept volumes
 *   stock.h          the OpenVDB stock: remove, measure, read and write
 *   swarf_sim.h      the simulation handle tying them together
 *
 * The exact path (envelope_exact.h, on FLINT and arb) is in the library too
 * but not included here: include <swarf/envelope_exact.h> itself (it needs
 * the FLINT and arb headers).
 *
 * Use: #include <swarf/swarf.h>; compile and link with
 *   cc prog.c $(pkg-config --cflags --libs swarf)
 * or, in CMake, find_package(swarf) and target_link_libraries(prog swarf::swarf)
 * (swarf::swarf_static for libswarf.a). Units: mm, radians, seconds. Each
 * header states its own thread safety and ownership rules.
 */
#ifndef SWARF_H
#define SWARF_H

#include "engine.h"
#include "gcode.h"
#include "move_motion.h"
#include "stock.h"
#include "swarf_sim.h"
#include "swarf_status.h"
#include "swarf_version.h"
#include "toolpath.h"

#endif
