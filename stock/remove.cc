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

namespace swarf {
namespace {

using openvdb::Coord;
using openvdb::Vec3d;
using Tree = openvdb::FloatTree;
using Leaf = Tree::LeafNodeType;
using ConstAcc = openvdb::tree::ValueAccessor<const Tree, false>;
using Acc = openvdb::tree::ValueAccessor<Tree, false>;

enum Action : uint8_t { kSkip, kClear, kVisitLeaf, kVisitTile, kCollapse };

/// What every pass needs: the stock's frame and band and the cuts.
struct Pass {
  swarf_stock &s;
  const swarf_stock_cut *cuts;
  double voxel;                     ///< mm
  float bgf;                        ///< band half-width (the background), mm
  double reach;                     ///< half diagonal of a block plus the band, mm
  float radius[Leaf::SIZE];         ///< distance (mm) from each voxel centre to the block centre
  double roct[Leaf::SIZE];          ///< distance (mm) from each voxel centre to its octant's centre
  double rcube[64]; ///< distance (mm) from the block centre to each 2^3 cube's farthest voxel
  const Measure *measure = nullptr; ///< measured removal (per-cut volumes, gouges)
  bool flat = false;                ///< SWARF_REMOVE_FLAT=1: no hierarchy (tests)
  bool plain = false;               ///< SWARF_REMOVE_PLAIN=1: no range functions (tests)
  const swarf_stock_support_fn *support = nullptr; ///< per cut, may be null (stock.h)
};

/// World position (mm) of the point at (fractional) offset d from block origin o.
inline Vec3d block_point(const Pass &p, const Coord &o, double dx, double dy, double dz) {
  return p.s.origin + p.voxel * Vec3d(o.x() + dx, o.y() + dy, o.z() + dz);
}

/// Margin (mm) of the hierarchical tests below: above the certified error of
/// any cut's sdf (1e-6 mm for rotary sweeps), so that a voxel they pass over
/// or clear ends exactly as if its sdf had been evaluated.
constexpr double kMargin = 1e-5;
/// A voxel within kTie voxels of the surface is on it, for gouges: a cut
/// whose surface passes through a voxel centre (a tie, the sign of the
/// zero left to rounding) gouges there if the voxel was material, and the
/// next cut through the same centre (a retract from that pose) removes
/// nothing more and gouges nothing.
constexpr double kTie = 1e-9;

/// A cut's sdf at q where only values in (lo, hi) decide anything: with the
/// cut's range function (rotary sweeps: their search is pruned by both), a
/// value <= lo (still >= the sdf) below lo, >= hi at or above hi; else sdf.
/// Every test below that reads it gives what the full sdf would give (to the
/// cut's certified error, under kMargin).
inline double cut_value(const Pass &p, const swarf_stock_cut &cut, const Vec3d &q, double lo,
                        double hi) {
  if (cut.range == nullptr || p.plain || !(lo < hi)) return cut.sdf(cut.ctx, q.x(), q.y(), q.z());
  const double qq[3] = {q.x(), q.y(), q.z()};
  return cut.range(cut.ctx, qq, lo, hi);
}

void init_pass(Pass &p) {
  const double v = p.voxel;
  p.reach = 3.5 * std::sqrt(3.0) * v + p.bgf;
  for (int x = 0; x < 8; x++)
    for (int y = 0; y < 8; y++)
      for (int z = 0; z < 8; z++)
        p.radius[(x << 6) | (y << 3) | z] = float(
            v * std::sqrt((x - 3.5) * (x - 3.5) + (y - 3.5) * (y - 3.5) + (z - 3.5) * (z - 3.5)));
  for (int x = 0; x < 8; x++)
    for (int y = 0; y < 8; y++)
      for (int z = 0; z < 8; z++) {
        const double dx = (x & 3) - 1.5, dy = (y & 3) - 1.5, dz = (z & 3) - 1.5;
        p.roct[(x << 6) | (y << 3) | z] = v * std::sqrt(dx * dx + dy * dy + dz * dz);
      }
  for (int c = 0; c < 64; c++) {
    const double x = 2 * (c >> 4) - 3, y = 2 * ((c >> 2) & 3) - 3, z = 2 * (c & 3) - 3;
    p.rcube[c] = v * (std::sqrt(x * x + y * y + z * z) + 0.5 * std::sqrt(3.0));
  }
}

/// Index box (block origins, both ends inclusive) of the blocks a cut may
/// change: its bounds padded by the band and one voxel, clipped to the content
/// box. False if it misses the content box.
bool cut_blocks(const Pass &p, const swarf_stock_cut &c, Coord &bmin, Coord &bmax) {
  const openvdb::CoordBBox &box = p.s.content;
  const double pad = p.bgf / p.voxel + 1.0; // voxels
  int lo[3], hi[3];
  for (int k = 0; k < 3; k++) {
    double a = std::floor((c.lo[k] - p.s.origin[k]) / p.voxel - pad);
    double b = std::ceil((c.hi[k] - p.s.origin[k]) / p.voxel + pad);
    a = std::max(a, double(box.min()[k]));
    b = std::min(b, double(box.max()[k]));
    if (!(a <= b)) return false;
    lo[k] = int(a) & ~7;
    hi[k] = int(b) & ~7;
    if (p.s.has_region) { // only the blocks of this part (swarf_stock_set_region)
      lo[k] = std::max(lo[k], p.s.region_lo[k]);
      hi[k] = std::min(hi[k], p.s.region_hi[k]);
      if (lo[k] > hi[k]) return false;
    }
  }
  bmin = Coord(lo[0], lo[1], lo[2]);
  bmax = Coord(hi[0], hi[1], hi[2]);
  return true;
}

inline bool pair_less(const BlockCut &a, const BlockCut &b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  if (a.z != b.z) return a.z < b.z;
  return a.cut < b.cut;
}

/// The pairs in pair_less order. Where the blocks' span and the cuts fit in
/// 16 bits each (always, in a simulation's batches), sorted as 64-bit keys
/// (block offsets from the least block, then the cut): 2x faster than the
/// comparison of the fields.
void sort_pairs(std::vector<BlockCut> &pairs, size_t ncuts) {
  struct Span {
    int32_t lo[3] = {INT32_MAX, INT32_MAX, INT32_MAX}, hi[3] = {INT32_MIN, INT32_MIN, INT32_MIN};
    int32_t unaligned = 0; // block origins are multiples of 8
  };
  const tbb::blocked_range<size_t> all(0, pairs.size(), 4096);
  const Span sp = tbb::parallel_reduce(
      all, Span(),
      [&](const tbb::blocked_range<size_t> &r, Span a) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
          const BlockCut &q = pairs[i];
          a.unaligned |= (q.x | q.y | q.z) & 7;
          a.lo[0] = std::min(a.lo[0], q.x), a.hi[0] = std::max(a.hi[0], q.x);
          a.lo[1] = std::min(a.lo[1], q.y), a.hi[1] = std::max(a.hi[1], q.y);
          a.lo[2] = std::min(a.lo[2], q.z), a.hi[2] = std::max(a.hi[2], q.z);
        }
        return a;
      },
      [](Span a, const Span &b) {
        a.unaligned |= b.unaligned;
        for (int k = 0; k < 3; k++)
          a.lo[k] = std::min(a.lo[k], b.lo[k]), a.hi[k] = std::max(a.hi[k], b.hi[k]);
        return a;
      });
  const int32_t *lo = sp.lo, *hi = sp.hi;
  bool fits = ncuts <= 0x10000 && sp.unaligned == 0;
  for (int k = 0; k < 3; k++)
    fits = fits && (int64_t(hi[k]) - lo[k]) / 8 < 0x10000;
  if (!fits) {
    tbb::parallel_sort(pairs.begin(), pairs.end(), pair_less);
    return;
  }
  thread_local std::vector<uint64_t> keys_v; // this thread's buffer
  keys_v.resize(pairs.size());
  uint64_t *const keys = keys_v.data(); // the workers see the caller's buffer through it
  tbb::parallel_for(all, [&](const tbb::blocked_range<size_t> &r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const BlockCut &q = pairs[i];
      keys[i] = uint64_t((q.x - lo[0]) >> 3) << 48 | uint64_t((q.y - lo[1]) >> 3) << 32 |
                uint64_t((q.z - lo[2]) >> 3) << 16 | uint64_t(q.cut);
    }
  });
  tbb::parallel_sort(keys, keys + pairs.size());
  tbb::parallel_for(all, [&](const tbb::blocked_range<size_t> &r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const uint64_t k = keys[i];
      pairs[i] = {lo[0] + int32_t((k >> 48) << 3), lo[1] + int32_t(((k >> 32) & 0xffff) << 3),
                  lo[2] + int32_t(((k >> 16) & 0xffff) << 3), uint32_t(k & 0xffff)};
    }
  });
}

