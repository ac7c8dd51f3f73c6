/* SPDX-License-Identifier: MPL-2.0 */
/* swarf_reference.h -- the reference paths the tests compare the fast ones
 * with (engine/base, plain C).
 *
 * Some algorithms keep a slower, simpler twin: removal without the block
 * hierarchy or the range functions, the general sweep search for every
 * cutter, a stock shaped by removal, OpenVDB's serial writer. The tests run
 * both and compare grids. Each twin is chosen by an environment variable
 * (SWARF_REMOVE_FLAT=1 ...), but only in a build configured with
 * -DSWARF_REFERENCE_PATHS=ON (what `tools/run test` builds): an installed
 * library, built without it, ignores the environment and always takes the
 * fast path.
 */
#ifndef SWARF_REFERENCE_H
#define SWARF_REFERENCE_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  SWARF_REFERENCE_REMOVE_FLAT,      /* SWARF_REMOVE_FLAT: removal without the hierarchy */
  SWARF_REFERENCE_REMOVE_PLAIN,     /* SWARF_REMOVE_PLAIN: no range functions */
  SWARF_REFERENCE_SWEEP_GENERAL,    /* SWARF_SWEEP_GENERAL: every cutter's general search */
  SWARF_REFERENCE_SHAPE_REMOVE,     /* SWARF_SHAPE_REMOVE: stocks shaped by removal */
  SWARF_REFERENCE_VDB_SERIAL_WRITE, /* SWARF_VDB_SERIAL_WRITE: OpenVDB's own writer */
  SWARF_REFERENCE_COUNT
} swarf_reference;

/* 1 when the reference path `which` is asked for (its variable's value
 * starts with '1') in a build with the reference paths, else 0. Read once
 * per process; thread-safe. */
int swarf_reference_on(swarf_reference which);

/* 1 when this build has the reference paths (-DSWARF_REFERENCE_PATHS=ON). */
int swarf_reference_built(void);

#ifdef __cplusplus
}
#endif

#endif
