/* SPDX-License-Identifier: MPL-2.0 */
/// @file remove.cc
/// @brief Removal of volumes from the stock: stock = max(stock, -sdf), written
/// directly into the stock's leaves, one leaf-aligned block of 8^3 voxels at a
/// time (the hot path of the simulator; csgDifference is ten times slower).
///
/// A cut is a volume {sdf < 0} inside world bounds [lo, hi] (mm); its sdf is
/// 1-Lipschitz, so the sdf at a block's centre bounds it on the whole block.
/// With r = the block's half diagonal (3.5 sqrt(3) voxels) and w = the band
/// half-width (the grid's background, mm), a block is
///  - untouched by a cut if sdf_centre > r + w: every voxel keeps its value;
///  - cleared if -sdf_centre > r + w: every voxel becomes outside (+w, inactive);
///  - visited otherwise: each voxel takes max(old, -sdf(voxel centre)).
///
/// Passes (one call, any number of cuts):
///  1. list_pairs: the (block, cut) pairs, blocks meeting a cut's bounds padded
///     by the band and lying in the stock's content box; sorted by block.
///  2. classify (parallel, read-only tree): blocks entirely outside the stock
///     are skipped; the others are classified from their cuts' centre values.
///  3. serial topology: cleared blocks become outside tiles.
///  4. visit (parallel, one leaf per task, no topology change), top down:
///     each cut's sdf at the block centre, then, octant by octant and cube by
///     cube with all their cuts, at the 4^3 octants' and 2^3 cubes' centres
///     where the voxels below them may change, and at a voxel only where the
///     bound from its cube's centre cannot decide (1.4x fewer sdf calls on the
///     impeller; a cut whose cube centre lies deeper than the band plus a
///     margin clears the cube's voxels without evaluation). Per-octant and
///     per-cube summaries of the values (min of value - distance to the
///     centre) decide for a cut without looking at the voxels, and a cube's
///     cuts are applied deepest first, so that the others mostly find the
///     voxels already above their bound (tiger.nc: 2x fewer raised voxels).
///     A block that is a tile is visited in a per-thread leaf densified from
///     the tile's value and copied into a leaf of its own only if it does not
///     collapse (a roughing empties most such blocks: the impeller at 0.1 mm
///     with 1024-move batches peaked at ~800 MB when every one became a leaf).
///  5. serial: visited leaves left without any band collapse back into tiles,
///     the tiles' new leaves go into the tree.
///
/// Voxel values stay in [-w, w]; a voxel is active iff |value| < w, inactive
/// voxels hold exactly +-w: the narrow band stays valid without a flood fill.
/// Every voxel ends at float(clamp(max(old, -sdf_1, ..., -sdf_n))), whatever the
/// order of the cuts or their grouping into batches (rounding and clamping are
/// monotone), so results are bit-identical between orders and batchings.
#include <openvdb/tree/ValueAccessor.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <utility>

#include "stock_private.h"
#include "swarf_reference.h"

#include "remove_pass.h"

