/* SPDX-License-Identifier: MPL-2.0 */
/* slab.c -- the simulation on several processes (swarf_sim_comm in
 * swarf_sim.h): slabs planned from the work a survey of the program
 * estimates, queries and measured effects combined across processes, the
 * slabs gathered into rank 0's stock at finish.
 *
 * The stock's index space is cut into columns of whole 8-voxel blocks (the
 * unit of removal, stock/remove.cc) across its two longest axes, and the
 * columns into one rectangle a process by recursive bisection, balancing
 * the estimated work. A survey handle (a second handle on the same config
 * with a token stock) plays the program without removing anything and
 * adds, for each cut, the blocks its padded bounds cover to their columns:
 * the work estimate (block and cut pairs, what removal's cost follows).
 * Every process computes the same plan from the same program, with no
 * message.
 *
 * A process other than rank 0 whose stock is a box or cylinder spec builds
 * it at the plan, in its slab only (sim.c, swarf_sim_slab_stock): until then
 * a shell with the whole stock's index box, which is all the plan reads.
 * Stocks read from files (and rank 0's, which gathers the whole) are built
 * whole, then cropped to the slab.
 *
 * Exactness: removal is per block, so the slabs' blocks are the one-process
 * run's; a query's first hit is the minimum of the processes' first hits in
 * the stock's scan order (blocks x, y, z, then voxels x, y, z: remove.cc's
 * loops), a gouge the deepest with ties to the first in that order, a cut's
 * volume the sum of the slabs' (exact: stock.h's removed_voxels).
 */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sim_private.h"

int swarf_sim_slabs(const swarf_sim *s) {
  return s->cfg.comm != NULL && s->cfg.comm->size > 1;
}

void swarf_sim_slab_clear(swarf_sim *s) {
  free(s->work);
  free(s->tally);
  s->work = NULL;
  s->tally = NULL;
}

/* ---- The plan --------------------------------------------------------------- */

/* Columns of blocks across the index box's two longest axes (ax[0], ax[1]):
 * each rank gets a rectangle of them, through the whole third axis. */
static int plan_columns(swarf_sim *s) {
  int lo[3], hi[3];
  swarf_stock_index_box(s->stock, lo, hi);
  for (int k = 0; k < 3; k++) {
    s->blo[k] = lo[k] & ~7;
    s->nb[k] = hi[k] < lo[k] ? 1 : ((hi[k] & ~7) - s->blo[k]) / 8 + 1;
    s->index_lo[k] = lo[k];
    s->index_hi[k] = hi[k];
  }
  int shortest = 0;
  for (int k = 1; k < 3; k++)
    if (s->nb[k] < s->nb[shortest]) shortest = k;
  s->ax[0] = shortest == 0 ? 1 : 0;
  s->ax[1] = shortest == 2 ? 1 : 2;
  const size_t ncol = (size_t)s->nb[s->ax[0]] * (size_t)s->nb[s->ax[1]];
  s->work = calloc(ncol, sizeof *s->work);
  if (s->cfg.tally) s->tally = calloc(ncol * (size_t)s->nb[shortest], sizeof *s->tally);
  if (s->work == NULL || (s->cfg.tally && s->tally == NULL)) {
    swarf_sim_fail(s, SWARF_ERR_MEMORY, 0, 0, "out of memory");
    return 1;
  }
  return 0;
}

void swarf_sim_slab_survey(swarf_sim *s, const swarf_stock_cut *c) {
  swarf_sim *p = s->surveyor;
  const double pad = swarf_stock_half_width(p->stock) + 2.0;
  int a[3], b[3], n = 1, third = 3 - p->ax[0] - p->ax[1];
  double lo[3], hi[3];
  for (int k = 0; k < 3; k++) {
    lo[k] = c->lo[k] - pad * s->cfg.voxel;
    hi[k] = c->hi[k] + pad * s->cfg.voxel;
  }
  swarf_stock_index_of(p->stock, lo, a);
  swarf_stock_index_of(p->stock, hi, b);
  for (int k = 0; k < 3; k++) { /* block numbers within the index box */
    a[k] = ((a[k] > p->index_lo[k] ? a[k] : p->index_lo[k]) & ~7) - p->blo[k];
    b[k] = ((b[k] < p->index_hi[k] ? b[k] : p->index_hi[k]) & ~7) - p->blo[k];
    if (a[k] > b[k]) return;
    a[k] /= 8, b[k] /= 8;
  }
  n = b[third] - a[third] + 1;
  for (int i = a[p->ax[0]]; i <= b[p->ax[0]]; i++)
    for (int j = a[p->ax[1]]; j <= b[p->ax[1]]; j++)
      p->work[(size_t)i * (size_t)p->nb[p->ax[1]] + (size_t)j] += n;
}

