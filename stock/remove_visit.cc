/* SPDX-License-Identifier: MPL-2.0 */
/// @file remove_visit.cc
/// @brief Pass 4 of a removal (remove.cc): the voxels of one block, top down
/// through its octants and cubes with their cuts' bounds (the plain visit;
/// remove_replay.cc replays it cut by cut when the removal is measured).
#include <algorithm>
#include <limits>
#include <utility>

#include "remove_pass.h"

namespace swarf {
namespace removal {

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
  bool plane = false; ///< sdf(q) >= pd + g.(q - centre) for every voxel q it is asked for
  double pd;          ///< the plane's value at the centre: d for a supporting plane, below
                      ///< it for a local one (range_plane; the Lipschitz bound may be better)
  double g[3];
};

/// Cut k's value at c, whose voxels lie at most r away, as the visits ask it:
/// its supporting plane where it has a support function (3-axis moves), else
/// cut_value_plane with the window (lo, hi) and, where the cut gives one, a
/// local plane.
inline void cut_at(const Pass &p, uint32_t k, const Vec3d &c, double lo, double hi, double r,
                   CutAt &o) {
  const swarf_stock_cut &cut = p.cuts[k];
  const swarf_stock_support_fn f = p.support ? p.support[k] : nullptr;
  o.cut = &cut;
  if (f != nullptr) {
    o.plane = f(cut.ctx, c.x(), c.y(), c.z(), &o.d, o.g) == 1;
    o.pd = o.d;
  } else {
    o.plane = cut_value_plane(p, cut, c, lo, hi, r, o.d, o.pd, o.g);
  }
}

/// An octant's cuts deepest first (a NaN sdf first), sorted lazily: the
/// cubes walk the order from its start and most stop after a few cuts, so
/// the order is drawn from a heap only as far as some cube reads it
/// (with 1024 moves a batch, a full sort of every octant's cuts took 12 % of
/// bear.nc at 0.2 mm).
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
  const double base = c.plane ? c.pd : c.d, lip = c.plane && c.pd < c.d ? c.d - rv : -HUGE_VAL;
  double mlo = std::numeric_limits<double>::infinity();
  for (int x = x0; x < x0 + 2; x++)
    for (int y = y0; y < y0 + 2; y++)
      for (int z = z0; z < z0 + 2; z++) {
        const openvdb::Index n = (x << 6) | (y << 3) | z;
        double &m = bv.m[n];
        const double bound =
            std::max(base + (x > x0 ? gx : -gx) + (y > y0 ? gy : -gy) + (z > z0 ? gz : -gz), lip);
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
/// value (o.pd + o.g.(voxel - centre) is a lower bound of the sdf: may_raise
/// false for each voxel): at once when the plane's least value over the cube
/// does so for the cube's lowest value, else voxel by voxel.
inline bool plane_keeps_below(const Pass &p, const BlockValues &bv, const CutAt &o, int x0, int y0,
                              int z0) {
  const double bg = p.bgf, v = p.voxel;
  // the cube's first voxel's offset from the octant's centre, in voxels
  const double ox = (x0 & 3) - 1.5, oy = (y0 & 3) - 1.5, oz = (z0 & 3) - 1.5;
  const double least = o.pd + v * (std::min(o.g[0] * ox, o.g[0] * (ox + 1.0)) +
                                   std::min(o.g[1] * oy, o.g[1] * (oy + 1.0)) +
                                   std::min(o.g[2] * oz, o.g[2] * (oz + 1.0)));
  if (least + bv.mlo[((x0 >> 1) << 4) | ((y0 >> 1) << 2) | (z0 >> 1)] >= kMargin) return true;
  for (int x = 0; x < 2; x++)
    for (int y = 0; y < 2; y++)
      for (int z = 0; z < 2; z++) {
        const double m = bv.m[((x0 + x) << 6) | ((y0 + y) << 3) | (z0 + z)];
        const double bound = o.pd + v * (o.g[0] * (ox + x) + o.g[1] * (oy + y) + o.g[2] * (oz + z));
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
    cut_at(p, uint32_t(o.cut - p.cuts), c, cube_lo, cube_hi, rv, k);
    if (k.d - rv + bv.mlo[ci] >= kMargin) continue; // may_raise, for the lowest value: false
    visit_cube(p, b, k, x0, y0, z0, bv);
  }
}

/// The lowest of g.(q - centre) over a 4^3 octant's voxels q, whose offsets
/// from the centre are lo[a] to lo[a] + 3 voxels per axis.
inline double plane_low(const Vec3d &g, const double lo[3], double voxel) {
  double s = 0.0;
  for (int a = 0; a < 3; a++)
    s += std::min(g[a] * lo[a], g[a] * (lo[a] + 3.0));
  return voxel * s;
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
  const double roct = 1.5 * std::sqrt(3.0) * p.voxel; // the centre's farthest voxel
  const double oct_lo = -double(p.bgf) - kMargin - rcube - rv;
  double oct_hi = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < 8; k++)
    oct_hi = std::max(
        oct_hi, kMargin - bv.cmin[(((x0 >> 1) + (k >> 2)) << 4) |
                                  (((y0 >> 1) + ((k >> 1) & 1)) << 2) | ((z0 >> 1) + (k & 1))]);
  uint32_t n = 0;
  const int octant = ((x0 >> 2) << 2) | ((y0 >> 2) << 1) | (z0 >> 2);
  // the octant's lowest value below the band (its voxels are not yet raised:
  // the summaries of its cubes hold their starting values)
  double mlo = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 8; k++)
    mlo = std::min(mlo, bv.mlo[(((x0 >> 1) + (k >> 2)) << 4) | (((y0 >> 1) + ((k >> 1) & 1)) << 2) |
                               ((z0 >> 1) + (k & 1))]);
  // the octant's voxels' offsets from the block's centre, per axis (voxels)
  const double lo[3] = {x0 - 3.5, y0 - 3.5, z0 - 3.5};
  for (uint32_t i = b.begin; i < b.begin + b.count; i++) {
    // the bound from the block's centre, or its supporting plane there
    const Vec3d &g = w.centre_plane[i];
    const bool below =
        w.centre_sdf[i] + omin >= kMargin || // a NaN sdf: visited
        (!std::isnan(g[0]) && w.centre_sdf[i] + plane_low(g, lo, p.voxel) + mlo >= kMargin);
    if (below) {
      if (bv.planes != nullptr) bv.planes->at(octant, i - b.begin).state = OctantPlanes::kOut;
      continue;
    }
    CutAt &o = oct[n++];
    cut_at(p, w.pairs[i].cut, c, oct_lo, oct_hi, roct, o);
    if (bv.planes != nullptr) {
      OctantPlanes::Entry &r = bv.planes->at(octant, i - b.begin);
      r.state = o.plane ? OctantPlanes::kPlane : OctantPlanes::kNoPlane;
      r.d = o.pd;
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
void visit_leaf(const Pass &p, Leaf &leaf, Block &b, OctScratch &os, uint32_t *arg,
                OctantPlanes *planes) {
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

/// A thread's scratch for the visits (remove_cuts takes it once per task).
struct VisitScratch {
  OctScratch oct;
  std::unique_ptr<Leaf> tile; ///< a tile's block, until it proves a leaf
};

/// This thread's VisitScratch. Not inlined: GCC otherwise propagates the
/// thread_local into the visit and asks __tls_get_addr for its address at
/// each use in the loops (4 % of a measured run's instructions).
__attribute__((noinline)) VisitScratch &visit_scratch() {
  thread_local VisitScratch vs;
  return vs;
}

/// Pass 4 for one block: its leaf (a tile's block in this thread's scratch
/// leaf, filled from the tile), visited plain or measured; a tile's block that
/// did not collapse gets a leaf of its own in `fresh`.
void visit_block(const Pass &p, Acc &acc, Block &b, GridProbe *design, ConstAcc *dacc,
                 std::unique_ptr<Leaf> &fresh) {
  VisitScratch &vs = visit_scratch();
  std::unique_ptr<Leaf> &scratch = vs.tile;
  const bool was_tile = b.action == kVisitTile;
  Leaf *leaf = was_tile ? nullptr : acc.probeLeaf(b.origin);
  if (was_tile) {
    if (!scratch) scratch.reset(new Leaf());
    scratch->setOrigin(b.origin);
    scratch->fill(b.tile, b.tile_on);
    leaf = scratch.get();
  }
  if (p.measure)
    visit_leaf_measured(p, *leaf, b, design, dacc, vs.oct);
  else
    visit_leaf(p, *leaf, b, vs.oct);
  if (was_tile && b.action != kCollapse) fresh.reset(new Leaf(*leaf));
}

} // namespace removal
} // namespace swarf
