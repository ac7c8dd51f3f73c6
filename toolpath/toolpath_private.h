/* SPDX-License-Identifier: MPL-2.0 */
/* toolpath_private.h -- the toolpath module's insides, shared by its files only.
 *
 *   motion.c   xyz motions (lines, helices) and the public dispatch.
 *   rigid.c    RIGID motions: table rotations, poses, velocities, bounds.
 *   machine.c  machine descriptions (--machine).
 *   move_motion.c  canonical moves -> motions (library swarf_move_motion).
 *   pose_table.c  per-thread tables of poses at evenly spaced times.
 */
#ifndef SWARF_TOOLPATH_PRIVATE_H
#define SWARF_TOOLPATH_PRIVATE_H

#include "toolpath.h"

/* The programmed tip path P(alpha) (line, or helix when m->helix) and, if d
 * is not NULL, dP/dalpha; in the frame p0 and p1 are given in. */
void swarf_path_point(const swarf_motion *m, double alpha, double P[3], double d[3]);

void swarf_rigid_eval(const swarf_motion *m, double alpha, double t[3], double U[9]);
void swarf_rigid_pose(const swarf_motion *m, double alpha, double t[3], double U[9], double tdot[3],
                      double v[3], double omega[3]);
void swarf_rigid_velocity(const swarf_motion *m, double alpha, double tdot[3], double v[3],
                          double omega[3]);
void swarf_rigid_bounds(const swarf_motion *m, double lo[3], double hi[3]);
double swarf_rigid_length(const swarf_motion *m);

#endif