namespace swarf {
namespace removal {

/// Measured: the pairs' findings added up per cut, in pair order (deterministic).
void report_effects(const Pass &p, size_t ncuts) {
  const RemoveScratch &w = p.s.scratch;
  swarf_stock_cut_effect *e = p.measure->effects;
  const double nan = std::numeric_limits<double>::quiet_NaN(), v3 = p.voxel * p.voxel * p.voxel;
  std::vector<double> removed(ncuts, 0.0);
  for (size_t i = 0; i < ncuts; i++)
    e[i].removed = e[i].removed_voxels = 0.0, e[i].gouge_depth = 0.0,
    e[i].gouge_at[0] = e[i].gouge_at[1] = e[i].gouge_at[2] = nan;
  for (const Block &b : w.blocks)
    for (uint32_t i = b.begin; i < b.begin + b.count; i++) {
      if (b.action == kSkip) break;
      swarf_stock_cut_effect &c = e[w.pairs[i].cut];
      // whole multiples of 2^-16 voxel: sums exact in any order or grouping
      // (up to 2^37 voxels a cut), so parts of a stock add up to the same bits
      removed[w.pairs[i].cut] += std::ldexp(std::round(std::ldexp(w.removed[i], 16)), -16);
      if (w.gouge[i] > c.gouge_depth) {
        c.gouge_depth = w.gouge[i];
        for (int k = 0; k < 3; k++)
          c.gouge_at[k] = w.gouge_at[i][k];
      }
    }
  if (!p.measure->volumes) return; // gouges only: no volumes (left 0)
  for (size_t i = 0; i < ncuts; i++)
    e[i].removed_voxels = removed[i], e[i].removed = removed[i] * v3;
}

/// Runs a parallel pass in chunks when the stock has a tick
/// (swarf_stock_set_tick): between chunks, on the calling thread with no
/// worker running (the stock is a valid narrow band then), the tick is told
/// the fraction done once `every` seconds have passed since the last call;
/// chunks aim at a fifth of that. A non-zero answer stops the pass (ABORTED):
/// the stock stays valid, partly cut.
struct Ticker {
  swarf_stock &s;
  size_t total;
  double last;
  Ticker(swarf_stock &st, size_t n) : s(st), total(n), last(now()) {}
  static double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }
  /// Items [first, first + n) of the pass's total (as numbered by body).
  template <class Body> void run(size_t first, size_t n, size_t grain, const Body &body) {
    if (s.tick == nullptr) {
      tbb::parallel_for(tbb::blocked_range<size_t>(first, first + n, grain), body);
      return;
    }
    const double aim = s.tick_every > 0 ? 0.2 * s.tick_every : 0.0;
    size_t chunk = 64;
    for (size_t at = first; at < first + n;) {
      const size_t end = std::min(first + n, at + chunk);
      const double t0 = now();
      tbb::parallel_for(tbb::blocked_range<size_t>(at, end, grain), body);
      const double t1 = now(), took = t1 - t0;
      at = end;
      if (aim > 0 && took > 0) // next chunk: about `aim` seconds, within 16x of this one
        chunk = std::max<size_t>(
            grain, size_t(double(chunk) * std::min(16.0, std::max(1.0 / 16, aim / took))));
      if (t1 - last < s.tick_every) continue;
      last = t1;
      if (s.tick(s.tick_user, total ? double(at) / double(total) : 1.0) != 0)
        throw Error(SWARF_ERR_ABORTED, "removal stopped by the caller");
    }
  }
};

/// Pass 5: leaves without band become tiles, serial.
void collapse(Pass &p) {
  RemoveScratch &w = p.s.scratch;
  Tree &tree = p.s.grid->tree();
  for (size_t i = 0; i < w.visit.size(); i++) {
    const Block &b = w.blocks[w.visit[i]];
    if (b.action == kCollapse)
      tree.addTile(1, b.origin, b.tile, false);
    else if (w.fresh[i])
      tree.addLeaf(w.fresh[i].release());
  }
}

/// Check one cut: an sdf, finite bounds, lo < hi on every axis.
void check_cut(const swarf_stock_cut &c, size_t i) {
  const std::string at = "cut " + std::to_string(i) + ": ";
  if (c.sdf == nullptr) throw swarf::Error(SWARF_ERR_ARG, at + "sdf is NULL");
  for (int k = 0; k < 3; k++) {
    if (!std::isfinite(c.lo[k]) || !std::isfinite(c.hi[k]))
      throw swarf::Error(SWARF_ERR_ARG, at + "bounds are not finite");
    if (!(c.lo[k] < c.hi[k])) throw swarf::Error(SWARF_ERR_ARG, at + "bounds need lo < hi");
  }
}

} // namespace removal

using namespace removal;

void remove_cuts(swarf_stock &s, const swarf_stock_cut *cuts, size_t ncuts, const Measure *measure,
                 const swarf_stock_support_fn *support) {
  const bool plain = swarf_reference_on(SWARF_REFERENCE_REMOVE_PLAIN);
  const bool flat = swarf_reference_on(SWARF_REFERENCE_REMOVE_FLAT);
  Pass p{s, cuts, s.voxel, s.background, 0.0, {}, {}, {}, measure, flat, plain, support};
  init_pass(p);
  RemoveScratch &w = s.scratch;
  list_pairs(p, ncuts);
  if (w.blocks.empty()) {
    if (measure) report_effects(p, ncuts);
    return;
  }
  const Tree &ctree = s.grid->constTree();
  Ticker ticker(s, w.blocks.size() + w.blocks.size());
  ticker.run(0, w.blocks.size(), 16, [&](const tbb::blocked_range<size_t> &r) {
    ConstAcc acc(ctree);
    std::unique_ptr<ConstAcc> dacc;
    if (measure && measure->design && GridProbe::lattices_coincide(*measure->design, s))
      dacc.reset(new ConstAcc(measure->design->grid->constTree()));
    for (size_t i = r.begin(); i != r.end(); ++i)
      classify(p, acc, w.blocks[i], dacc.get());
  });
  change_topology(p);
  Tree &tree = s.grid->tree();
  w.fresh.clear(); // (an aborted pass's leftovers)
  w.fresh.resize(w.visit.size());
  ticker.total = w.blocks.size() + w.visit.size();
  ticker.run(w.blocks.size(), w.visit.size(), 1, [&](const tbb::blocked_range<size_t> &r0) {
    const tbb::blocked_range<size_t> r(r0.begin() - w.blocks.size(), r0.end() - w.blocks.size());
    Acc acc(tree);
    std::unique_ptr<GridProbe> design;
    std::unique_ptr<ConstAcc> dacc;
    if (measure && measure->design) design.reset(new GridProbe(*measure->design, s));
    if (design && design->aligned()) dacc.reset(new ConstAcc(measure->design->grid->constTree()));
    for (size_t i = r.begin(); i != r.end(); ++i)
      visit_block(p, acc, w.blocks[w.visit[i]], design.get(), dacc.get(), w.fresh[i]);
  });
  collapse(p);
  if (measure) report_effects(p, ncuts);
}

} // namespace swarf

