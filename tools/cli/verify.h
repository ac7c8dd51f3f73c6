/* SPDX-License-Identifier: MPL-2.0 */
/* verify.h -- `swarf simulate`'s verification options: the machine's setup
 * (--start, --g54, --offsets, --units), the design (--design, --tolerance,
 * --fail-on gouge) and the JSON report (--report).
 *
 * Role: the part of the command line that turns these options into the
 * driver's configuration, collects what its alarm and line callbacks say,
 * and after the run prints the located warnings (gouges, a missing units
 * word) and the summary lines (start, design, peak removal rate) and writes
 * the report. The caller owns the swarf_verify value; swarf_verify_free
 * releases what it holds. Units: mm. One thread.
 */
#ifndef SWARF_CLI_VERIFY_H
#define SWARF_CLI_VERIFY_H

#include "report.h"
#include "swarf_sim.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SWARF_VERIFY_NOTES 20 /* notes printed after the run; more are counted */

typedef struct {
  /* the options */
  const char *report_path, *design_path, *offsets, *units;
  double tolerance; /* <= 0: half a voxel */
  int fail_on_gouge;
  int start_set, g54_set;
  double start[3], g54[3];
  const char *dialect, *subroutine_path; /* --dialect, --subroutine-path */
  int lines_wanted;                      /* per-line volumes without --report (--html) */
  int block_delete;                      /* --block-delete */
  long work_limit;                       /* --work-limit (0: the default) */
  swarf_design_cache cache;              /* --design-cache, --design-cache-max */
  long notes;                            /* the program's notes (the first ones are kept) */
  char *note_text[SWARF_VERIFY_NOTES];
  /* the inputs as given, for the report */
  const char *stock_spec, *machine_spec;
  const char *tool_specs[SWARF_SIM_MAX_TOOLS];
  int ntools;
  /* what the design is read for (its band: swarf_stock_design_band) */
  const swarf_stock *frame; /* the stock given (NULL: one made at the run's voxel) */
  int views;                /* the design also colours a picture or mesh */
  /* the run */
  swarf_stock *design;
  double design_read_s; /* CPU time (all threads) reading the design, s */
  int design_cached;    /* the design's band came from the cache */
  swarf_report *report;
} swarf_verify;

extern const char swarf_verify_help[];

/* Option `flag` with value `val` (NULL if none) at argv[*i]: 0 taken (*i
 * past its value), 2 bad (the message on stderr names the flag), -1 not
 * one of these. Also records --stock, --tool and --machine for the report
 * (returning -1: the caller handles them). */
int swarf_verify_option(swarf_verify *v, const char *flag, const char *val, int *i);

/* Before the run: refuses an unwritable --report folder, reads the design at
 * the stock's voxel with the band its uses need (frame, views, tolerance),
 * puts the setup and design into cfg. 0, or the exit
 * status (2 bad input, 1 internal) after a message. */
int swarf_verify_prepare(swarf_verify *v, swarf_sim_config *cfg);

/* The driver's callbacks call these. */
void swarf_verify_alarm(swarf_verify *v, const swarf_alarm *a);
void swarf_verify_line(swarf_verify *v, const swarf_line_result *l);
void swarf_verify_note(swarf_verify *v, long line, int column, const char *text);

/* After a successful run: the warnings on stderr (a move before any units
 * word unless --units was given; one gouge a program line, deepest first of
 * its moves, in line order). */
void swarf_verify_warn(swarf_verify *v, const char *program, const swarf_sim_report *r);

/* The summary's lines (start, design comparison, peak removal rate). */
void swarf_verify_summary(swarf_verify *v, const swarf_sim_report *r);

/* Writes --report if asked (into the output group the caller opened with
 * swarf_stock_outputs_begin: published with the .vdb and mesh, or not at
 * all): 0, or 1 when it cannot be written (the message is printed). */
int swarf_verify_write_report(swarf_verify *v, const char *program, const swarf_sim_config *cfg,
                              const swarf_sim_report *r);

/* The report's document as compact JSON (the caller frees it), or NULL
 * when out of memory (err says so): for the --html page. */
char *swarf_verify_report_text(swarf_verify *v, const char *program, const swarf_sim_config *cfg,
                               const swarf_sim_report *r, swarf_error *err);

/* The exit status after the outputs: 0, or 4 (--fail-on gouge and a gouge
 * was found). */
int swarf_verify_finish(const swarf_verify *v, const swarf_sim_report *r);

void swarf_verify_free(swarf_verify *v);

#ifdef __cplusplus
}
#endif
#endif
