/* SPDX-License-Identifier: MPL-2.0 */
/* cli_stock.h -- the stock side of the command line: stocks from files
 * (`--stock stl:FILE`, `--stock vdb:FILE`), their placement for a setup
 * (`--stock-transform`), outputs by format (--mesh .stl/.obj/.ply, --image
 * with --view, coloured by a design), and `swarf compare`.
 *
 * Role: turns these options into stock.h calls for `swarf simulate`
 * (cli_simulate.c), `swarf render` and `swarf compare`. Messages go to
 * stderr and name the flag; functions return an exit status (0 ok, 2 bad
 * input, 1 internal). Units mm and degrees. One thread.
 */
#ifndef SWARF_CLI_STOCK_H
#define SWARF_CLI_STOCK_H

#include "stock.h"
#include "swarf_sim.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  const char *file; /* --stock stl:FILE or vdb:FILE; NULL: box or cylinder */
  int is_vdb;
  int place_set; /* --stock-transform given */
  swarf_stock_placement place;
  int voxel_given; /* --voxel given */
  swarf_stock_view view;
} swarf_cli_stock;

extern const char swarf_cli_stock_help[];

/* Option `flag` with value `val` (NULL if none) at argv[*i]: 0 taken (*i
 * past its value), 2 bad (message on stderr), -1 not one of these (also for
 * --voxel and box:/cylinder: stocks, which it notes and leaves to the
 * caller). */
int swarf_cli_stock_option(swarf_cli_stock *c, const char *flag, const char *val, int *i);

/* 2 with a message unless `path` (may be NULL) names a mesh format. */
int swarf_cli_mesh_name(const char *flag, const char *path);

/* The initial stock when it is not the driver's to make (a file, or a box or
 * cylinder to place): *out is the new stock, NULL when the driver makes it
 * from cfg->stock; cfg->voxel becomes the stock's. Returns the exit status. */
int swarf_cli_stock_make(const swarf_cli_stock *c, swarf_sim_config *cfg, swarf_stock **out);

/* swarf_sim_run on `stock` (owned; NULL: the driver's own from cfg). With
 * balance >= 2 (and cfg->tally) it prints after the run how evenly 2 to
 * `balance` processes would have shared the removal (swarf_sim_balance). */
swarf_status swarf_cli_run(const swarf_sim_config *cfg, const char *program, swarf_stock *stock,
                           int balance, swarf_stock **out, swarf_sim_report *rep, swarf_error *err);

/* The mesh (format by extension) and picture (may be NULL) of `s`, coloured
 * by `design` (may be NULL) with `tolerance` (<= 0: half a voxel). *ntri gets
 * the mesh's triangles. Messages start with `cmd`. */
int swarf_cli_write_views(const char *cmd, const swarf_stock *s, const char *mesh,
                          const char *image, const swarf_stock *design, double tolerance,
                          swarf_stock_view view, size_t *ntri);

/* `swarf compare A.vdb B.vdb|B.stl ...` */
int swarf_cli_compare(int argc, char **argv);

#ifdef __cplusplus
}
#endif
#endif
