/* SPDX-License-Identifier: MPL-2.0 */
/* codes.c -- the G and M codes LinuxCNC knows, with their modal groups.
 *
 * Codes are integers in tenths (G91.1 -> 911). User M codes M100-M199 and
 * M400-M499 (LinuxCNC REMAPs them, e.g. M428/M429 switching kinematics in
 * its 5-axis samples) are accepted and make no motion. A code with `later` set is a
 * real LinuxCNC code that this version refuses with a "not supported yet"
 * message naming it; a code missing from the tables is unknown ("Unknown g
 * code used"). The tables are constant data, owned by this file.
 */
#include <stddef.h>

#include "gcode_private.h"

/* Sorted by code (find() searches them by halves). */
static const swarf_gc_code g_codes[] = {
    {0, SWARF_GC_GROUP_MOTION, NULL},
    {10, SWARF_GC_GROUP_MOTION, NULL},
    {20, SWARF_GC_GROUP_MOTION, NULL},
    {30, SWARF_GC_GROUP_MOTION, NULL},
    {40, SWARF_GC_GROUP_NONMODAL, NULL},
    {50, SWARF_GC_GROUP_MOTION, NULL},
    {51, SWARF_GC_GROUP_MOTION, NULL},
    {52, SWARF_GC_GROUP_MOTION, "NURBS"},
    {53, SWARF_GC_GROUP_NONMODAL, "NURBS"},
    {70, SWARF_GC_GROUP_LATHE, "lathe diameter mode"},
    {80, SWARF_GC_GROUP_LATHE, "lathe radius mode"},
    {100, SWARF_GC_GROUP_NONMODAL, NULL},
    {170, SWARF_GC_GROUP_PLANE, NULL},
    {171, SWARF_GC_GROUP_PLANE, "UV plane"},
    {180, SWARF_GC_GROUP_PLANE, NULL},
    {181, SWARF_GC_GROUP_PLANE, "WU plane"},
    {190, SWARF_GC_GROUP_PLANE, NULL},
    {191, SWARF_GC_GROUP_PLANE, "VW plane"},
    {200, SWARF_GC_GROUP_UNITS, NULL},
    {210, SWARF_GC_GROUP_UNITS, NULL},
    {280, SWARF_GC_GROUP_NONMODAL, NULL},
    {281, SWARF_GC_GROUP_NONMODAL, NULL},
    {300, SWARF_GC_GROUP_NONMODAL, NULL},
    {301, SWARF_GC_GROUP_NONMODAL, NULL},
    {330, SWARF_GC_GROUP_MOTION, "spindle-synchronized motion"},
    {331, SWARF_GC_GROUP_MOTION, "rigid tapping"},
    {382, SWARF_GC_GROUP_MOTION, NULL},
    {383, SWARF_GC_GROUP_MOTION, NULL},
    {384, SWARF_GC_GROUP_MOTION, NULL},
    {385, SWARF_GC_GROUP_MOTION, NULL},
    {400, SWARF_GC_GROUP_CUTTER_COMP, NULL},
    {410, SWARF_GC_GROUP_CUTTER_COMP, NULL},
    {411, SWARF_GC_GROUP_CUTTER_COMP, NULL},
    {420, SWARF_GC_GROUP_CUTTER_COMP, NULL},
    {421, SWARF_GC_GROUP_CUTTER_COMP, NULL},
    {430, SWARF_GC_GROUP_TOOL_LENGTH, NULL},
    {431, SWARF_GC_GROUP_TOOL_LENGTH, NULL},
    {432, SWARF_GC_GROUP_TOOL_LENGTH, "additional tool length offset"},
    {490, SWARF_GC_GROUP_TOOL_LENGTH, NULL},
    {520, SWARF_GC_GROUP_NONMODAL, NULL},
    {530, SWARF_GC_GROUP_NONMODAL, NULL},
    {540, SWARF_GC_GROUP_COORD_SYSTEM, NULL},
    {550, SWARF_GC_GROUP_COORD_SYSTEM, NULL},
    {560, SWARF_GC_GROUP_COORD_SYSTEM, NULL},
    {570, SWARF_GC_GROUP_COORD_SYSTEM, NULL},
    {580, SWARF_GC_GROUP_COORD_SYSTEM, NULL},
    {590, SWARF_GC_GROUP_COORD_SYSTEM, NULL},
    {591, SWARF_GC_GROUP_COORD_SYSTEM, NULL},
    {592, SWARF_GC_GROUP_COORD_SYSTEM, NULL},
    {593, SWARF_GC_GROUP_COORD_SYSTEM, NULL},
    {610, SWARF_GC_GROUP_PATH_CONTROL, NULL},
    {611, SWARF_GC_GROUP_PATH_CONTROL, NULL},
    {640, SWARF_GC_GROUP_PATH_CONTROL, NULL},
    {700, SWARF_GC_GROUP_MOTION, "lathe finishing cycle"},
    {710, SWARF_GC_GROUP_MOTION, "lathe roughing cycle"},
    {711, SWARF_GC_GROUP_MOTION, "lathe roughing cycle"},
    {720, SWARF_GC_GROUP_MOTION, "lathe roughing cycle"},
    {721, SWARF_GC_GROUP_MOTION, "lathe roughing cycle"},
    {730, SWARF_GC_GROUP_MOTION, NULL},
    {740, SWARF_GC_GROUP_MOTION, "canned cycle"},
    {760, SWARF_GC_GROUP_MOTION, "threading cycle"},
    {800, SWARF_GC_GROUP_MOTION, NULL},
    {810, SWARF_GC_GROUP_MOTION, NULL},
    {820, SWARF_GC_GROUP_MOTION, NULL},
    {830, SWARF_GC_GROUP_MOTION, NULL},
    {840, SWARF_GC_GROUP_MOTION, NULL},
    {850, SWARF_GC_GROUP_MOTION, NULL},
    {860, SWARF_GC_GROUP_MOTION, NULL},
    {870, SWARF_GC_GROUP_MOTION, NULL},
    {880, SWARF_GC_GROUP_MOTION, NULL},
    {890, SWARF_GC_GROUP_MOTION, NULL},
    {900, SWARF_GC_GROUP_DISTANCE, NULL},
    {901, SWARF_GC_GROUP_ARC_DISTANCE, NULL},
    {910, SWARF_GC_GROUP_DISTANCE, NULL},
    {911, SWARF_GC_GROUP_ARC_DISTANCE, NULL},
    {920, SWARF_GC_GROUP_NONMODAL, NULL},
    {921, SWARF_GC_GROUP_NONMODAL, NULL},
    {922, SWARF_GC_GROUP_NONMODAL, NULL},
    {923, SWARF_GC_GROUP_NONMODAL, NULL},
    {930, SWARF_GC_GROUP_FEED_MODE, NULL},
    {940, SWARF_GC_GROUP_FEED_MODE, NULL},
    {950, SWARF_GC_GROUP_FEED_MODE, NULL},
    {960, SWARF_GC_GROUP_SPINDLE_MODE, "constant surface speed"},
    {970, SWARF_GC_GROUP_SPINDLE_MODE, NULL},
    {980, SWARF_GC_GROUP_RETURN_MODE, NULL},
    {990, SWARF_GC_GROUP_RETURN_MODE, NULL},
};

