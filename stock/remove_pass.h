/* SPDX-License-Identifier: MPL-2.0 */
/// @file remove_pass.h
/// @brief What the files of the removal share (remove.cc: the passes in
/// order and the entry points; remove_blocks.cc: which blocks the cuts meet
/// and what becomes of them; remove_visit.cc: the voxels of a block;
/// remove_replay.cc: the same, measured; remove_query.cc: the read-only
/// questions, overlap, penetration, gouge): a pass's frame and band, the
/// margins of its hierarchical tests, and the steps each file gives the
/// others.
#ifndef SWARF_STOCK_REMOVE_PASS_H
#define SWARF_STOCK_REMOVE_PASS_H

#include <openvdb/tree/ValueAccessor.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "stock_private.h"

namespace swarf {
namespace removal {

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
  double voxel;             ///< mm
  float bgf;                ///< band half-width (the background), mm
  double reach;             ///< half diagonal of a block plus the band, mm
  float radius[Leaf::SIZE]; ///< distance (mm) from each voxel centre to the block centre
  double roct[Leaf::SIZE];  ///< distance (mm) from each voxel centre to its octant's centre
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

/// cut_value at the centre q of voxels at most r away, with the plane the cut's
/// range_plane function gives there when it has one: true when given, with
/// sdf(voxel) >= pd + g.(voxel - q) for those voxels (stock.h).
inline bool cut_value_plane(const Pass &p, const swarf_stock_cut &cut, const Vec3d &q, double lo,
                            double hi, double r, double &d, double &pd, double g[3]) {
  if (cut.range_plane == nullptr || cut.range == nullptr || p.plain || !(lo < hi)) {
    d = cut_value(p, cut, q, lo, hi);
    return false;
  }
  const double qq[3] = {q.x(), q.y(), q.z()};
  return cut.range_plane(cut.ctx, qq, lo, hi, r, &d, &pd, g) == 1;
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

/// Measured: what the plain visit learnt of the block's cuts at each 4^3
/// octant's centre, for the replay (visit_leaf_measured), per octant and pair
/// (index - the block's first): whether the cut may raise a voxel of the
/// octant at all (the block centre's bound), and its supporting plane there.
struct OctantPlanes {
  enum : uint8_t { kOut, kNoPlane, kPlane };
  struct Entry {
    uint8_t state; ///< kOut: no voxel of the octant can be raised (from the block's values)
    double d;      ///< kPlane: sdf(q) >= d + g.(q - centre) for every voxel q of the octant
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

/// Whether voxel n (value m, at distance r from a point where the cut's sdf is
/// d) may be raised by the cut: not already outside, and the Lipschitz bound
/// d - r does not keep -sdf at or below m.
inline bool may_raise(double m, double bg, double d, double r) {
  return m < bg && !(d - r + m >= kMargin); // a NaN sdf: the voxels decide
}

/// A thread's scratch for the octants' visits (remove_visit.cc).
struct OctScratch;
/// Pass 4 for one leaf, plain: max over the cuts, clamp, band state; with
/// arg, the cut each raised voxel's final value came from; with planes, what
/// the octants learnt of the cuts (remove_visit.cc).
void visit_leaf(const Pass &p, Leaf &leaf, Block &b, OctScratch &os, uint32_t *arg = nullptr,
                OctantPlanes *planes = nullptr);
/// Pass 4 for one leaf, measured: the plain visit, then the replay that
/// credits each cut (remove_replay.cc).
void visit_leaf_measured(const Pass &p, Leaf &leaf, Block &b, GridProbe *design, ConstAcc *dacc,
                         OctScratch &os);

/// A pass over the cuts: the per-voxel distances of its frame.
void init_pass(Pass &p);
/// The index range of the 8^3 blocks the cut's padded bounds meet inside the
/// stock's content box; false if none.
bool cut_blocks(const Pass &p, const swarf_stock_cut &c, Coord &bmin, Coord &bmax);
/// Pass 1: the (block, cut) pairs of the pass, sorted and grouped by block.
void list_pairs(Pass &p, size_t ncuts);
/// Pass 2: what the pass does to block b (dacc: the design's tree when it
/// shares the stock's lattice, else null).
void classify(const Pass &p, ConstAcc &acc, Block &b, ConstAcc *dacc);
/// Pass 3: cleared blocks become outside tiles (serial).
void change_topology(Pass &p);
/// Pass 4 for one block (remove_visit.cc).
void visit_block(const Pass &p, Acc &acc, Block &b, GridProbe *design, ConstAcc *dacc,
                 std::unique_ptr<Leaf> &fresh);
/// An argument check of the entry points: an sdf, finite bounds, lo < hi.
void check_cut(const swarf_stock_cut &c, size_t i);

} // namespace removal
} // namespace swarf

#endif