/* A survey of the program at `path`: a handle on the same config that
 * removes nothing, its token stock at the material's corner. */
static int survey(swarf_sim *s, const char *path) {
  swarf_sim_config cfg = s->cfg;
  swarf_stock *token = NULL;
  swarf_sim *v = NULL;
  swarf_error e;
  double hi[3];
  for (int k = 0; k < 3; k++)
    hi[k] = s->mat_lo[k] + 4 * s->cfg.voxel;
  memset(&cfg.cb, 0, sizeof cfg.cb);
  cfg.comm = NULL;
  cfg.tally = 0;
  cfg.design = NULL;
  cfg.line_volumes = 0;
  cfg.nfixtures = 0;
  cfg.start_set = 1;
  memcpy(cfg.start, s->rep.start, sizeof cfg.start);
  swarf_error_init(&e);
  if (swarf_stock_new_box(s->mat_lo, hi, s->cfg.voxel, 3, &token, &e) != SWARF_OK ||
      swarf_sim_new_with_stock(&cfg, s->name, token, &v, &e) != SWARF_OK) {
    swarf_sim_fail(s, e.status, 0, 0, "%s", e.message);
    return 1;
  }
  v->surveyor = s;
  memcpy(v->pad_lo, s->pad_lo, sizeof v->pad_lo);
  memcpy(v->pad_hi, s->pad_hi, sizeof v->pad_hi);
  swarf_status st = swarf_sim_feed_file(v, path);
  if (st == SWARF_OK) st = swarf_sim_finish(v);
  if (st != SWARF_OK) { /* the run would fail there too: the same error */
    s->err = v->err;
    s->state = SIM_FAILED;
  }
  swarf_sim_free(v);
  return st != SWARF_OK;
}

/* A rectangle of columns [lo, hi) on ax[0], ax[1]; empty when lo == hi. */
typedef struct {
  int lo[2], hi[2];
} slab_box;

/* Work of the columns of slice `c` across axis d of box b (plus a floor a
 * column, so that columns nobody cuts still spread). */
static double slice_work(const swarf_sim *s, const slab_box *b, int d, int c, double floor_w) {
  double w = 0;
  for (int o = b->lo[1 - d]; o < b->hi[1 - d]; o++) {
    const int i = d == 0 ? c : o, j = d == 0 ? o : c;
    w += s->work[(size_t)i * (size_t)s->nb[s->ax[1]] + (size_t)j] + floor_w;
  }
  return w;
}

/* Recursive bisection: ranks [r0, r1) share box b, split across its longer
 * side where the work divides as the ranks do. */
static void bisect(const swarf_sim *s, slab_box b, int r0, int r1, double floor_w, slab_box *out) {
  const int n = r1 - r0, na = n / 2;
  int d = b.hi[0] - b.lo[0] >= b.hi[1] - b.lo[1] ? 0 : 1;
  if (n == 1) {
    out[r0] = b;
    return;
  }
  if (b.hi[d] - b.lo[d] < 2) { /* one column: the first rank takes it */
    out[r0] = b;
    for (int r = r0 + 1; r < r1; r++)
      out[r] = (slab_box){{0, 0}, {0, 0}};
    return;
  }
  double total = 0, sum = 0, best = -1;
  for (int c = b.lo[d]; c < b.hi[d]; c++)
    total += slice_work(s, &b, d, c, floor_w);
  const double target = total * na / n;
  int cut = b.lo[d] + 1;
  for (int c = b.lo[d]; c < b.hi[d] - 1; c++) {
    sum += slice_work(s, &b, d, c, floor_w);
    const double miss = sum > target ? sum - target : target - sum;
    if (best < 0 || miss < best) best = miss, cut = c + 1;
  }
  slab_box a = b, z = b;
  a.hi[d] = cut;
  z.lo[d] = cut;
  bisect(s, a, r0, r0 + na, floor_w, out);
  bisect(s, z, r0 + na, r1, floor_w, out);
}

/* Each rank's rectangle for `nranks` ranks; NULL when out of memory. */
static slab_box *plan(const swarf_sim *s, int nranks) {
  slab_box *out = malloc(sizeof *out * (size_t)nranks), all = {{0, 0}, {0, 0}};
  const size_t ncol = (size_t)s->nb[s->ax[0]] * (size_t)s->nb[s->ax[1]];
  double total = 0;
  if (out == NULL) return NULL;
  for (size_t i = 0; i < ncol; i++)
    total += s->work[i];
  all.hi[0] = s->nb[s->ax[0]];
  all.hi[1] = s->nb[s->ax[1]];
  bisect(s, all, 0, nranks, 1e-3 * total / (double)ncol + 1e-9, out);
  return out;
}

