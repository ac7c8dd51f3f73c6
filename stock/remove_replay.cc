/* SPDX-License-Identifier: MPL-2.0 */
/// @file remove_replay.cc
/// @brief Pass 4 of a removal, measured (remove.cc): the plain visit of a
/// block (remove_visit.cc), then a replay of the voxels whose inside fraction
/// changed, cut by cut in program order, crediting each cut with the volume
/// it removed and the deepest gouge it made into the design.
#include <algorithm>
#include <cstring>
#include <limits>

#include "remove_pass.h"

namespace swarf {
namespace removal {

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
    double d;  ///< the cut's sdf at the cube's centre (a range's value where the cut has one)
    int plane; ///< 1: sdf(q) >= pd + g.(q - centre) for the cube's voxels q; 0: none; -1: not
               ///< asked yet
    double pd; ///< the plane's value at the centre (d for a supporting plane)
    double g[3];
    /// The plane's bound at the cube's voxel l (block-local; +-h from the centre per axis).
    double at(const Coord &l, double h) const {
      return pd + (l.x() & 1 ? h : -h) * g[0] + (l.y() & 1 ? h : -h) * g[1] +
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
      // a cut with a range function resolves only values below what passes the cube over
      // (rotary sweeps, with their local plane: only the voxels' steps credit the cut); others
      // give their sdf
      Entry e{i, 0.0, 0, 0.0, {0.0, 0.0, 0.0}};
      e.plane = cut_value_plane(p, cut, q, -HUGE_VAL, kMargin + rv - low[c], rv, e.d, e.pd, e.g);
      if (e.d - rv + low[c] >= kMargin) continue;
      if (p.support != nullptr && p.support[w.pairs[i].cut] != nullptr) e.plane = -1;
      list[c].push_back(e);
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
    e.pd = e.d;
    return e;
  }
};

/// A thread's scratch for the measured visits (each block takes it once).
struct MeasureScratch {
  OctantPlanes planes;
  CubeCuts cubes;
};

/// This thread's MeasureScratch (not inlined, as visit_scratch).
__attribute__((noinline)) MeasureScratch &measure_scratch() {
  thread_local MeasureScratch ms;
  return ms;
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
/// cut with a supporting plane there (3-axis moves), whose plane does (asked
/// for at the first voxel of the cube the Lipschitz bound leaves undecided;
/// bear.nc at 0.2 mm: 26.1 M -> 14.6 M replay sdf calls, of which 12.6 M
/// raise the voxel, with planes outside the cuts only); where the
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
                         OctScratch &os) {
  const bool volumes = p.measure->volumes;
  const double far = volumes ? p.voxel : gouge_floor(p);
  if (design && dacc && design_far(p, *dacc, b.origin, far)) design = nullptr;
  if (!volumes && design == nullptr) { // gouges only, and none can be found here
    visit_leaf(p, leaf, b, os);
    return;
  }
  MeasureScratch &ms = measure_scratch();
  const float *data = leaf.buffer().data();
  float old[Leaf::SIZE];
  std::memcpy(old, data, sizeof old);
  uint32_t arg[Leaf::SIZE]; // the cut each changed voxel's final value came from
  std::fill_n(arg, Leaf::SIZE, UINT32_MAX);
  OctantPlanes &planes = ms.planes;
  planes.reset(b.count);
  visit_leaf(p, leaf, b, os, arg, &planes);
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
  CubeCuts &cubes = ms.cubes;
  cubes.reset();
  cubes.planes = p.flat ? nullptr : &planes;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // the voxels to replay, with their design values (gouges only; else NaN:
  // asked when needed), and each cube's lowest starting value
  bool take[Leaf::SIZE];
  double dqs[Leaf::SIZE];
  uint8_t taken[64] = {0};
  for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
    double dq = nan;
    take[n] = false;
    if (volumes) { // the voxels whose fraction changed
      if (!(data[n] > old[n] && old[n] < r.half && data[n] > -r.half)) continue;
    } else { // those that crossed from material to air where the design may be gouged
      if (!(old[n] < -r.tie && data[n] > -r.tie)) continue;
      const Coord l = Leaf::offsetToLocalCoord(n);
      dq = design->at(block_point(p, b.origin, l.x(), l.y(), l.z()));
      if (!(dq < far)) continue;
    }
    take[n] = true;
    dqs[n] = dq;
    taken[cube_of(n)]++;
    double &lo = cubes.low[cube_of(n)];
    lo = std::min(lo, std::max(double(old[n]), floor));
  }
  // cube by cube, each cube's voxels in voxel order
  for (int c = 0; c < 64; c++) {
    if (taken[c] == 0) continue;
    ReplayVoxel vx[8];
    int m = 0;
    const int x0 = (c >> 4) << 1, y0 = ((c >> 2) & 3) << 1, z0 = (c & 3) << 1;
    for (int x = x0; x < x0 + 2; x++)
      for (int y = y0; y < y0 + 2; y++)
        for (int z = z0; z < z0 + 2; z++) {
          const openvdb::Index n = (x << 6) | (y << 3) | z;
          if (!take[n]) continue;
          ReplayVoxel &v = vx[m++];
          v.n = n;
          v.l = Coord(x, y, z);
          v.q = block_point(p, b.origin, x, y, z);
          v.v = std::max(double(old[n]), floor);
          // No cut raises the voxel beyond its final value (the maximum the
          // plain visit stored): the replay ends there, or where the voxel is
          // empty; for the gouges only, where it has no material left (a
          // gouge needs some).
          v.end = volumes ? std::min(r.half, double(data[n])) : 0.0;
          v.dq = dqs[n];
          v.dq_exact = false;
        }
    replay_cube(r, cubes, c, vx, m);
  }
}

} // namespace removal
} // namespace swarf