/// The sorted pairs grouped into blocks (each block's first pair and count),
/// in chunks found in parallel: the pairs of a big batch number millions.
void group_blocks(RemoveScratch &w) {
  const size_t np = w.pairs.size(), nchunk = std::max<size_t>(1, std::min<size_t>(256, np >> 14));
  auto starts = [&](size_t i) {
    const BlockCut &q = w.pairs[i];
    return i == 0 || q.x != w.pairs[i - 1].x || q.y != w.pairs[i - 1].y || q.z != w.pairs[i - 1].z;
  };
  auto chunk = [&](size_t c) {
    return tbb::blocked_range<size_t>(c * np / nchunk, (c + 1) * np / nchunk);
  };
  thread_local std::vector<size_t> first_v; // first block of each chunk (this thread's buffer)
  first_v.assign(nchunk + 1, 0);
  size_t *const first = first_v.data(); // the workers see the caller's buffer through it
  tbb::parallel_for(size_t(0), nchunk, [&](size_t c) {
    size_t n = 0;
    for (size_t i = chunk(c).begin(); i != chunk(c).end(); ++i)
      n += starts(i);
    first[c + 1] = n;
  });
  for (size_t c = 0; c < nchunk; c++)
    first[c + 1] += first[c];
  w.blocks.resize(first[nchunk]);
  tbb::parallel_for(size_t(0), nchunk, [&](size_t c) {
    size_t j = first[c];
    for (size_t i = chunk(c).begin(); i != chunk(c).end(); ++i)
      if (starts(i)) {
        const BlockCut &q = w.pairs[i];
        w.blocks[j++] = {Coord(q.x, q.y, q.z), uint32_t(i), 0, kSkip, 0.0f, false};
      }
  });
  const size_t nb = w.blocks.size();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nb, 4096),
                    [&](const tbb::blocked_range<size_t> &r) {
                      for (size_t j = r.begin(); j != r.end(); ++j)
                        w.blocks[j].count =
                            uint32_t((j + 1 < nb ? w.blocks[j + 1].begin : np) - w.blocks[j].begin);
                    });
}

/// Pass 1: the (block, cut) pairs sorted by block, grouped into blocks.
void list_pairs(Pass &p, size_t ncuts) {
  RemoveScratch &w = p.s.scratch;
  thread_local std::vector<size_t> at_v; // first pair of each cut (this thread's buffer)
  at_v.assign(ncuts + 1, 0);
  size_t *const at = at_v.data(); // the workers see the caller's buffer through it
  for (size_t i = 0; i < ncuts; i++) {
    Coord a, b;
    size_t n = 0;
    if (cut_blocks(p, p.cuts[i], a, b))
      n = size_t((b.x() - a.x()) / 8 + 1) * size_t((b.y() - a.y()) / 8 + 1) *
          size_t((b.z() - a.z()) / 8 + 1);
    at[i + 1] = at[i] + n;
  }
  w.pairs.resize(at[ncuts]); // no clear(): growing zero-fills only what is new
  tbb::parallel_for(tbb::blocked_range<size_t>(0, ncuts, 8),
                    [&](const tbb::blocked_range<size_t> &r) {
                      for (size_t i = r.begin(); i != r.end(); ++i) {
                        Coord a, b;
                        if (at[i + 1] == at[i] || !cut_blocks(p, p.cuts[i], a, b)) continue;
                        BlockCut *q = &w.pairs[at[i]];
                        for (int x = a.x(); x <= b.x(); x += 8)
                          for (int y = a.y(); y <= b.y(); y += 8)
                            for (int z = a.z(); z <= b.z(); z += 8)
                              *q++ = {x, y, z, uint32_t(i)};
                      }
                    });
  if (ncuts > 1) sort_pairs(w.pairs, ncuts);
  w.centre_sdf.resize(w.pairs.size());
  if (p.measure) {
    w.removed.assign(w.pairs.size(), 0.0);
    w.gouge.assign(w.pairs.size(), 0.0);
    w.gouge_at.assign(w.pairs.size(), Vec3d(0.0));
  }
  group_blocks(w);
}

/// True if the block holds no material and no band (all voxels outside).
bool block_outside(const Pass &p, ConstAcc &acc, const Coord &o, const Leaf **leaf) {
  *leaf = acc.probeConstLeaf(o);
  if (*leaf == nullptr) return !acc.isValueOn(o) && acc.getValue(o) >= p.bgf;
  if (!(*leaf)->isInactive()) return false;
  const float *v = (*leaf)->buffer().data();
  for (openvdb::Index n = 0; n < Leaf::SIZE; n++)
    if (!(v[n] >= p.bgf)) return false;
  return true;
}

/// Sum of the inside fractions of the block's voxels (leaf, or the tile at o).
double block_material(const Pass &p, ConstAcc &acc, const Coord &o, const Leaf *leaf) {
  if (leaf == nullptr) return Leaf::SIZE * inside_fraction(acc.getValue(o), p.voxel);
  double sum = 0.0;
  const float *v = leaf->buffer().data();
  for (openvdb::Index n = 0; n < Leaf::SIZE; n++)
    sum += inside_fraction(v[n], p.voxel);
  return sum;
}

/// True if the design cannot be gouged anywhere in the block at o (stock
/// index): the design and the stock share a lattice and every design value
/// over the block's voxels is at least a voxel (outside the design by more
/// than any depth vouched there). dacc: the design's tree.
bool design_clear(const Pass &p, ConstAcc *dacc, const Coord &o) {
  if (dacc == nullptr) return false;
  const swarf_stock &d = *p.measure->design;
  const Vec3d off = (p.s.origin - d.origin) / p.voxel;
  const Coord lo(o.x() + int(std::lround(off[0])), o.y() + int(std::lround(off[1])),
                 o.z() + int(std::lround(off[2])));
  const Coord hi = lo.offsetBy(7);
  const float floor_value = float(p.voxel);
  for (int x = lo.x() & ~7; x <= hi.x(); x += 8)
    for (int y = lo.y() & ~7; y <= hi.y(); y += 8)
      for (int z = lo.z() & ~7; z <= hi.z(); z += 8) {
        const Coord c(x, y, z);
        const Leaf *leaf = dacc->probeConstLeaf(c);
        if (leaf == nullptr) {
          if (!(dacc->getValue(c) >= floor_value)) return false;
          continue;
        }
        const float *v = leaf->buffer().data();
        for (openvdb::Index n = 0; n < Leaf::SIZE; n++)
          if (!(v[n] >= floor_value)) return false;
      }
  return true;
}

/// Pass 2 for one block: keep the cuts that reach into it (compacted to the
/// front of its pair range, with their centre values) and choose its action.
/// dacc: the design's tree when measuring against a design on the stock's
/// lattice (else null).
void classify(const Pass &p, ConstAcc &acc, Block &b, ConstAcc *dacc) {
  RemoveScratch &w = p.s.scratch;
  const Leaf *leaf;
  b.action = kSkip;
  if (block_outside(p, acc, b.origin, &leaf)) return;
  const Vec3d c = block_point(p, b.origin, 3.5, 3.5, 3.5);
  uint32_t kept = 0;
  int clear = -1; // whether the design is clear of the block (asked once, when needed)
  auto design_clear_here = [&] {
    if (clear < 0) clear = p.measure->design == nullptr || design_clear(p, dacc, b.origin);
    return clear == 1;
  };
  for (uint32_t i = b.begin; i < b.begin + b.count; i++) {
    const swarf_stock_cut &cut = p.cuts[w.pairs[i].cut];
    const double d = cut_value(p, cut, c, -p.reach - kMargin, p.reach + kMargin);
    if (d > p.reach) continue; // untouched (a NaN is kept: its voxels decide)
    if (-d > p.reach && (p.measure == nullptr || (!p.measure->volumes && design_clear_here()))) {
      b.action = kClear; // (gouges only: none can be found in the block)
      return;
    }
    if (-d > p.reach && kept == 0 && design_clear_here()) {
      // Measured: the first cut reaching the block clears it and removes all of it.
      w.pairs[b.begin] = w.pairs[i];
      w.removed[b.begin] = block_material(p, acc, b.origin, leaf);
      b.count = 1;
      b.action = kClear;
      return;
    }
    w.pairs[b.begin + kept] = w.pairs[i];
    w.centre_sdf[b.begin + kept] = d;
    kept++;
    if (-d > p.reach) break; // measured: it clears every voxel; later cuts find nothing
  }
  b.count = kept;
  if (kept > 0) b.action = leaf ? kVisitLeaf : kVisitTile;
  if (b.action == kVisitTile) b.tile = acc.getValue(b.origin), b.tile_on = acc.isValueOn(b.origin);
}

