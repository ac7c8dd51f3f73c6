/* SPDX-License-Identifier: MPL-2.0 */
/* html.h -- `swarf simulate --html FILE.html`: the run as one page that
 * opens from disk with no network (three.js inlined at build time): the
 * remaining stock as a mesh (coarsened to stay under ~500k triangles),
 * coloured by its deviation from the design when there is one, the toolpath
 * with a slider through the program's lines, the tool at the chosen line,
 * the alarms linked to their lines, the line that last cut where the user
 * clicks, and a chart of removal rate and feed per line (tools/doc/html.md).
 *
 * Role: a client of the driver. It collects the moves the driver hands to
 * its move callback (workpiece frame, tool tip), then renders the page in
 * memory before the run's outputs are written, so that the page is written
 * with them, all or none. Units: mm. One thread.
 */
#ifndef SWARF_CLI_HTML_H
#define SWARF_CLI_HTML_H

#include <stddef.h>

#include "gcode.h"
#include "report.h"
#include "stock.h"
#include "swarf_sim.h"

typedef struct swarf_html swarf_html;

/* What the page shows besides the moves (borrowed for the call). */
typedef struct {
  const char *program;
  const swarf_stock *stock;    /* the remaining material */
  const swarf_stock *design;   /* NULL: none */
  double tolerance;            /* of the design comparison, mm */
  const swarf_sim_config *cfg; /* its tools */
  const swarf_sim_report *report;
  const char *report_json; /* the --report document (report.h), NUL-terminated */
} swarf_html_page;

/* NULL when out of memory, or when swarf was built without three.js
 * (swarf_html_available says which). */
swarf_html *swarf_html_new(void);
int swarf_html_available(void);
void swarf_html_free(swarf_html *h);

/* A move in the workpiece frame at the tool tip (swarf_sim_callbacks.move). */
void swarf_html_add_move(swarf_html *h, const swarf_move *m);

/* The page as bytes (*text, *len: the caller frees *text), built before the
 * outputs are written. SWARF_ERR_MEMORY, or the mesh's error. */
swarf_status swarf_html_render(swarf_html *h, const swarf_html_page *page, char **text, size_t *len,
                               swarf_error *err);

#endif
