/* SPDX-License-Identifier: MPL-2.0 */
/// @file remove_visit.cc
/// @brief Pass 4 of a removal (remove.cc): the voxels of one block, top down
/// through its octants and cubes with their cuts' bounds (the plain visit),
/// and the measured visit that replays the voxels whose inside fraction
/// changed cut by cut, crediting each cut's removed volume and gouges.
#include <algorithm>
#include <cstring>
#include <limits>
#include <utility>

#include "remove_pass.h"

namespace swarf {
namespace removal {

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
  uint32_t next[64]; ///< the next pair to look at, an index into its octant's pairs
  /// Per octant, once a cube of it asks: the pairs that may raise a voxel of
  /// any of its cubes (the bound from the block's centre with the octant's
  /// farthest cube and lowest value; the plain visit's verdict there).
  std::vector<uint32_t> pairs[8];
  bool listed[8];
  double low[64]; ///< lowest starting value of the cube's changed voxels (+inf: none)
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
  void reset() {
    for (int c = 0; c < 64; c++) {
      list[c].clear();
      next[c] = 0;
      low[c] = std::numeric_limits<double>::infinity();
    }
    std::fill_n(listed, 8, false);
  }
  /// The pairs of octant o (its cubes' low values known): those that pass
  /// what get tests first with the bounds of all its cubes at once.
  void list_octant(const Pass &p, const Block &b, int o) {
    const RemoveScratch &w = p.s.scratch;
    double r = 0.0, lo = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 8; k++) {
      const int c = ((((o >> 2) << 1) | (k >> 2)) << 4) |
                    (((((o >> 1) & 1) << 1) | ((k >> 1) & 1)) << 2) | (((o & 1) << 1) | (k & 1));
      if (low[c] < lo) lo = low[c];
      if (low[c] < std::numeric_limits<double>::infinity() && p.rcube[c] > r) r = p.rcube[c];
    }
    pairs[o].clear();
    for (uint32_t i = b.begin; i < b.begin + b.count; i++) {
      // for each cube c: centre_sdf - rcube[c] + low[c] >= that (rounding is monotone)
      if (w.centre_sdf[i] - r + lo >= kMargin) continue; // a NaN: looked at
      if (planes != nullptr && planes->at(o, i - b.begin).state == OctantPlanes::kOut) continue;
      pairs[o].push_back(i);
    }
    listed[o] = true;
  }
  /// Entry k of cube c's list, found if needed; null when there is none.
  /// (Valid until the next call: the list may grow.)
  Entry *get(const Pass &p, const Block &b, int c, size_t k) {
    const RemoveScratch &w = p.s.scratch;
    const double rv = 0.5 * std::sqrt(3.0) * p.voxel;
    const int o = octant_of(c);
    if (!listed[o]) list_octant(p, b, o);
    while (list[c].size() <= k) {
      if (next[c] >= pairs[o].size()) return nullptr;
      const uint32_t i = pairs[o][next[c]++];
      if (w.centre_sdf[i] - p.rcube[c] + low[c] >= kMargin) continue; // a NaN: looked at
      if (planes != nullptr && octant_keeps_below(p, planes->at(o, i - b.begin), c)) continue;
      const swarf_stock_cut &cut = p.cuts[w.pairs[i].cut];
      const Vec3d q = centre(p, b, c);
      const double d = cut.sdf(cut.ctx, q.x(), q.y(), q.z());
      if (d - rv + low[c] >= kMargin) continue;
      // a plane only outside the cut (its support function's rule)
      const bool ask = p.support != nullptr && p.support[w.pairs[i].cut] != nullptr && d > 0.0;
      list[c].push_back({i, d, ask ? -1 : 0, {0.0, 0.0, 0.0}});
    }
    return &list[c][k];
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

/// One voxel of a block's replay (visit_leaf_measured): its index and place,
/// its value as the cuts are replayed in program order, the value where its
/// replay ends, and its design value (NaN: asked when needed; dq_exact: made
/// exact beyond the band, where it is).
struct ReplayVoxel {
  openvdb::Index n;
  Coord l;
  Vec3d q;
  double v, end, dq;
  bool dq_exact;
};

/// What a block's replay shares across its cubes.
struct Replay {
  const Pass &p;
  const Block &b;
  const float *data;   ///< the block's final values (the plain visit's)
  const uint32_t *arg; ///< per voxel, the cut its final value came from
  GridProbe *design;   ///< null: no gouge can be found in the block
  double half, rv;     ///< half a voxel; a voxel's distance to its cube's centre
  double tie;          ///< kTie voxels
  double deep;         ///< the value beyond which nothing more is measured
};

/// The 2^3 cube of voxel n, index (x >> 1) << 4 | (y >> 1) << 2 | z >> 1.
inline int cube_of(openvdb::Index n) {
  return int(((n >> 7) << 4) | (((n >> 4) & 3) << 2) | ((n >> 1) & 3));
}

/// Whether place a comes before place b (x, then y, then z): within a block,
/// the order of the voxels' indices.
inline bool before(const Vec3d &a, const Vec3d &b) {
  return a.x() != b.x() ? a.x() < b.x() : a.y() != b.y() ? a.y() < b.y() : a.z() < b.z();
}

/// One step of voxel x's replay: entry k of cube c's list, whose bounds from
/// the block's and the cube's centres did not pass it over. Credits the cut
/// with the inside fraction it removes and checks it for a gouge.
void replay_step(const Replay &r, CubeCuts &cubes, int c, size_t k, ReplayVoxel &x) {
  const Pass &p = r.p;
  RemoveScratch &w = p.s.scratch;
  const CubeCuts::Entry &e = cubes.list[c][k];
  const double ed = e.d; // as read before its plane is asked for (which sets d again)
  const uint32_t i = e.pair;
  if (e.plane != 0) {
    const CubeCuts::Entry &pe = cubes.with_plane(p, r.b, c, k);
    if (pe.plane == 1 && pe.at(x.l, r.half) + x.v >= kMargin)
      return; // nor by the cut's supporting plane at the cube's centre
  }
  const swarf_stock_cut &cut = p.cuts[w.pairs[i].cut];
  const double v = x.v;
  double d, nv;
  if (-ed - r.rv - kMargin >= r.deep) { // emptied, deeper than anything measured
    d = r.deep, nv = r.deep;
    w.removed[i] += inside_fraction(v, p.voxel);
  } else if (w.pairs[i].cut == r.arg[x.n] && (cut.range == nullptr || p.plain) &&
             !(r.design && v < 0.0)) {
    // The cut the plain visit took the final value from (by the same sdf at
    // the same point): its step ends there, unevaluated. (A gouge needs its
    // sdf: evaluated below.)
    d = nv = double(r.data[x.n]);
    if (!(nv > v)) return;
    w.removed[i] += inside_fraction(v, p.voxel) - inside_fraction(nv, p.voxel);
  } else {
    d = -cut.sdf(cut.ctx, x.q.x(), x.q.y(), x.q.z());
    nv = stored(d, p.bgf);
    if (!(nv > v)) return;
    w.removed[i] += inside_fraction(v, p.voxel) - inside_fraction(nv, p.voxel);
  }
  if (r.design && v < -r.tie && d > -r.tie) {
    const swarf_stock &ds = *p.measure->design;
    if (!x.dq_exact) {
      if (std::isnan(x.dq)) x.dq = r.design->at(x.q);
      // Beyond the band of a design read from a mesh: its exact depth.
      if (ds.surface && x.dq <= -double(ds.background) * (1.0 - 1e-6))
        x.dq = -surface_distance(ds, x.q);
      x.dq_exact = true;
    }
    const double depth = gouge_depth(ds, x.dq, std::min(d, -v), p.voxel);
    // the deepest, and of equal ones the first in voxel order (as a replay
    // voxel by voxel finds them)
    if (depth > p.measure->tolerance &&
        (depth > w.gouge[i] || (depth == w.gouge[i] && before(x.q, w.gouge_at[i]))))
      w.gouge[i] = depth, w.gouge_at[i] = x.q;
  }
  x.v = nv;
}

/// The replay of cube c's m voxels (in voxel order), entry by entry of the
/// cube's list: an entry whose bound from the cube's centre keeps the lowest
/// voxel still replayed where it is passes over all of them at once. Each
/// voxel takes the same steps as when replayed alone.
void replay_cube(const Replay &r, CubeCuts &cubes, int c, ReplayVoxel *vx, int m) {
  const Pass &p = r.p;
  const RemoveScratch &w = p.s.scratch;
  const double bg = p.bgf, inf = std::numeric_limits<double>::infinity();
  double vmin = inf; // the lowest value still replayed (+inf: none)
  for (int j = 0; j < m; j++)
    if (vx[j].v < vx[j].end) vmin = std::min(vmin, vx[j].v);
  for (size_t k = 0; vmin < inf; k++) {
    const CubeCuts::Entry *e = cubes.get(p, r.b, c, k);
    if (e == nullptr) break;
    if (e->d - r.rv + vmin >= kMargin) continue; // no voxel of the cube is raised
    const uint32_t i = e->pair;
    double lo = inf;
    for (int j = 0; j < m; j++) {
      ReplayVoxel &x = vx[j];
      if (!(x.v < x.end)) continue;
      // the bounds from the block's and the cube's centres (d as it is now:
      // a voxel before this one may have asked for the plane)
      if (may_raise(x.v, bg, w.centre_sdf[i], p.radius[x.n]) &&
          !(cubes.list[c][k].d - r.rv + x.v >= kMargin))
        replay_step(r, cubes, c, k, x);
      if (x.v < x.end) lo = std::min(lo, x.v);
    }
    vmin = lo;
  }
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
  Replay r{p,
           b,
           data,
           arg,
           design,
           0.5 * p.voxel,
           0.5 * std::sqrt(3.0) * p.voxel,
           kTie * p.voxel,
           design ? p.voxel : 0.5 * p.voxel};
  const double floor = design ? -p.voxel : -r.half;
  CubeCuts &cubes = vs.cubes;
  cubes.reset();
  cubes.planes = p.flat ? nullptr : &planes;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // the voxels to replay (in voxel order), then grouped by cube
  ReplayVoxel vx[Leaf::SIZE];
  uint16_t per_cube[65] = {0};
  size_t count = 0;
  for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
    double dq = nan;
    if (volumes) { // the voxels whose fraction changed
      if (!(data[n] > old[n] && old[n] < r.half && data[n] > -r.half)) continue;
    } else { // those that crossed from material to air where the design may be gouged
      if (!(old[n] < -r.tie && data[n] > -r.tie)) continue;
      const Coord l = Leaf::offsetToLocalCoord(n);
      dq = design->at(block_point(p, b.origin, l.x(), l.y(), l.z()));
      if (!(dq < far)) continue;
    }
    const int c = cube_of(n);
    double &lo = cubes.low[c];
    lo = std::min(lo, std::max(double(old[n]), floor));
    per_cube[c + 1]++;
    ReplayVoxel &x = vx[count++];
    x.n = n;
    x.dq = dq;
    x.v = std::max(double(old[n]), floor);
    // No cut raises the voxel beyond its final value (the maximum the plain
    // visit stored): the replay ends there, or where the voxel is empty; for
    // the gouges only, where it has no material left (a gouge needs some).
    x.end = volumes ? std::min(r.half, double(data[n])) : 0.0;
  }
  if (count == 0) return;
  for (int c = 0; c < 64; c++)
    per_cube[c + 1] += per_cube[c];
  ReplayVoxel sorted[Leaf::SIZE];
  uint16_t at[64];
  std::copy(per_cube, per_cube + 64, at);
  for (size_t j = 0; j < count; j++) {
    ReplayVoxel &x = sorted[at[cube_of(vx[j].n)]++];
    x = vx[j];
    x.l = Leaf::offsetToLocalCoord(x.n);
    x.q = block_point(p, b.origin, x.l.x(), x.l.y(), x.l.z());
    x.dq_exact = false;
  }
  for (int c = 0; c < 64; c++)
    if (per_cube[c + 1] > per_cube[c])
      replay_cube(r, cubes, c, sorted + per_cube[c], per_cube[c + 1] - per_cube[c]);
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
    visit_leaf_measured(p, *leaf, b, design, dacc, vs);
  else
    visit_leaf(p, *leaf, b, vs.oct);
  if (was_tile && b.action != kCollapse) fresh.reset(new Leaf(*leaf));
}

} // namespace removal
} // namespace swarf