/// Count a visited block's cuts (swarf_stock_set_tally).
inline void tally_block(swarf_stock &s, const Coord &o, uint32_t cuts) {
  long at = 0;
  for (int k = 0; k < 3; k++) {
    const long i = (long(o[k]) - s.tally_lo[k]) / 8;
    if (i < 0 || i >= s.tally_n[k]) return;
    at = at * s.tally_n[k] + i;
  }
  s.tally[at] += cuts;
}

/// Pass 3: topology changes, serial. Collects the blocks to visit. (A tile
/// to visit stays a tile until the visit has made its leaf: most of a
/// roughing's are emptied by their cuts and collapse, and never take memory.)
void change_topology(Pass &p) {
  RemoveScratch &w = p.s.scratch;
  Tree &tree = p.s.grid->tree();
  w.visit.clear();
  for (size_t i = 0; i < w.blocks.size(); i++) {
    Block &b = w.blocks[i];
    if (b.action == kClear) tree.addTile(1, b.origin, p.bgf, false);
    if (b.action == kVisitLeaf || b.action == kVisitTile) {
      w.visit.push_back(uint32_t(i));
      if (p.s.tally) tally_block(p.s, b.origin, b.count);
    }
  }
}

/// Measured: what the plain visit learnt of the block's cuts at each 4^3
/// octant's centre, for the replay (visit_leaf_measured), per octant and pair
/// (index - the block's first): whether the cut may raise a voxel of the
/// octant at all (the block centre's bound), and its supporting plane there.
struct OctantPlanes {
  enum : uint8_t { kOut, kNoPlane, kPlane };
  struct Entry {
    uint8_t state; ///< kOut: no voxel of the octant can be raised (from the block's values)
    double d;      ///< kPlane: sdf(q) >= d + g.(q - centre) for every q
    double g[3];
  };
  std::vector<Entry> e;
  uint32_t count = 0;
  /// Room for n cuts; the octants' visits write every entry, so none is
  /// cleared here.
  void reset(uint32_t n) {
    count = n;
    if (e.size() < 8 * size_t(n)) e.resize(8 * size_t(n));
  }
  Entry &at(int octant, uint32_t k) { return e[size_t(octant) * count + k]; }
};

/// Voxel values of a block while its cuts are applied one after another, with
/// the summaries that let a cut pass over an octant or a cube without looking
/// at its voxels: omin[o] = min over the octant's voxels n still below the band
/// (m < bg) of m - radius[n], cmin[c] = the same over a cube's voxels with
/// roct[n] (+inf when every voxel is outside). A cut whose sdf is d at the block
/// centre can raise a voxel of octant o only if d + omin[o] < kMargin (the test
/// may_raise makes voxel by voxel, taken at once), likewise per cube with its
/// sdf at the octant's centre. The summaries are lower bounds kept exact.
struct BlockValues {
  double m[Leaf::SIZE]; ///< max(old, -sdf) over the cuts applied so far
  double omin[8];       ///< per 4^3 octant, index (x >> 2) << 2 | (y >> 2) << 1 | z >> 2
  double cmin[64];      ///< per 2^3 cube, index (x >> 1) << 4 | (y >> 1) << 2 | z >> 1
  double mlo[64];       ///< per 2^3 cube: min of m over its voxels with m < bg (+inf if none)
  uint32_t *arg;        ///< measured: per voxel, the cut that last raised m (else null)
  OctantPlanes *planes = nullptr; ///< measured: filled by the octants' visits (else null)
  /// m[n] = value, raised by cut c (an index into the pass's cuts).
  void raise(openvdb::Index n, double value, size_t c) {
    m[n] = value;
    if (arg != nullptr) arg[n] = uint32_t(c);
  }
};

/// Whether voxel n (value m, at distance r from a point where the cut's sdf is
/// d) may be raised by the cut: not already outside, and the Lipschitz bound
/// d - r does not keep -sdf at or below m.
inline bool may_raise(double m, double bg, double d, double r) {
  return m < bg && !(d - r + m >= kMargin); // a NaN sdf: the voxels decide
}

/// A cut's sdf at voxel centre q whose value is m: only values that change
/// the voxel matter (below -m; deeper than -bg - kMargin it is cleared).
inline double voxel_sdf(const Pass &p, const swarf_stock_cut &cut, const Vec3d &q, double m) {
  return cut_value(p, cut, q, -double(p.bgf) - kMargin, -m);
}

/// Summary value of voxel n: m - r, or +inf if it is outside (cannot be raised).
inline double summary(double m, double bg, double r) {
  return m < bg ? m - r : std::numeric_limits<double>::infinity();
}

/// Recompute cmin for the cube at (x0, y0, z0) (even coordinates).
inline void cube_summary(const Pass &p, BlockValues &bv, int x0, int y0, int z0) {
  double lo = std::numeric_limits<double>::infinity(), mlo = lo;
  for (int x = x0; x < x0 + 2; x++)
    for (int y = y0; y < y0 + 2; y++)
      for (int z = z0; z < z0 + 2; z++) {
        const openvdb::Index n = (x << 6) | (y << 3) | z;
        const double s = summary(bv.m[n], p.bgf, p.roct[n]), m = summary(bv.m[n], p.bgf, 0.0);
        lo = s < lo ? s : lo;
        mlo = m < mlo ? m : mlo;
      }
  bv.cmin[((x0 >> 1) << 4) | ((y0 >> 1) << 2) | (z0 >> 1)] = lo;
  bv.mlo[((x0 >> 1) << 4) | ((y0 >> 1) << 2) | (z0 >> 1)] = mlo;
}

/// All the summaries of a block, octant by octant and cube by cube.
void leaf_summaries(const Pass &p, BlockValues &bv) {
  const double inf = std::numeric_limits<double>::infinity(), bg = p.bgf;
  for (int x0 = 0; x0 < 8; x0 += 4)
    for (int y0 = 0; y0 < 8; y0 += 4)
      for (int z0 = 0; z0 < 8; z0 += 4) {
        double olo = inf;
        for (int sx = x0; sx < x0 + 4; sx += 2)
          for (int sy = y0; sy < y0 + 4; sy += 2)
            for (int sz = z0; sz < z0 + 4; sz += 2) {
              double clo = inf, mlo = inf;
              for (int x = sx; x < sx + 2; x++)
                for (int y = sy; y < sy + 2; y++)
                  for (int z = sz; z < sz + 2; z++) {
                    const openvdb::Index n = (x << 6) | (y << 3) | z;
                    const double m = bv.m[n];
                    const double c = m < bg ? m - p.roct[n] : inf;
                    const double o = m < bg ? m - double(p.radius[n]) : inf;
                    const double l = m < bg ? m : inf;
                    clo = c < clo ? c : clo;
                    mlo = l < mlo ? l : mlo;
                    olo = o < olo ? o : olo;
                  }
              bv.cmin[((sx >> 1) << 4) | ((sy >> 1) << 2) | (sz >> 1)] = clo;
              bv.mlo[((sx >> 1) << 4) | ((sy >> 1) << 2) | (sz >> 1)] = mlo;
            }
        bv.omin[((x0 >> 2) << 2) | ((y0 >> 2) << 1) | (z0 >> 2)] = olo;
      }
}

/// A cut and its sdf (mm) at the centre of the octant or cube being visited,
/// with, at a cube's centre, the supporting plane's normal when it has one.
struct CutAt {
  double d;
  const swarf_stock_cut *cut;
  bool plane = false; ///< sdf(q) >= d + g.(q - centre) for every q
  double g[3];
};

/// An octant's cuts deepest first (a NaN sdf first), sorted lazily: the
/// cubes walk the order from its start and most stop after a few cuts, so
/// the order is drawn from a heap only as far as some cube reads it
/// (issue 12: with 1024 moves a batch, a full sort of every octant's cuts
/// took 12 % of bear.nc at 0.2 mm).
class OctOrder {
public:
  using Key = std::pair<double, uint32_t>; ///< sort key (NaN: -inf), index in the octant's cuts

  /// Takes the octant's n cuts; keys and order are the caller's scratch of n each.
  OctOrder(const CutAt *oct, uint32_t n, Key *keys, uint32_t *order)
      : oct_(oct), heap_(keys), order_(order), hn_(n) {
    for (uint32_t i = 0; i < n; i++)
      heap_[i] = {std::isnan(oct[i].d) ? -HUGE_VAL : oct[i].d, i};
    std::make_heap(heap_, heap_ + hn_, std::greater<Key>());
  }