static int set_region(swarf_sim *s, const slab_box *b) {
  int lo[3], hi[3];
  swarf_error e;
  for (int k = 0; k < 3; k++)
    lo[k] = -(1 << 30), hi[k] = 1 << 30;
  for (int d = 0; d < 2; d++) {
    const int k = s->ax[d];
    if (b->lo[d] == b->hi[d]) { /* nothing: a block beyond any stock */
      lo[k] = hi[k] = INT_MAX & ~7;
      continue;
    }
    if (b->lo[d] > 0) lo[k] = s->blo[k] + 8 * b->lo[d];
    if (b->hi[d] < s->nb[k]) hi[k] = s->blo[k] + 8 * b->hi[d] - 1;
  }
  if (s->slab_build) return swarf_sim_slab_stock(s, lo, hi); /* built in its slab only */
  if (swarf_stock_set_region(s->stock, lo, hi, &e) != SWARF_OK ||
      swarf_stock_slab_crop(s->stock, &e) != SWARF_OK) { /* memory: this slab only */
    swarf_sim_fail(s, SWARF_ERR_INTERNAL, 0, 0, "%s", e.message);
    return 1;
  }
  return 0;
}

int swarf_sim_slab_plan(swarf_sim *s, const char *path) {
  int rc = 0;
  if (s->planned || s->surveyor != NULL) return 0;
  s->planned = 1;
  if (!swarf_sim_slabs(s) && !s->cfg.tally) return 0;
  if (plan_columns(s) != 0 || (path != NULL && survey(s, path) != 0)) return 1;
  if (swarf_sim_slabs(s)) {
    slab_box *b = plan(s, s->cfg.comm->size);
    if (b == NULL) return swarf_sim_fail(s, SWARF_ERR_MEMORY, 0, 0, "out of memory"), 1;
    rc = set_region(s, &b[s->cfg.comm->rank]); /* may build the stock: the tally after */
    free(b);
  }
  if (rc == 0 && s->cfg.tally) swarf_stock_set_tally(s->stock, s->blo, s->nb, s->tally);
  return rc;
}

swarf_status swarf_sim_balance(const swarf_sim *s, int nranks, double *max_over_mean,
                               double *visited) {
  if (s == NULL || nranks < 1 || max_over_mean == NULL) return SWARF_ERR_ARG;
  if (s->tally == NULL || s->work == NULL) return SWARF_ERR_STATE;
  slab_box *b = plan(s, nranks);
  double most = 0, total = 0;
  if (b == NULL) return SWARF_ERR_MEMORY;
  for (int r = 0; r < nranks; r++) {
    double w = 0;
    int lo[3] = {0, 0, 0}, hi[3] = {s->nb[0], s->nb[1], s->nb[2]};
    for (int d = 0; d < 2; d++)
      lo[s->ax[d]] = b[r].lo[d], hi[s->ax[d]] = b[r].hi[d];
    for (int i = lo[0]; i < hi[0]; i++)
      for (int j = lo[1]; j < hi[1]; j++)
        for (int k = lo[2]; k < hi[2]; k++)
          w += 512.0 * (double)s->tally[((size_t)i * s->nb[1] + j) * s->nb[2] + k];
    total += w;
    if (w > most) most = w;
  }
  free(b);
  if (visited != NULL) *visited = total;
  *max_over_mean = total > 0 ? most / (total / nranks) : 1.0;
  return SWARF_OK;
}

/* ---- Combining ------------------------------------------------------------- */

static int comm_failed(swarf_sim *s) {
  swarf_sim_fail(s, SWARF_ERR_INTERNAL, 0, 0, "the processes could not exchange their results");
  return 1;
}

/* Position in the stock's scan order of the voxel at world point p. */
static void scan_key(const swarf_sim *s, const double p[3], int key[6]) {
  int ijk[3];
  swarf_stock_index_of(s->stock, p, ijk);
  for (int k = 0; k < 3; k++) {
    key[k] = ijk[k] >> 3;
    key[3 + k] = ijk[k] & 7;
  }
}

static int key_less(const int a[6], const int b[6]) {
  for (int k = 0; k < 6; k++)
    if (a[k] != b[k]) return a[k] < b[k];
  return 0;
}

typedef struct {
  int hit, key[6];
  double where[3];
} slab_hit;

int swarf_sim_slab_hit(swarf_sim *s, int *hit, double where[3]) {
  const swarf_sim_comm *c = s->cfg.comm;
  slab_hit mine, *all;
  int best = -1;
  if (!swarf_sim_slabs(s)) return 0;
  memset(&mine, 0, sizeof mine);
  mine.hit = *hit;
  if (*hit) {
    memcpy(mine.where, where, sizeof mine.where);
    scan_key(s, where, mine.key);
  }
  if ((all = malloc(sizeof *all * (size_t)c->size)) == NULL)
    return swarf_sim_fail(s, SWARF_ERR_MEMORY, 0, 0, "out of memory"), 1;
  if (c->allgather(c->user, &mine, sizeof mine, all) != 0) return free(all), comm_failed(s);
  for (int r = 0; r < c->size; r++)
    if (all[r].hit && (best < 0 || key_less(all[r].key, all[best].key))) best = r;
  *hit = best >= 0;
  if (best >= 0) memcpy(where, all[best].where, sizeof all[best].where);
  free(all);
  return 0;
}

