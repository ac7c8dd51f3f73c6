/* SPDX-License-Identifier: MPL-2.0 */
/// @file remove_blocks.cc
/// @brief Passes 1 to 3 of a removal (remove.cc): the (block, cut) pairs,
/// each block's action from its cuts' values at its centre, and the blocks
/// cleared whole turned into outside tiles.
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <utility>

#include "remove_pass.h"

namespace swarf {
namespace removal {

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

/// The pairs (made cut by cut: list_pairs) in pair_less order by a counting
/// sort on their block, when the blocks' box holds at most kSlots blocks: a
/// histogram, its prefix sums, one scatter. Stable, so each block's cuts stay
/// in the order made. False (nothing done) for a larger box. The pairs of a
/// big batch (millions at 0.1 mm) are counted and scattered in chunks on the
/// stock's threads, each chunk's elements of a block after the previous
/// chunk's: the order a serial pass gives.
bool counting_sort(ScratchVector<BlockCut> &pairs, const int32_t lo[3], const int32_t hi[3]) {
  constexpr uint64_t kSlots = uint64_t(1) << 20; // 4 MB of counts
  const uint64_t ny = uint64_t(hi[1] - lo[1]) / 8 + 1, nz = uint64_t(hi[2] - lo[2]) / 8 + 1;
  const uint64_t slots = (uint64_t(hi[0] - lo[0]) / 8 + 1) * ny * nz;
  if (slots > kSlots || pairs.size() >= (uint64_t(1) << 32)) return false;
  auto slot = [&](const BlockCut &q) {
    return ((uint64_t(q.x - lo[0]) >> 3) * ny + (uint64_t(q.y - lo[1]) >> 3)) * nz +
           (uint64_t(q.z - lo[2]) >> 3);
  };
  // chunks of at least 64 k pairs, at most 16, their counts within 4 MB
  const size_t np = pairs.size();
  const size_t nchunk = slots <= (uint64_t(1) << 16) ? std::clamp<size_t>(np >> 16, 1, 16) : 1;
  thread_local std::vector<uint32_t> count_v; // this thread's buffers
  thread_local ScratchVector<BlockCut> sorted;
  count_v.assign(nchunk * slots, 0);
  sorted.resize(np);
  uint32_t *const count = count_v.data(); // the workers see the caller's buffers through these
  const BlockCut *const in = pairs.data();
  BlockCut *const out = sorted.data();
  auto first = [&](size_t c) { return c * np / nchunk; };
  tbb::parallel_for(size_t(0), nchunk, [&](size_t c) {
    uint32_t *n = count + c * slots;
    for (size_t i = first(c); i < first(c + 1); i++)
      n[slot(in[i])]++;
  });
  uint32_t at = 0; // each (slot, chunk)'s first place, slot by slot
  for (uint64_t k = 0; k < slots; k++)
    for (size_t c = 0; c < nchunk; c++) {
      const uint32_t n = count[c * slots + k];
      count[c * slots + k] = at;
      at += n;
    }
  tbb::parallel_for(size_t(0), nchunk, [&](size_t c) {
    uint32_t *n = count + c * slots;
    for (size_t i = first(c); i < first(c + 1); i++)
      out[n[slot(in[i])]++] = in[i];
  });
  pairs.swap(sorted);
  return true;
}

/// The pairs (made cut by cut) in pair_less order. Where the blocks' span and
/// the cuts fit in 16 bits each (always, in a simulation's batches): by a
/// counting sort on the block (counting_sort; the tiger at 0.5 mm spent 5 %
/// of its time in a comparison sort), or, for a box of more blocks, sorted as
/// 64-bit keys (block offsets from the least block, then the cut): 2x faster
/// than the comparison of the fields.
void sort_pairs(ScratchVector<BlockCut> &pairs, size_t ncuts) {
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
  if (counting_sort(pairs, lo, hi)) return;
  thread_local ScratchVector<uint64_t> keys_v; // this thread's buffer
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
  w.pairs.resize(at[ncuts]); // written below, in parallel
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
  w.centre_plane.resize(w.pairs.size());
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
    const swarf_stock_support_fn f = p.support ? p.support[w.pairs[i].cut] : nullptr;
    // with a support function, the sdf and, where it has one, its plane (the
    // octants the plane keeps below their values are passed over)
    double d, g[3] = {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0};
    if (f == nullptr || f(cut.ctx, c.x(), c.y(), c.z(), &d, g) != 1) {
      if (f == nullptr) d = cut_value(p, cut, c, -p.reach - kMargin, p.reach + kMargin);
      g[0] = std::numeric_limits<double>::quiet_NaN();
    }
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
    w.centre_plane[b.begin + kept] = Vec3d(g[0], g[1], g[2]);
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

} // namespace removal
} // namespace swarf