  /// The i-th deepest cut, or null past the last.
  const CutAt *get(uint32_t i) {
    while (ns_ <= i && hn_ > 0) {
      std::pop_heap(heap_, heap_ + hn_, std::greater<Key>());
      order_[ns_++] = heap_[--hn_].second;
    }
    return i < ns_ ? &oct_[order_[i]] : nullptr;
  }

private:
  const CutAt *oct_;
  Key *heap_;
  uint32_t *order_;
  uint32_t hn_, ns_ = 0;
};

/// A thread's scratch for the octants' visits, taken once per task with
/// the rest of VisitScratch (a thread_local in this module costs a call to
/// __tls_get_addr at each access).
struct OctScratch {
  std::vector<OctOrder::Key> keys;
  std::vector<uint32_t> order;
  std::vector<CutAt> oct;
};

/// Pass 4 for the 2^3 voxels at (x0, y0, z0) of the block and one cut whose
/// sdf at the cube's centre is dcube: a voxel is evaluated unless the bound
/// from the centre keeps it below its value; all are cleared when the cube lies
/// deeper than the band.
void visit_cube(const Pass &p, const Block &b, const CutAt &c, int x0, int y0, int z0,
                BlockValues &bv) {
  const double bg = p.bgf, rv = 0.5 * std::sqrt(3.0) * p.voxel; // voxel -> cube centre
  const bool clear = c.d + rv <= -bg - kMargin;
  // The bound at each voxel: d - rv, or with a plane d + g.(voxel - centre)
  // (>= d - rv), the voxel's offset from the centre being +-voxel/2 per axis.
  const double h = 0.5 * p.voxel;
  const double gx = c.plane ? h * c.g[0] : 0.0, gy = c.plane ? h * c.g[1] : 0.0,
               gz = c.plane ? h * c.g[2] : 0.0, r = c.plane ? 0.0 : rv;
  double mlo = std::numeric_limits<double>::infinity();
  for (int x = x0; x < x0 + 2; x++)
    for (int y = y0; y < y0 + 2; y++)
      for (int z = z0; z < z0 + 2; z++) {
        const openvdb::Index n = (x << 6) | (y << 3) | z;
        double &m = bv.m[n];
        const double bound = c.d + (x > x0 ? gx : -gx) + (y > y0 ? gy : -gy) + (z > z0 ? gz : -gz);
        if (may_raise(m, bg, bound, r)) {
          if (clear) {
            bv.raise(n, bg, c.cut - p.cuts);
          } else {
            const double d = -voxel_sdf(p, *c.cut, block_point(p, b.origin, x, y, z), m);
            if (d > m) bv.raise(n, d, c.cut - p.cuts);
          }
        }
        const double l = summary(m, bg, 0.0);
        mlo = l < mlo ? l : mlo;
      }
  bv.mlo[((x0 >> 1) << 4) | ((y0 >> 1) << 2) | (z0 >> 1)] = mlo;
}

/// Whether the supporting plane of cut o at the centre of the octant holding
/// the 2^3 cube at (x0, y0, z0) keeps every voxel of the cube at or below its
/// value (o.d + o.g.(voxel - centre) is a lower bound of the sdf: may_raise
/// false for each voxel).
inline bool plane_keeps_below(const Pass &p, const BlockValues &bv, const CutAt &o, int x0, int y0,
                              int z0) {
  const double bg = p.bgf, v = p.voxel;
  // the cube's first voxel's offset from the octant's centre, in voxels
  const double ox = (x0 & 3) - 1.5, oy = (y0 & 3) - 1.5, oz = (z0 & 3) - 1.5;
  for (int x = 0; x < 2; x++)
    for (int y = 0; y < 2; y++)
      for (int z = 0; z < 2; z++) {
        const double m = bv.m[((x0 + x) << 6) | ((y0 + y) << 3) | (z0 + z)];
        const double bound = o.d + v * (o.g[0] * (ox + x) + o.g[1] * (oy + y) + o.g[2] * (oz + z));
        if (m < bg && !(bound + m >= kMargin)) return false;
      }
  return true;
}

/// Pass 4 for the 2^3 cube at (x0, y0, z0) and the cuts of its octant (their
/// sdf at the octant's centre, in oct, sorted deepest first): those the
/// cube's summary lets through are cleared from the octant's value when it
/// lies deeper than the band, or have their sdf taken at the cube's centre and
/// the cube visited. In that order the first cuts raise the voxels most, so
/// the later ones mostly find their bound below the voxels' values and
/// evaluate nothing, down to the first whose octant value keeps every voxel
/// of the cube below (the maximum does not depend on the order).
void visit_cube_cuts(const Pass &p, const Block &b, OctOrder &oct, int x0, int y0, int z0,
                     BlockValues &bv) {
  const double bg = p.bgf, v = p.voxel, rcube = std::sqrt(3.0) * v; // cube centre -> octant centre
  const double rv = 0.5 * std::sqrt(3.0) * v;                       // voxel -> its cube's centre
  const int ci = ((x0 >> 1) << 4) | ((y0 >> 1) << 2) | (z0 >> 1);
  const Vec3d c = block_point(p, b.origin, x0 + 0.5, y0 + 0.5, z0 + 0.5);
  // Range functions resolve only cube values that decide something: at or
  // above cube_hi no voxel of the cube can be raised (may_raise), at or below
  // cube_lo every one is cleared (visit_cube). (The voxels only rise: cube_hi
  // taken before the first cut stays an upper bound of what decides.)
  const double cube_lo = -bg - kMargin - rv;
  double cube_hi = -std::numeric_limits<double>::infinity();
  for (int x = x0; x < x0 + 2; x++)
    for (int y = y0; y < y0 + 2; y++)
      for (int z = z0; z < z0 + 2; z++) {
        const double m = bv.m[(x << 6) | (y << 3) | z];
        if (m < bg) cube_hi = std::max(cube_hi, kMargin + rv - m);
      }
  for (uint32_t i = 0;; i++) {
    const CutAt *at = oct.get(i);
    if (at == nullptr) break;
    const CutAt &o = *at;
    // may_raise for the cube's lowest value with the cube's sdf at least
    // o.d - rcube: false, and false for the remaining (shallower) cuts too
    if (o.d - rcube - rv + bv.mlo[ci] >= kMargin) break;
    if (o.d + bv.cmin[ci] >= kMargin) continue; // no voxel of the cube can be raised
    if (o.plane && plane_keeps_below(p, bv, o, x0, y0, z0)) continue; // the same, by the plane
    if (o.d + rcube + rv <= -bg - kMargin) { // every voxel lies deeper than the band
      for (int x = x0; x < x0 + 2; x++)
        for (int y = y0; y < y0 + 2; y++)
          for (int z = z0; z < z0 + 2; z++) {
            const openvdb::Index n = (x << 6) | (y << 3) | z;
            if (may_raise(bv.m[n], bg, o.d, p.roct[n])) bv.raise(n, bg, o.cut - p.cuts);
          }
      cube_summary(p, bv, x0, y0, z0);
      continue;
    }
    CutAt k;
    const swarf_stock_support_fn f = p.support ? p.support[o.cut - p.cuts] : nullptr;
    k.cut = o.cut;
    k.plane = f != nullptr && f(o.cut->ctx, c.x(), c.y(), c.z(), &k.d, k.g) == 1;
    if (f == nullptr) k.d = cut_value(p, *o.cut, c, cube_lo, cube_hi);
    if (k.d - rv + bv.mlo[ci] >= kMargin) continue; // may_raise, for the lowest value: false
    visit_cube(p, b, k, x0, y0, z0, bv);
  }
}

