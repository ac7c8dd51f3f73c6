/* SPDX-License-Identifier: MPL-2.0 */
/* limits.c -- what a run may take, checked before any work.
 *
 * The arguments (voxel, band, batch), the size of the stock's grid against
 * the memory this process can have, and the threads against an address-space
 * limit: each refused in words with what to give instead, for every client
 * (the command, C, Python), before a byte of the grid is built. Each message
 * starts with the setting's name (voxel, band, batch, stock, threads): the
 * command puts `--` before it to name its flag.
 */
#include <math.h>
#include <stdio.h>
#include <sys/resource.h>
#include <unistd.h>

#include "sim_private.h"

/* Bytes a narrow-band voxel costs at the peak of a run (grid, removal
 * passes, writing): measured with /usr/bin/time on a 40 x 40 x 10 mm box,
 * 0.1 mm to 0.05 mm voxels (2.40 M to 9.59 M active voxels, 84.5 MB to 193 MB:
 * 15.5 bytes a voxel), with a margin. */
#define BYTES_PER_VOXEL 18.0

/* Address space a thread reserves: its stack (8 MiB) and, up to 8 per core,
 * a malloc arena (64 MiB). Under an address-space limit (ulimit -v) too many
 * threads made TBB abort the process; here they are refused in words. */
#define THREAD_RESERVE ((8.0 + 64.0) * 1048576.0)

/* The memory a run may take: 80 % of the physical memory, or of the
 * address-space limit if lower. */
static double memory_budget(void) {
  double phys = (double)sysconf(_SC_PHYS_PAGES) * (double)sysconf(_SC_PAGESIZE);
  struct rlimit as;
  if (!(phys > 0)) phys = 8e9;
  if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY && (double)as.rlim_cur < phys)
    phys = (double)as.rlim_cur;
  return 0.8 * phys;
}

static swarf_status check_args(const swarf_sim_config *cfg, swarf_error *err) {
  if (!(cfg->voxel > 0) || !isfinite(cfg->voxel))
    return swarf_error_set(err, SWARF_ERR_ARG, "voxel: a size in mm > 0 is needed (got %g)",
                           cfg->voxel);
  if (cfg->half_width < 3 || cfg->half_width > 64)
    return swarf_error_set(err, SWARF_ERR_ARG, "band: 3 to 64 voxels (got %d)", cfg->half_width);
  if (cfg->batch < 1)
    return swarf_error_set(err, SWARF_ERR_ARG, "batch: 1 move or more (got %d)", cfg->batch);
  return SWARF_OK;
}

/* A voxel larger than the stock's smallest side cannot hold the stock (the
 * volumes would be off by orders of magnitude); one so small that the band
 * of the stock's surface would not fit in memory is refused with a voxel
 * that fits. */
static swarf_status check_size(const swarf_sim_config *cfg, swarf_error *err) {
  double d[3], smallest, voxels, bytes, budget;
  for (int k = 0; k < 3; k++)
    d[k] = cfg->stock.hi[k] - cfg->stock.lo[k];
  smallest = fmin(d[0], fmin(d[1], d[2]));
  if (smallest < 1e-3)
    return swarf_error_set(err, SWARF_ERR_ARG,
                           "stock: %g mm thick, thinner than the smallest voxel (0.001 mm): no "
                           "grid can hold it",
                           smallest);
  if (cfg->voxel > smallest)
    return swarf_error_set(err, SWARF_ERR_ARG,
                           "voxel %g mm: larger than the stock's smallest side (%g mm): the grid "
                           "cannot hold the stock; give a voxel of %.3g mm or less (a quarter of "
                           "that side or less for usable volumes)",
                           cfg->voxel, smallest, smallest);
  voxels = 2.0 * (d[0] * d[1] + d[1] * d[2] + d[0] * d[2]) / (cfg->voxel * cfg->voxel) * 2.0 *
           cfg->half_width;
  bytes = voxels * BYTES_PER_VOXEL;
  budget = memory_budget();
  if (bytes <= budget) return SWARF_OK;
  if (cfg->voxel * sqrt(bytes / budget) * 1.05 > smallest) /* no voxel fits: the stock's fault */
    return swarf_error_set(err, SWARF_ERR_LIMIT,
                           "stock: %g x %g x %g mm: its surface needs more than the %.3g GB this "
                           "machine can give at any voxel up to its smallest side (%g mm); give "
                           "a smaller stock",
                           d[0], d[1], d[2], budget / 1e9, smallest);
  return swarf_error_set(err, SWARF_ERR_LIMIT,
                         "voxel %g mm: the stock's surface alone would need ~%.3g GB (%.3g M "
                         "voxels at %.0f bytes), more than the %.3g GB this machine can give; "
                         "give a voxel of %.3g mm or more",
                         cfg->voxel, bytes / 1e9, voxels / 1e6, BYTES_PER_VOXEL, budget / 1e9,
                         cfg->voxel * sqrt(bytes / budget) * 1.05);
}

static swarf_status check_threads(const swarf_sim_config *cfg, swarf_error *err) {
  struct rlimit as;
  long pages = 0, page = sysconf(_SC_PAGESIZE);
  FILE *f;
  if (cfg->threads <= 0 || getrlimit(RLIMIT_AS, &as) != 0 || as.rlim_cur == RLIM_INFINITY)
    return SWARF_OK;
  if ((f = fopen("/proc/self/statm", "r")) != NULL) {
    if (fscanf(f, "%ld", &pages) != 1) pages = 0;
    fclose(f);
  }
  const double room = (double)as.rlim_cur - (double)pages * (double)page;
  const long fit = room > 0 ? (long)(room / THREAD_RESERVE) : 0;
  if (cfg->threads > fit)
    return swarf_error_set(err, SWARF_ERR_LIMIT,
                           "threads %d: under this address-space limit (ulimit -v: %.0f MB, "
                           "%.0f MB free) about %ld threads fit, each reserving ~72 MB (stack "
                           "and malloc arena); give %ld or fewer, or raise the limit",
                           cfg->threads, (double)as.rlim_cur / 1e6, room > 0 ? room / 1e6 : 0.0,
                           fit, fit > 1 ? fit - 1 : 1);
  return SWARF_OK;
}

swarf_status swarf_sim_config_check(const swarf_sim_config *cfg, int stock_from_spec,
                                    swarf_error *err) {
  swarf_status st;
  if (cfg == NULL) return swarf_error_set(err, SWARF_ERR_ARG, "swarf_sim_config_check: no config");
  if ((st = check_args(cfg, err)) != SWARF_OK) return st;
  if (stock_from_spec && (st = check_size(cfg, err)) != SWARF_OK) return st;
  return check_threads(cfg, err);
}