/* Sorted by code, as g_codes. */
static const swarf_gc_code m_codes[] = {
    {0, SWARF_GC_MGROUP_STOP, NULL},
    {10, SWARF_GC_MGROUP_STOP, NULL},
    {20, SWARF_GC_MGROUP_STOP, NULL},
    {30, SWARF_GC_MGROUP_SPINDLE, NULL},
    {40, SWARF_GC_MGROUP_SPINDLE, NULL},
    {50, SWARF_GC_MGROUP_SPINDLE, NULL},
    {60, SWARF_GC_MGROUP_TOOL, NULL},
    {70, SWARF_GC_MGROUP_COOLANT, NULL},
    {80, SWARF_GC_MGROUP_COOLANT, NULL},
    {90, SWARF_GC_MGROUP_COOLANT, NULL},
    {190, SWARF_GC_MGROUP_SPINDLE, NULL},
    {300, SWARF_GC_MGROUP_STOP, NULL},
    {480, SWARF_GC_MGROUP_OVERRIDE, NULL},
    {490, SWARF_GC_MGROUP_OVERRIDE, NULL},
    {500, SWARF_GC_MGROUP_OVERRIDE, NULL},
    {510, SWARF_GC_MGROUP_OVERRIDE, NULL},
    {520, SWARF_GC_MGROUP_OVERRIDE, NULL},
    {530, SWARF_GC_MGROUP_OVERRIDE, NULL},
    {600, SWARF_GC_MGROUP_STOP, NULL},
    {610, SWARF_GC_MGROUP_TOOL, NULL},
    {620, SWARF_GC_MGROUP_IO, NULL},
    {630, SWARF_GC_MGROUP_IO, NULL},
    {640, SWARF_GC_MGROUP_IO, NULL},
    {650, SWARF_GC_MGROUP_IO, NULL},
    {660, SWARF_GC_MGROUP_IO, "waiting on an input"},
    {670, SWARF_GC_MGROUP_IO, NULL},
    {680, SWARF_GC_MGROUP_IO, NULL},
    {700, SWARF_GC_MGROUP_OVERRIDE, NULL},
    {710, SWARF_GC_MGROUP_OVERRIDE, NULL},
    {720, SWARF_GC_MGROUP_OVERRIDE, NULL},
    {730, SWARF_GC_MGROUP_OVERRIDE, NULL},
};

/* Binary search of a table sorted by code. */
static const swarf_gc_code *find(const swarf_gc_code *table, size_t n, int tenths) {
  size_t lo = 0, hi = n;
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (table[mid].code == tenths) return &table[mid];
    if (table[mid].code < tenths)
      lo = mid + 1;
    else
      hi = mid;
  }
  return NULL;
}

const swarf_gc_code *swarf_gc_g_code(int tenths) {
  return find(g_codes, sizeof g_codes / sizeof g_codes[0], tenths);
}

const swarf_gc_code *swarf_gc_m_code(int tenths) {
  static const swarf_gc_code user = {0, SWARF_GC_MGROUP_USER, "user-defined M code"};
  static const swarf_gc_code remap = {0, SWARF_GC_MGROUP_USER, NULL};
  if (tenths >= 1000 && tenths <= 1990 && tenths % 10 == 0) return &remap;
  if (tenths >= 4000 && tenths <= 4990 && tenths % 10 == 0) return &remap;
  (void)user;
  return find(m_codes, sizeof m_codes / sizeof m_codes[0], tenths);
}