/// Pass 4 for the 4^3 octant at (x0, y0, z0) and the block's cuts: each cut
/// whose bound from the block centre (its summary) may raise a voxel of the
/// octant has its sdf taken at the octant's centre, with its supporting plane
/// where it has one (3-axis moves; that plane passes over 45 % of the cubes
/// the summaries let through on bear.nc and tiger.nc); the octant's eight
/// cubes are then visited one after another with all of them, deepest first.
void visit_octant(const Pass &p, const Block &b, int x0, int y0, int z0, BlockValues &bv,
                  OctScratch &os) {
  CutAt *oct = os.oct.data();
  const RemoveScratch &w = p.s.scratch;
  const double omin = bv.omin[((x0 >> 2) << 2) | ((y0 >> 2) << 1) | (z0 >> 2)];
  const Vec3d c = block_point(p, b.origin, x0 + 1.5, y0 + 1.5, z0 + 1.5);
  // Where a cut has a range function, only octant values that decide something
  // are resolved: at or above oct_hi no cube's summary lets it through; at or
  // below oct_lo it clears every cube it reaches (visit_cube_cuts).
  const double rcube = std::sqrt(3.0) * p.voxel, rv = 0.5 * std::sqrt(3.0) * p.voxel;
  const double oct_lo = -double(p.bgf) - kMargin - rcube - rv;
  double oct_hi = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < 8; k++)
    oct_hi = std::max(
        oct_hi, kMargin - bv.cmin[(((x0 >> 1) + (k >> 2)) << 4) |
                                  (((y0 >> 1) + ((k >> 1) & 1)) << 2) | ((z0 >> 1) + (k & 1))]);
  uint32_t n = 0;
  const int octant = ((x0 >> 2) << 2) | ((y0 >> 2) << 1) | (z0 >> 2);
  for (uint32_t i = b.begin; i < b.begin + b.count; i++) {
    if (w.centre_sdf[i] + omin >= kMargin) { // a NaN sdf: visited
      if (bv.planes != nullptr) bv.planes->at(octant, i - b.begin).state = OctantPlanes::kOut;
      continue;
    }
    const swarf_stock_cut &cut = p.cuts[w.pairs[i].cut];
    const swarf_stock_support_fn f = p.support ? p.support[w.pairs[i].cut] : nullptr;
    CutAt &o = oct[n++];
    o.cut = &cut;
    o.plane = f != nullptr && f(cut.ctx, c.x(), c.y(), c.z(), &o.d, o.g) == 1;
    if (f == nullptr) o.d = cut_value(p, cut, c, oct_lo, oct_hi);
    if (bv.planes != nullptr) {
      OctantPlanes::Entry &r = bv.planes->at(octant, i - b.begin);
      r.state = o.plane ? OctantPlanes::kPlane : OctantPlanes::kNoPlane;
      r.d = o.d;
      std::copy(o.g, o.g + 3, r.g);
    }
  }
  if (n == 0) return;
  if (os.keys.size() < n) os.keys.resize(n), os.order.resize(n);
  OctOrder ord(oct, n, os.keys.data(), os.order.data());
  for (int sx = x0; sx < x0 + 4; sx += 2)
    for (int sy = y0; sy < y0 + 4; sy += 2)
      for (int sz = z0; sz < z0 + 4; sz += 2)
        visit_cube_cuts(p, b, ord, sx, sy, sz, bv);
}

/// Pass 4 for one cut without the hierarchy (SWARF_REMOVE_FLAT=1, the
/// reference the tests compare with): every voxel the block centre's bound
/// cannot decide is evaluated.
void visit_flat(const Pass &p, const Block &b, const swarf_stock_cut &cut, double dc,
                BlockValues &bv) {
  for (int x = 0; x < 8; x++)
    for (int y = 0; y < 8; y++)
      for (int z = 0; z < 8; z++) {
        const openvdb::Index n = (x << 6) | (y << 3) | z;
        if (!may_raise(bv.m[n], p.bgf, dc, p.radius[n])) continue;
        const double d = -voxel_sdf(p, cut, block_point(p, b.origin, x, y, z), bv.m[n]);
        if (d > bv.m[n]) bv.raise(n, d, &cut - p.cuts);
      }
}

/// Store a raised value: inactive at the band's edges (+-bgf), active inside.
inline void put_value(Leaf &leaf, openvdb::Index n, float v, float bgf) {
  if (v >= bgf)
    leaf.setValueOff(n, bgf);
  else if (v <= -bgf)
    leaf.setValueOff(n, -bgf);
  else
    leaf.setValueOn(n, v);
}

/// After a pass: a block left with no active voxel and one value becomes a tile.
inline void collapse_if_uniform(const Leaf &leaf, Block &b) {
  if (!leaf.isInactive()) return;
  const float *data = leaf.buffer().data();
  for (openvdb::Index n = 1; n < Leaf::SIZE; n++)
    if (data[n] != data[0]) return;
  b.action = kCollapse;
  b.tile = data[0];
}

/// Pass 4 for one leaf: max over the cuts, clamp, band state. The block is
/// visited octant by octant and cube by cube (their voxels are independent),
/// each with all its cuts, top down (8^3 block centre, 4^3 octants, 2^3 cubes,
/// voxels; the sdf is 1-Lipschitz): a voxel's sdf is evaluated only where the
/// bound from the nearest centre above it cannot decide, and an octant or a
/// cube is looked at only where its summary (BlockValues) says a voxel may be
/// raised. Marks the block kCollapse (with its tile value) if no voxel is left
/// in the band. arg (measured): where each voxel's final value came from
/// (BlockValues::arg), left as it was for voxels no cut raised.
void visit_leaf(const Pass &p, Leaf &leaf, Block &b, OctScratch &os, uint32_t *arg = nullptr,
                OctantPlanes *planes = nullptr) {
  const RemoveScratch &w = p.s.scratch;
  const float bgf = p.bgf;
  const float *data = leaf.buffer().data();
  BlockValues bv;
  bv.arg = arg;
  bv.planes = p.flat ? nullptr : planes;
  for (openvdb::Index n = 0; n < Leaf::SIZE; n++)
    bv.m[n] = data[n];
  if (p.flat) {
    for (uint32_t i = b.begin; i < b.begin + b.count; i++)
      visit_flat(p, b, p.cuts[w.pairs[i].cut], w.centre_sdf[i], bv);
  } else {
    if (os.oct.size() < b.count) os.oct.resize(b.count);
    leaf_summaries(p, bv);
    for (int x = 0; x < 8; x += 4)
      for (int y = 0; y < 8; y += 4)
        for (int z = 0; z < 8; z += 4)
          visit_octant(p, b, x, y, z, bv, os);
  }
  for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
    const float old = data[n];
    const double m = bv.m[n];
    if (!(old < bgf) || !(m > old)) continue;
    put_value(leaf, n, float(m), bgf);
  }
  collapse_if_uniform(leaf, b);
}

/// The depth of a gouge at a voxel whose design value is dq, with r mm of
/// removed material vouched beyond its centre. A design without triangles
/// (a .vdb) knows only its band: where dq is at the band's edge the gouge
/// reads as the band's depth (the reach; the summary says "or more").
inline double gouge_depth(const swarf_stock &design, double dq, double r, double voxel) {
  const double bg = design.background;
  if (!design.surface && dq <= -bg * (1.0 - 1e-6)) return bg;
  return -dq + vouched_radius(r, voxel);
}

/// True if no voxel of the block at o (stock index) can gouge the design by
/// more than the tolerance: design and stock share a lattice and every design
/// value over the block is at least `far` (a gouge's depth is -value plus at
/// most a voxel: with far = a voxel, <= 0 there; with gouge_floor's, at most
/// the tolerance). dacc: the design's tree.
bool design_far(const Pass &p, ConstAcc &dacc, const Coord &o, double far) {
  const swarf_stock &d = *p.measure->design;
  const Vec3d off = (p.s.origin - d.origin) / p.voxel;
  const Coord lo(o.x() + int(std::lround(off[0])), o.y() + int(std::lround(off[1])),
                 o.z() + int(std::lround(off[2])));
  const Coord hi = lo.offsetBy(7);
  for (int x = lo.x() & ~7; x <= hi.x(); x += 8)
    for (int y = lo.y() & ~7; y <= hi.y(); y += 8)
      for (int z = lo.z() & ~7; z <= hi.z(); z += 8) {
        const Coord c(x, y, z);
        const Leaf *leaf = dacc.probeConstLeaf(c);
        if (leaf == nullptr) {
          if (!(double(dacc.getValue(c)) >= far)) return false;
          continue;
        }
        // the part of this leaf under the block
        const Coord a = openvdb::Coord::maxComponent(lo, c),
                    e = openvdb::Coord::minComponent(hi, c.offsetBy(7));
        const float *v = leaf->buffer().data();
        for (int i = a.x(); i <= e.x(); i++)
          for (int j = a.y(); j <= e.y(); j++)
            for (int k = a.z(); k <= e.z(); k++)
              if (!(double(v[Leaf::coordToOffset(Coord(i, j, k))]) >= far)) return false;
      }
  return true;
}

/// The design value at and above which a voxel cannot be gouged by more than
/// the tolerance: its depth, -value plus at most a voxel, is then within it
/// (a hair above voxel - tolerance, so that the rounding of that sum cannot
/// make it exceed it), and the value is not the band's edge, beyond which a
/// mesh's depth is measured on its triangles. The gouges-only replay passes
/// such voxels over.
inline double gouge_floor(const Pass &p) {
  const double edge = -double(p.measure->design->background) * (1.0 - 1e-6);
  return std::max(p.voxel - p.measure->tolerance, edge) + 1e-9;
}