typedef struct {
  double voxels, depth, at[3];
  int key[6];
} slab_effect;

int swarf_sim_slab_effects(swarf_sim *s, swarf_stock_cut_effect *e, int n) {
  const swarf_sim_comm *c = s->cfg.comm;
  const double v3 = s->cfg.voxel * s->cfg.voxel * s->cfg.voxel;
  slab_effect *mine, *all;
  if (!swarf_sim_slabs(s) || n == 0) return 0;
  mine = calloc((size_t)n, sizeof *mine);
  all = calloc((size_t)n * (size_t)c->size, sizeof *all);
  if (mine == NULL || all == NULL)
    return free(mine), free(all), swarf_sim_fail(s, SWARF_ERR_MEMORY, 0, 0, "out of memory"), 1;
  for (int i = 0; i < n; i++) {
    mine[i].voxels = e[i].removed_voxels;
    mine[i].depth = e[i].gouge_depth;
    memcpy(mine[i].at, e[i].gouge_at, sizeof mine[i].at);
    if (e[i].gouge_depth > 0) scan_key(s, e[i].gouge_at, mine[i].key);
  }
  if (c->allgather(c->user, mine, sizeof *mine * (size_t)n, all) != 0)
    return free(mine), free(all), comm_failed(s);
  for (int i = 0; i < n; i++) {
    const slab_effect *best = NULL;
    double voxels = 0;
    for (int r = 0; r < c->size; r++) {
      const slab_effect *f = &all[(size_t)r * (size_t)n + (size_t)i];
      voxels += f->voxels; /* whole multiples of 2^-16: exact */
      if (f->depth > 0 && (best == NULL || f->depth > best->depth ||
                           (f->depth == best->depth && key_less(f->key, best->key))))
        best = f;
    }
    e[i].removed_voxels = voxels;
    e[i].removed = voxels * v3;
    e[i].gouge_depth = best != NULL ? best->depth : 0.0;
    for (int k = 0; k < 3; k++)
      e[i].gouge_at[k] = best != NULL ? best->at[k] : NAN;
  }
  free(mine);
  free(all);
  return 0;
}

int swarf_sim_slab_sync(swarf_sim *s) {
  const swarf_sim_comm *c = s->cfg.comm;
  int *all, stop = 0;
  if (!swarf_sim_slabs(s)) return 0;
  if ((all = malloc(sizeof *all * (size_t)c->size)) == NULL)
    return swarf_sim_fail(s, SWARF_ERR_MEMORY, 0, 0, "out of memory"), 1;
  if (c->allgather(c->user, &s->abort_pending, sizeof s->abort_pending, all) != 0)
    return free(all), comm_failed(s);
  for (int r = 0; r < c->size; r++)
    stop |= all[r];
  free(all);
  if (!stop) return 0;
  swarf_sim_fail(s, SWARF_ERR_ABORTED, s->cur.line, 0, "aborted by the caller");
  return 1;
}

/* ---- The gathering ---------------------------------------------------------- */

static int take_slab(void *ctx, int rank, const void *buf, size_t n) {
  swarf_sim *s = ctx;
  swarf_error e;
  (void)rank;
  if (swarf_stock_slab_load(s->stock, buf, n, &e) == SWARF_OK) return 0;
  swarf_sim_fail(s, SWARF_ERR_INTERNAL, 0, 0, "gathering the stock: %s", e.message);
  return 1;
}

int swarf_sim_slab_merge(swarf_sim *s) {
  const swarf_sim_comm *c = s->cfg.comm;
  void *buf = NULL;
  size_t n = 0;
  swarf_error e;
  int rc;
  if (!swarf_sim_slabs(s)) return 0;
  if (c->rank != 0 && swarf_stock_slab_save(s->stock, &buf, &n, &e) != SWARF_OK) {
    /* the others wait in the gathering: stop them all (the caller's transport) */
    swarf_sim_fail(s, SWARF_ERR_INTERNAL, 0, 0, "saving the stock's slab: %s", e.message);
    c->gather(c->user, NULL, 0, take_slab, s);
    return 1;
  }
  rc = c->gather(c->user, buf, n, take_slab, s);
  free(buf);
  if (rc != 0 && s->err.status == SWARF_OK) return comm_failed(s);
  if (s->err.status != SWARF_OK) return 1;
  if (c->rank == 0) swarf_stock_set_region(s->stock, NULL, NULL, NULL);
  return 0;
}