extern "C" swarf_status swarf_stock_remove(swarf_stock *s, const double lo[3], const double hi[3],
                                           swarf_stock_sdf_fn sdf, const void *ctx,
                                           swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || lo == nullptr || hi == nullptr)
      throw swarf::Error(SWARF_ERR_ARG, "stock, lo or hi is NULL");
    swarf_stock_cut cut{};
    for (int k = 0; k < 3; k++)
      cut.lo[k] = lo[k], cut.hi[k] = hi[k];
    cut.sdf = sdf;
    cut.ctx = ctx;
    swarf::removal::check_cut(cut, 0);
    swarf::in_arena(*s, [&] { swarf::remove_cuts(*s, &cut, 1); });
  });
}

extern "C" swarf_status swarf_stock_remove_batch(swarf_stock *s, const swarf_stock_cut *cuts,
                                                 size_t ncuts, swarf_error *err) {
  return swarf_stock_remove_batch_support(s, cuts, nullptr, ncuts, err);
}

extern "C" swarf_status swarf_stock_remove_batch_support(swarf_stock *s,
                                                         const swarf_stock_cut *cuts,
                                                         const swarf_stock_support_fn *support,
                                                         size_t ncuts, swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr) throw swarf::Error(SWARF_ERR_ARG, "stock is NULL");
    if (ncuts == 0) return;
    if (cuts == nullptr) throw swarf::Error(SWARF_ERR_ARG, "cuts is NULL");
    if (ncuts > UINT32_MAX) throw swarf::Error(SWARF_ERR_ARG, "too many cuts in one batch");
    for (size_t i = 0; i < ncuts; i++)
      swarf::removal::check_cut(cuts[i], i);
    swarf::in_arena(*s, [&] { swarf::remove_cuts(*s, cuts, ncuts, nullptr, support); });
  });
}

extern "C" swarf_status
swarf_stock_remove_batch_measured(swarf_stock *s, const swarf_stock_cut *cuts, size_t ncuts,
                                  const swarf_stock *design, double tolerance,
                                  swarf_stock_cut_effect *effects, swarf_error *err) {
  return swarf_stock_remove_batch_measured_support(s, cuts, nullptr, ncuts, design, tolerance,
                                                   effects, err);
}

namespace {

swarf_status remove_measured(swarf_stock *s, const swarf_stock_cut *cuts,
                             const swarf_stock_support_fn *support, size_t ncuts,
                             const swarf_stock *design, double tolerance,
                             swarf_stock_cut_effect *effects, bool volumes, swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr) throw swarf::Error(SWARF_ERR_ARG, "stock is NULL");
    if (ncuts == 0) return;
    if (cuts == nullptr || effects == nullptr)
      throw swarf::Error(SWARF_ERR_ARG, "cuts or effects is NULL");
    if (ncuts > UINT32_MAX) throw swarf::Error(SWARF_ERR_ARG, "too many cuts in one batch");
    if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
      throw swarf::Error(SWARF_ERR_ARG, "tolerance must be finite and >= 0");
    for (size_t i = 0; i < ncuts; i++)
      swarf::removal::check_cut(cuts[i], i);
    swarf::Measure m{design, tolerance, effects};
    m.volumes = volumes;
    if (!volumes && design == nullptr) { // nothing to measure: the plain removal
      const double nan = std::numeric_limits<double>::quiet_NaN();
      for (size_t i = 0; i < ncuts; i++)
        effects[i] = {0.0, 0.0, 0.0, {nan, nan, nan}};
      swarf::in_arena(*s, [&] { swarf::remove_cuts(*s, cuts, ncuts, nullptr, support); });
      return;
    }
    swarf::in_arena(*s, [&] { swarf::remove_cuts(*s, cuts, ncuts, &m, support); });
  });
}

} // namespace

extern "C" swarf_status
swarf_stock_remove_batch_measured_support(swarf_stock *s, const swarf_stock_cut *cuts,
                                          const swarf_stock_support_fn *support, size_t ncuts,
                                          const swarf_stock *design, double tolerance,
                                          swarf_stock_cut_effect *effects, swarf_error *err) {
  return remove_measured(s, cuts, support, ncuts, design, tolerance, effects, true, err);
}

extern "C" swarf_status
swarf_stock_remove_batch_gouges_support(swarf_stock *s, const swarf_stock_cut *cuts,
                                        const swarf_stock_support_fn *support, size_t ncuts,
                                        const swarf_stock *design, double tolerance,
                                        swarf_stock_cut_effect *effects, swarf_error *err) {
  return remove_measured(s, cuts, support, ncuts, design, tolerance, effects, false, err);
}
