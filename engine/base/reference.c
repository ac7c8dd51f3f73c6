/* SPDX-License-Identifier: MPL-2.0 */
/* reference.c -- the reference paths' switches (swarf_reference.h). */
#include "swarf_reference.h"

#include <stdatomic.h>
#include <stdlib.h>

int swarf_reference_built(void) {
#ifdef SWARF_REFERENCE_PATHS
  return 1;
#else
  return 0;
#endif
}

int swarf_reference_on(swarf_reference which) {
#ifdef SWARF_REFERENCE_PATHS
  static const char *const names[SWARF_REFERENCE_COUNT] = {
      "SWARF_REMOVE_FLAT", "SWARF_REMOVE_PLAIN", "SWARF_SWEEP_GENERAL", "SWARF_SHAPE_REMOVE",
      "SWARF_VDB_SERIAL_WRITE"};
  static atomic_int cached[SWARF_REFERENCE_COUNT] = {-1, -1, -1, -1, -1};
  if ((unsigned)which >= SWARF_REFERENCE_COUNT) return 0;
  int v = atomic_load_explicit(&cached[which], memory_order_relaxed);
  if (v < 0) {
    const char *e = getenv(names[which]);
    v = e != NULL && e[0] == '1';
    atomic_store_explicit(&cached[which], v, memory_order_relaxed);
  }
  return v;
#else
  (void)which;
  return 0;
#endif
}