/// The cuts that may change a block's 2^3 cubes, in program order, found
/// as the replay asks for them (per thread, reset for every block): for each
/// cube, the cuts whose Lipschitz bound, from the block's centre, then from
/// the cube's centre (one sdf for the cube), lets them raise its lowest
/// starting value, with that sdf.
struct CubeCuts {
  struct Entry {
    uint32_t pair;
    double d;  ///< the cut's sdf at the cube's centre
    int plane; ///< 1: sdf(q) >= d + g.(q - centre) for every q; 0: none; -1: not asked yet
    double g[3];
    /// The plane's bound at the cube's voxel l (block-local; +-h from the centre per axis).
    double at(const Coord &l, double h) const {
      return d + (l.x() & 1 ? h : -h) * g[0] + (l.y() & 1 ? h : -h) * g[1] +
             (l.z() & 1 ? h : -h) * g[2];
    }
  };
  std::vector<Entry> list[64];
  uint32_t next[64]; ///< the next pair to look at
  double low[64];    ///< lowest starting value of the cube's changed voxels (+inf: none)
  OctantPlanes *planes = nullptr; ///< the plain visit's octant planes (null: none)
  static int octant_of(int c) { return ((c >> 5) << 2) | (((c >> 3) & 1) << 1) | ((c >> 1) & 1); }
  /// Whether the octant's findings keep every voxel of cube c at or below
  /// low[c]: the plain visit passed the cut over the octant, or its plane at
  /// the octant's centre bounds it there (the cube's voxels lie at -1.5 or
  /// 0.5, and one more, voxels from that centre per axis).
  bool octant_keeps_below(const Pass &p, const OctantPlanes::Entry &o, int c) const {
    if (o.state == OctantPlanes::kOut) return true;
    if (o.state != OctantPlanes::kPlane) return false;
    const int cc[3] = {c >> 4, (c >> 2) & 3, c & 3};
    double bound = o.d;
    for (int a = 0; a < 3; a++) {
      const double ox = ((cc[a] & 1) << 1) - 1.5; // the cube's first voxel, in voxels
      bound += p.voxel * std::min(o.g[a] * ox, o.g[a] * (ox + 1.0));
    }
    return bound + low[c] >= kMargin;
  }
  /// The world position of cube c's centre in block b.
  static Vec3d centre(const Pass &p, const Block &b, int c) {
    return block_point(p, b.origin, ((c >> 4) << 1) + 0.5, (((c >> 2) & 3) << 1) + 0.5,
                       ((c & 3) << 1) + 0.5);
  }
  void reset(const Block &b) {
    for (int c = 0; c < 64; c++) {
      list[c].clear();
      next[c] = b.begin;
      low[c] = std::numeric_limits<double>::infinity();
    }
  }
  /// Entry k of cube c's list, found if needed; false when there is none.
  bool get(const Pass &p, const Block &b, int c, size_t k, Entry &e) {
    const RemoveScratch &w = p.s.scratch;
    const double rv = 0.5 * std::sqrt(3.0) * p.voxel;
    while (list[c].size() <= k) {
      if (next[c] >= b.begin + b.count) return false;
      const uint32_t i = next[c]++;
      if (w.centre_sdf[i] - p.rcube[c] + low[c] >= kMargin) continue; // a NaN: looked at
      if (planes != nullptr && octant_keeps_below(p, planes->at(octant_of(c), i - b.begin), c))
        continue;
      const swarf_stock_cut &cut = p.cuts[w.pairs[i].cut];
      const Vec3d q = centre(p, b, c);
      const double d = cut.sdf(cut.ctx, q.x(), q.y(), q.z());
      if (d - rv + low[c] >= kMargin) continue;
      // a plane only outside the cut (its support function's rule)
      const bool ask = p.support != nullptr && p.support[w.pairs[i].cut] != nullptr && d > 0.0;
      list[c].push_back({i, d, ask ? -1 : 0, {0.0, 0.0, 0.0}});
    }
    e = list[c][k];
    return true;
  }
  /// Entry k of cube c (found by get) with its supporting plane, asked for now
  /// if it was not yet (a voxel the Lipschitz bound could not decide).
  const Entry &with_plane(const Pass &p, const Block &b, int c, size_t k) {
    Entry &e = list[c][k];
    if (e.plane >= 0) return e;
    const RemoveScratch &w = p.s.scratch;
    const swarf_stock_cut &cut = p.cuts[w.pairs[e.pair].cut];
    const Vec3d q = centre(p, b, c);
    e.plane = p.support[w.pairs[e.pair].cut](cut.ctx, q.x(), q.y(), q.z(), &e.d, e.g) == 1;
    return e;
  }
};

/// A thread's scratch for the visits (remove_cuts takes it once per task).
struct VisitScratch {
  OctScratch oct;
  OctantPlanes planes;
  CubeCuts cubes;
  std::unique_ptr<Leaf> tile; ///< a tile's block, until it proves a leaf
};

/// This thread's VisitScratch. Not inlined: GCC otherwise propagates the
/// thread_local into the visit and asks __tls_get_addr for its address at
/// each use in the loops (4 % of a measured run's instructions).
__attribute__((noinline)) VisitScratch &visit_scratch() {
  thread_local VisitScratch vs;
  return vs;
}

