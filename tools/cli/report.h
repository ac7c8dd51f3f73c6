/* SPDX-License-Identifier: MPL-2.0 */
/* report.h -- `swarf simulate --report FILE.json`: what a run did, as JSON.
 *
 * Role: a client of the driver (swarf_sim.h). It collects what the driver's
 * line and alarm callbacks hand out -- per source line and tool: moves, time,
 * tip path and the volume removed -- sums them per tool, and writes them with
 * the final report (the design comparison included) and the run's inputs to
 * one JSON document (jansson; the schema is in tools/doc/simulate.md). The file is
 * written to a temporary name in the same folder and renamed into place.
 *
 * Units: mm, mm^3, seconds. Ownership: the collector owns its entries; the
 * inputs are borrowed for the call. Not thread-safe: the driver calls back in
 * the caller's thread.
 */
#ifndef SWARF_CLI_REPORT_H
#define SWARF_CLI_REPORT_H

#include <stddef.h>

#include "swarf_sim.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct swarf_report swarf_report;

/* Per source line and tool, summed over every time the line ran (a loop or
 * a subroutine runs its lines more than once). */
typedef struct {
  long line;
  int tool;
  long moves;
  double time_s, path_mm, removed_mm3; /* removed: NaN unless measured */
} swarf_report_line;

/* The run's inputs, as the user gave them (borrowed; NULL: not given). */
typedef struct {
  const char *program, *stock, *machine, *offsets, *units, *design;
  const char *const *tools; /* --tool specs */
  int ntools;
  double voxel;        /* of the stock, mm */
  double tolerance;    /* as given (<= 0: the default) */
  const double *g54;   /* [3], mm, or NULL */
  const double *start; /* [3], mm, or NULL (the default) */
} swarf_report_inputs;

swarf_report *swarf_report_new(void);
void swarf_report_free(swarf_report *r);

/* The driver's callbacks feed these (swarf_sim_callbacks.line / .alarm call
 * them from the client's own callbacks). Out of memory is remembered and
 * reported by swarf_report_write. */
void swarf_report_add_line(swarf_report *r, const swarf_line_result *l);
void swarf_report_add_alarm(swarf_report *r, const swarf_alarm *a);

/* The entries so far, sorted by line then tool (valid until the next add). */
const swarf_report_line *swarf_report_lines(swarf_report *r, size_t *n);

/* The alarms to tell: every one in program order, except that the gouges of
 * one program line are one alarm (its deepest; the column of the first).
 * *n gets the count; valid until the next call. */
const swarf_alarm *swarf_report_alarms(swarf_report *r, size_t *n);

/* The gouges of that list, one a program line, sorted by line. */
const swarf_alarm *swarf_report_gouges(swarf_report *r, size_t *n);

/* The line of the highest removal rate (removed / time over entries with
 * time > 0); *mm3_per_min its rate. 0 when nothing was removed. */
long swarf_report_peak_mrr(swarf_report *r, double *mm3_per_min, int *tool);

/* Writes the document to `path` (temporary name, then rename): the final
 * report (its start, units check and design comparison included), the
 * entries, the alarms and the inputs. */
swarf_status swarf_report_write(swarf_report *r, const swarf_sim_report *final,
                                const swarf_report_inputs *in, const char *path, swarf_error *err);

/* The same document as compact JSON text (the caller frees it), or NULL
 * when out of memory (err says so). */
char *swarf_report_text(swarf_report *r, const swarf_sim_report *final,
                        const swarf_report_inputs *in, swarf_error *err);

#ifdef __cplusplus
}
#endif
#endif