/// Pass 4, measured: the block's final values by the plain visit (the
/// maximum does not depend on the cuts' order), then each cut credited, in
/// program order, with the inside fraction it removed, and checked for a
/// gouge (material before it, inside it, into the design). Only the steps a
/// voxel takes between inside fractions 1 and 0 count (|value| < half a
/// voxel), so each voxel whose fraction changed is replayed cut by cut from
/// its old value until it is empty (every later step credits nothing and
/// finds no material to gouge); the others not at all. Steps are stored as
/// the grid would (float, clamped), so every credit is the one a cut by cut
/// evaluation of every voxel gives.
///
/// The replay evaluates a cut at a voxel only where that can change what is
/// measured. Values below a floor F (-half a voxel; -a voxel when the design
/// can be gouged in the block: a gouge's depth reads min(-value, voxel)) all
/// count as F, since their inside fraction is 1 and their depth a voxel, so a
/// voxel starts at max(old, F). A voxel looks only at its 2^3 cube's cuts
/// (CubeCuts: those that can raise some voxel of the cube; a cut the plain
/// visit passed over at the cube's octant, or whose supporting plane at the
/// octant's centre, taken there by that visit, keeps the cube where it is,
/// needs no sdf at the cube's centre: 15.4 M -> 5.3 M such calls on bear.nc
/// at 0.2 mm), and passes over
/// those whose bound from the cube's centre keeps it where it is, or, for a
/// cut with a supporting plane there (3-axis moves, the centre outside the
/// cut), whose plane does (asked for at the first voxel of the cube the
/// Lipschitz bound leaves undecided; bear.nc at 0.2 mm: 26.1 M -> 14.6 M
/// replay sdf calls, of which 12.6 M raise the voxel); where the
/// cube's centre lies so deep in the cut that the voxel ends at or beyond S
/// (half a voxel; a voxel with the design, where a depth also reads a
/// voxel), it is emptied without evaluating the cut: its credit is its
/// remaining fraction, its depth min(-value, voxel).
///
/// Gouges only (Measure::volumes false): a block where the design cannot be
/// gouged (design_far at gouge_floor) gets the plain visit alone, and the
/// replay takes only the voxels that went from material to air (a gouge needs
/// material before the step and the cut at the centre) where the design value
/// is below gouge_floor, each until it has no material left. Such a voxel's
/// replay is step for step the full one's up to there (its cube's lists hold
/// every cut that can raise it: they are cut by a lowest value at most its
/// own), so every gouge, depth and place is the full measurement's.
void visit_leaf_measured(const Pass &p, Leaf &leaf, Block &b, GridProbe *design, ConstAcc *dacc,
                         VisitScratch &vs) {
  RemoveScratch &w = p.s.scratch;
  const bool volumes = p.measure->volumes;
  const double far = volumes ? p.voxel : gouge_floor(p);
  if (design && dacc && design_far(p, *dacc, b.origin, far)) design = nullptr;
  if (!volumes && design == nullptr) { // gouges only, and none can be found here
    visit_leaf(p, leaf, b, vs.oct);
    return;
  }
  const float *data = leaf.buffer().data();
  float old[Leaf::SIZE];
  std::memcpy(old, data, sizeof old);
  uint32_t arg[Leaf::SIZE]; // the cut each changed voxel's final value came from
  std::fill_n(arg, Leaf::SIZE, UINT32_MAX);
  OctantPlanes &planes = vs.planes;
  planes.reset(b.count);
  visit_leaf(p, leaf, b, vs.oct, arg, &planes);
  const double half = 0.5 * p.voxel, bg = p.bgf, rv = 0.5 * std::sqrt(3.0) * p.voxel;
  const double tie = kTie * p.voxel;
  const swarf_stock *ds = p.measure->design;
  const double floor = design ? -p.voxel : -half, deep = design ? p.voxel : half;
  CubeCuts &cubes = vs.cubes;
  cubes.reset(b);
  cubes.planes = p.flat ? nullptr : &planes;
  auto cube_of = [](openvdb::Index n) {
    return int(((n >> 7) << 4) | (((n >> 4) & 3) << 2) | ((n >> 1) & 3)); // x>>1, y>>1, z>>1
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  uint16_t list[Leaf::SIZE]; // the voxels to replay
  double dqs[Leaf::SIZE];    // gouges only: their design values (else NaN: asked when needed)
  size_t count = 0;
  for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
    double dq = nan;
    if (volumes) { // the voxels whose fraction changed
      if (!(data[n] > old[n] && old[n] < half && data[n] > -half)) continue;
    } else { // those that crossed from material to air where the design may be gouged
      if (!(old[n] < -tie && data[n] > -tie)) continue;
      const Coord l = Leaf::offsetToLocalCoord(n);
      dq = design->at(block_point(p, b.origin, l.x(), l.y(), l.z()));
      if (!(dq < far)) continue;
    }
    double &lo = cubes.low[cube_of(n)];
    lo = std::min(lo, std::max(double(old[n]), floor));
    dqs[count] = dq;
    list[count++] = uint16_t(n);
  }
  for (size_t at = 0; at < count; at++) {
    const openvdb::Index n = list[at];
    const Coord l = Leaf::offsetToLocalCoord(n);
    const int cube = cube_of(n);
    const Vec3d q = block_point(p, b.origin, l.x(), l.y(), l.z());
    double v = std::max(double(old[n]), floor), dq = dqs[at];
    bool dq_exact = false; // dq made exact beyond the band, if it is
    // No cut raises the voxel beyond its final value (the maximum the plain
    // visit stored): the replay ends there, or where the voxel is empty; for
    // the gouges only, where it has no material left (a gouge needs some).
    const double end = volumes ? std::min(half, double(data[n])) : 0.0;
    CubeCuts::Entry e;
    for (size_t k = 0; v < end && cubes.get(p, b, cube, k, e); k++) {
      const uint32_t i = e.pair;
      if (!may_raise(v, bg, w.centre_sdf[i], p.radius[n]) || e.d - rv + v >= kMargin)
        continue; // the bounds from the block's and the cube's centres: no raise
      if (e.plane != 0) {
        const CubeCuts::Entry &pe = cubes.with_plane(p, b, cube, k);
        if (pe.plane == 1 && pe.at(l, half) + v >= kMargin)
          continue; // nor by the cut's supporting plane at the cube's centre
      }
      const swarf_stock_cut &cut = p.cuts[w.pairs[i].cut];
      double d, nv;
      if (-e.d - rv - kMargin >= deep) { // emptied, deeper than anything measured
        d = deep, nv = deep;
        w.removed[i] += inside_fraction(v, p.voxel);
      } else if (w.pairs[i].cut == arg[n] && (cut.range == nullptr || p.plain) &&
                 !(design && v < 0.0)) {
        // The cut the plain visit took the final value from (by the same sdf
        // at the same point): its step ends there, unevaluated. (A gouge
        // needs its sdf: evaluated below.)
        d = nv = double(data[n]);
        if (!(nv > v)) continue;
        w.removed[i] += inside_fraction(v, p.voxel) - inside_fraction(nv, p.voxel);
      } else {
        d = -cut.sdf(cut.ctx, q.x(), q.y(), q.z());
        nv = stored(d, p.bgf);
        if (!(nv > v)) continue;
        w.removed[i] += inside_fraction(v, p.voxel) - inside_fraction(nv, p.voxel);
      }
      if (design && v < -tie && d > -tie) {
        if (!dq_exact) {
          if (std::isnan(dq)) dq = design->at(q);
          // Beyond the band of a design read from a mesh: its exact depth.
          if (ds->surface && dq <= -double(ds->background) * (1.0 - 1e-6))
            dq = -surface_distance(*ds, q);
          dq_exact = true;
        }
        const double depth = gouge_depth(*ds, dq, std::min(d, -v), p.voxel);
        if (depth > p.measure->tolerance && depth > w.gouge[i])
          w.gouge[i] = depth, w.gouge_at[i] = q;
      }
      v = nv;
    }
  }
}

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

/// First voxel of the block at o lying deeper than depth in both the
/// material and the cut; false if none. Blocks the cut's Lipschitz bound
/// keeps away, and blocks without material, are passed over whole.
bool block_overlap(const Pass &p, ConstAcc &acc, const Coord &o, double depth, Vec3d &where) {
  const swarf_stock_cut &cut = p.cuts[0];
  const Vec3d c = block_point(p, o, 3.5, 3.5, 3.5);
  const double dc = cut.sdf(cut.ctx, c.x(), c.y(), c.z());
  if (dc - (p.reach - p.bgf) >= -depth) return false; // no voxel of it is that deep in the cut
  const Leaf *leaf = acc.probeConstLeaf(o);
  if (leaf == nullptr) { // a tile: all material (-w) or all outside (+w)
    if (!(acc.getValue(o) < -depth)) return false;
    for (int x = 0; x < 8; x++)
      for (int y = 0; y < 8; y++)
        for (int z = 0; z < 8; z++) {
          const Vec3d q = block_point(p, o, x, y, z);
          if (cut.sdf(cut.ctx, q.x(), q.y(), q.z()) < -depth) {
            where = q;
            return true;
          }
        }
    return false;
  }
  const float *v = leaf->buffer().data();
  for (int x = 0; x < 8; x++)
    for (int y = 0; y < 8; y++)
      for (int z = 0; z < 8; z++) {
        if (!(v[(x << 6) | (y << 3) | z] < -depth)) continue;
        const Vec3d q = block_point(p, o, x, y, z);
        if (cut.sdf(cut.ctx, q.x(), q.y(), q.z()) < -depth) {
          where = q;
          return true;
        }
      }
  return false;
}

/// Whether every cleared volume's sdf exceeds t at q (false as soon as one
/// does not). A volume lies inside its bounds, so its sdf is at least the
/// distance to them: those farther than t are passed over unevaluated.
inline bool cleared_enough(const swarf_stock_cut *clear, size_t n, const Vec3d &q, double t) {
  for (size_t i = 0; i < n; i++) {
    const swarf_stock_cut &c = clear[i];
    double d2 = 0;
    for (int k = 0; k < 3; k++) {
      const double o = std::max(c.lo[k] - q[k], q[k] - c.hi[k]);
      if (o > 0) d2 += o * o;
    }
    if (t < 0 ? d2 > 0 || c.sdf(c.ctx, q.x(), q.y(), q.z()) > t
              : d2 > t * t || c.sdf(c.ctx, q.x(), q.y(), q.z()) > t)
      continue;
    return false;
  }
  return true;
}

/// First voxel of the block at o whose score min(-v, clear) - sdf (v: the
/// stock value, at most half a voxel outside; clear: the sdf of a volume already cut away,
/// +inf without one) exceeds depth (see stock.h); false if none. A voxel
/// scores at most -v + (r - dc) (r: its distance to the block centre, dc:
/// the cut's sdf there), so blocks and voxels the Lipschitz bound keeps below
/// depth are passed over without evaluating the cut.
bool block_penetrates(const Pass &p, const swarf_stock_cut *clear, size_t nclear, ConstAcc &acc,
                      const Coord &o, double depth, Vec3d &where) {
  const swarf_stock_cut &cut = p.cuts[0];
  const Vec3d c = block_point(p, o, 3.5, 3.5, 3.5);
  const double dc = cut.sdf(cut.ctx, c.x(), c.y(), c.z()), r = p.reach - p.bgf;
  if (p.bgf + r - dc <= depth) return false;
  const Leaf *leaf = acc.probeConstLeaf(o);
  const float tile = leaf == nullptr ? acc.getValue(o) : 0.0f;
  if (leaf == nullptr && !(tile < 0.0f)) return false; // an outside tile
  const float *v = leaf != nullptr ? leaf->buffer().data() : nullptr;
  const double out = 0.5 * p.voxel;
  for (int x = 0; x < 8; x++)
    for (int y = 0; y < 8; y++)
      for (int z = 0; z < 8; z++) {
        const openvdb::Index n = (x << 6) | (y << 3) | z;
        const double val = v != nullptr ? v[n] : tile;
        if (!(val <= out) || -val + p.radius[n] - dc <= depth) continue;
        const Vec3d q = block_point(p, o, x, y, z);
        const double d = cut.sdf(cut.ctx, q.x(), q.y(), q.z());
        if (!(-val - d > depth)) continue;
        if (!cleared_enough(clear, nclear, q, d + depth)) continue;
        where = q;
        return true;
      }
  return false;
}

} // namespace

/// True if the cut penetrates the material by more than depth (see stock.h).
bool cut_penetrates(const swarf_stock &s, const swarf_stock_cut &cut, const swarf_stock_cut *clear,
                    size_t nclear, double depth, Vec3d &where) {
  Pass p{const_cast<swarf_stock &>(s), &cut, s.voxel, s.background, 0.0, {}, {}, {}};
  init_pass(p);
  Coord a, b;
  if (!cut_blocks(p, cut, a, b)) return false;
  ConstAcc acc(s.grid->constTree());
  for (int x = a.x(); x <= b.x(); x += 8)
    for (int y = a.y(); y <= b.y(); y += 8)
      for (int z = a.z(); z <= b.z(); z += 8)
        if (block_penetrates(p, clear, nclear, acc, Coord(x, y, z), depth, where)) return true;
  return false;
}

/// True if the cut overlaps the material deeper than depth (see stock.h).
bool cut_overlaps(const swarf_stock &s, const swarf_stock_cut &cut, double depth, Vec3d &where) {
  Pass p{const_cast<swarf_stock &>(s), &cut, s.voxel, s.background, 0.0, {}, {}, {}};
  init_pass(p);
  Coord a, b;
  if (!cut_blocks(p, cut, a, b)) return false;
  ConstAcc acc(s.grid->constTree());
  for (int x = a.x(); x <= b.x(); x += 8)
    for (int y = a.y(); y <= b.y(); y += 8)
      for (int z = a.z(); z <= b.z(); z += 8)
        if (block_overlap(p, acc, Coord(x, y, z), depth, where)) return true;
  return false;
}

/// Deepest gouge of the cut into the design where the stock has material (see stock.h).
double cut_gouge(const swarf_stock &s, const swarf_stock &design, const swarf_stock_cut &cut,
                 double tolerance, Vec3d &where) {
  Pass p{const_cast<swarf_stock &>(s), &cut, s.voxel, s.background, 0.0, {}, {}, {}};
  init_pass(p);
  Coord a, b;
  double best = 0.0;
  if (!cut_blocks(p, cut, a, b)) return best;
  ConstAcc acc(s.grid->constTree());
  GridProbe probe(design, s);
  const double half_diagonal = p.reach - p.bgf;
  for (int x = a.x(); x <= b.x(); x += 8)
    for (int y = a.y(); y <= b.y(); y += 8)
      for (int z = a.z(); z <= b.z(); z += 8) {
        const Coord o(x, y, z);
        const Vec3d c = block_point(p, o, 3.5, 3.5, 3.5);
        if (cut.sdf(cut.ctx, c.x(), c.y(), c.z()) - half_diagonal >= 0.0)
          continue; // no centre in the cut
        const Leaf *leaf = acc.probeConstLeaf(o);
        const float tile = leaf ? 0.0f : acc.getValue(o);
        if (!leaf && !(tile < 0.0f)) continue;
        for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
          const double v = leaf ? leaf->getValue(n) : tile;
          if (!(v < -kTie * p.voxel)) continue;
          const Coord l = Leaf::offsetToLocalCoord(n);
          const Vec3d q = block_point(p, o, l.x(), l.y(), l.z());
          const double d = -cut.sdf(cut.ctx, q.x(), q.y(), q.z());
          if (!(d > -kTie * p.voxel)) continue;
          double dq = probe.at(q);
          if (design.surface && dq <= -double(design.background) * (1.0 - 1e-6))
            dq = -surface_distance(design, q);
          const double depth = gouge_depth(design, dq, std::min(d, -v), p.voxel);
          if (depth > tolerance && depth > best) best = depth, where = q;
        }
      }
  return best;
}

void remove_cuts(swarf_stock &s, const swarf_stock_cut *cuts, size_t ncuts, const Measure *measure,
                 const swarf_stock_support_fn *support) {
  static const bool plain = [] {
    const char *e = std::getenv("SWARF_REMOVE_PLAIN");
    return e != nullptr && e[0] == '1';
  }();
  static const bool flat = [] {
    const char *e = std::getenv("SWARF_REMOVE_FLAT");
    return e != nullptr && e[0] == '1';
  }();
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
    VisitScratch &vs = visit_scratch();
    std::unique_ptr<Leaf> &scratch = vs.tile;
    for (size_t i = r.begin(); i != r.end(); ++i) {
      Block &b = w.blocks[w.visit[i]];
      const bool was_tile = b.action == kVisitTile;
      Leaf *leaf = was_tile ? nullptr : acc.probeLeaf(b.origin);
      if (was_tile) {
        if (!scratch) scratch.reset(new Leaf());
        scratch->setOrigin(b.origin);
        scratch->fill(b.tile, b.tile_on);
        leaf = scratch.get();
      }
      if (measure)
        visit_leaf_measured(p, *leaf, b, design.get(), dacc.get(), vs);
      else
        visit_leaf(p, *leaf, b, vs.oct);
      if (was_tile && b.action != kCollapse) w.fresh[i].reset(new Leaf(*leaf));
    }
  });
  collapse(p);
  if (measure) report_effects(p, ncuts);
}

} // namespace swarf

namespace {

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

} // namespace

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
    check_cut(cut, 0);
    swarf::in_arena(*s, [&] { swarf::remove_cuts(*s, &cut, 1); });
  });
}

extern "C" swarf_status swarf_stock_overlaps(const swarf_stock *s, const swarf_stock_cut *cut,
                                             double depth, int *hit, double where[3],
                                             swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || cut == nullptr || hit == nullptr)
      throw swarf::Error(SWARF_ERR_ARG, "stock, cut or hit is NULL");
    *hit = 0;
    check_cut(*cut, 0);
    if (!(depth >= 0.0 && depth < s->background))
      throw swarf::Error(SWARF_ERR_ARG, "depth must be >= 0 and below the band half-width");
    openvdb::Vec3d q;
    *hit = swarf::cut_overlaps(*s, *cut, depth, q) ? 1 : 0;
    if (*hit && where != nullptr)
      for (int k = 0; k < 3; k++)
        where[k] = q[k];
  });
}

extern "C" swarf_status swarf_stock_penetrates(const swarf_stock *s, const swarf_stock_cut *cut,
                                               const swarf_stock_cut *clear, size_t nclear,
                                               double depth, int *hit, double where[3],
                                               swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || cut == nullptr || hit == nullptr)
      throw swarf::Error(SWARF_ERR_ARG, "stock, cut or hit is NULL");
    *hit = 0;
    check_cut(*cut, 0);
    if (!(depth >= 0.0 && std::isfinite(depth)))
      throw swarf::Error(SWARF_ERR_ARG, "depth must be finite and >= 0");
    openvdb::Vec3d q;
    if (nclear > 0 && clear == nullptr) throw swarf::Error(SWARF_ERR_ARG, "clear is NULL");
    for (size_t i = 0; i < nclear; i++)
      check_cut(clear[i], i);
    *hit = swarf::cut_penetrates(*s, *cut, clear, nclear, depth, q) ? 1 : 0;
    if (*hit && where != nullptr)
      for (int k = 0; k < 3; k++)
        where[k] = q[k];
  });
}

extern "C" swarf_status swarf_stock_remove_batch(swarf_stock *s, const swarf_stock_cut *cuts,
                                                 size_t ncuts, swarf_error *err) {
  return swarf_stock_remove_batch_support(s, cuts, nullptr, ncuts, err);
}

extern "C" swarf_status swarf_stock_gouge(const swarf_stock *s, const swarf_stock *design,
                                          const swarf_stock_cut *cut, double tolerance,
                                          double *depth, double where[3], swarf_error *err) {
  if (depth) *depth = 0.0;
  if (where) where[0] = where[1] = where[2] = std::numeric_limits<double>::quiet_NaN();
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || design == nullptr || cut == nullptr || depth == nullptr)
      throw swarf::Error(SWARF_ERR_ARG, "stock, design, cut or depth is NULL");
    check_cut(*cut, 0);
    if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
      throw swarf::Error(SWARF_ERR_ARG, "tolerance must be finite and >= 0");
    openvdb::Vec3d q;
    *depth = swarf::cut_gouge(*s, *design, *cut, tolerance, q);
    if (*depth > 0.0 && where != nullptr)
      for (int k = 0; k < 3; k++)
        where[k] = q[k];
  });
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
      check_cut(cuts[i], i);
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
      check_cut(cuts[i], i);
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
