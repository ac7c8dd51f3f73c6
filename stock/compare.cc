/* SPDX-License-Identifier: MPL-2.0 */
/// @file compare.cc
/// @brief The deviation of a stock from a design (swarf_stock_compare).
///
/// Two passes over 8^3 blocks, in parallel, each block's findings kept apart
/// and added up in block order (the result does not depend on the threads):
///  - excess, over the stock's material (its leaves and inside tiles): each
///    voxel's inside fraction in the stock minus that in the design grown by
///    the tolerance (when positive);
///  - gouge (and missing), over the design's interior: each voxel's inside
///    fraction in the design shrunk by the tolerance minus that in the stock
///    (with an initial stock: in the smaller of the shrunk design and the
///    initial stock).
/// A difference of inside fractions is exact for parallel faces at any
/// offset, and counts nothing where the two surfaces coincide (the stock's
/// side walls on the design's); a product of fractions would count both.
/// Where both grids share one lattice and origin, a block that is a tile in
/// both is counted at once (most of a part's interior).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "stock_private.h"

namespace swarf {
namespace {

using openvdb::Coord;
using openvdb::Vec3d;
using Tree = openvdb::FloatTree;
using Leaf = Tree::LeafNodeType;
using ConstAcc = openvdb::tree::ValueAccessor<const Tree>;

const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// An 8^3 block of a grid: a leaf, or part of a tile of value `tile`.
struct Work {
  Coord origin;
  const Leaf *leaf;
  float tile;
};

/// The blocks of g that may hold values below `limit`: every leaf, and the
/// tiles below it split into 8^3 blocks.
std::vector<Work> blocks_below(const swarf_stock &g, float limit) {
  constexpr uint64_t kMaxBlocks = uint64_t(1) << 27; // 6.9e10 voxels
  std::vector<Work> w;
  const Tree &tree = g.grid->constTree();
  for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf)
    w.push_back({leaf->origin(), &*leaf, 0.0f});
  auto it = tree.cbeginValueAll();
  it.setMaxDepth(Tree::ValueAllCIter::LEAF_DEPTH - 1);
  for (; it; ++it) {
    if (!(*it < limit)) continue;
    const openvdb::CoordBBox b = it.getBoundingBox();
    if (w.size() + b.volume() / 512 > kMaxBlocks)
      throw Error(SWARF_ERR_LIMIT,
                  "the grid's material is too large to compare (over 6.9e10 voxels)");
    for (int x = b.min()[0]; x <= b.max()[0]; x += 8)
      for (int y = b.min()[1]; y <= b.max()[1]; y += 8)
        for (int z = b.min()[2]; z <= b.max()[2]; z += 8)
          w.push_back({Coord(x, y, z), nullptr, *it});
  }
  return w;
}

/// One block's findings.
struct Found {
  double volume = 0.0, missing = 0.0; ///< inside fractions, voxels
  double depth = 0.0;                 ///< deepest (mm), 0 none
  Vec3d at = Vec3d(0.0);
  bool clamped = false; ///< a depth read the design at its band's edge (a lower bound)
};

/// True if a design value is at its band's edge (background bg): beyond it,
/// the distance is at least that.
inline bool at_edge(double d, float bg) {
  return std::fabs(d) >= double(bg) * (1.0 - 1e-6);
}

/// What the passes share.
struct Frame {
  const swarf_stock &s, &design;
  const swarf_stock *initial;
  double tol;
  bool same_lattice; ///< design and stock: same voxel and origin
  /// The values the volumes need reach beyond the design's band (a design
  /// read from a mesh; exact_needed): design values at the band's edge are
  /// measured on its triangles.
  bool exact_far;
  bool initial_same; ///< the initial stock and the design: same voxel and origin
};

/// True if a design (read from a mesh, band `bg` mm) must be measured on its
/// triangles at its band's edge to compare at tolerance `tol`. On one
/// lattice (design values read at the stock's voxel centres) the volumes
/// take inside_fraction(d -/+ tol), which is 0 or 1 beyond |d| = tol + half
/// a voxel, and the band's edge reads as +-bg, on the same side: exact
/// values are needed up to there only (depths beyond the band are measured
/// anyway: beyond_band). Sampled trilinearly (another lattice) a value mixes
/// eight voxels a voxel away: as before, a voxel's margin.
bool exact_needed(double bg, double tol, double vs, double vd, bool aligned) {
  if (aligned) return bg < tol + 0.5 * vs;
  return tol + std::max(vs, vd) >= bg;
}

/// Design values at the band's edge of one block when the frame is
/// exact_far: blocks whose centre is farther from the design's surface than
/// their radius plus the tolerance and half a voxel read as that far (no
/// voxel of theirs is within the tolerance); the others are measured voxel
/// by voxel on the triangles.
struct FarValues {
  const Frame &f;
  Vec3d centre;     ///< world centre of the block
  double voxel;     ///< the block's grid's voxel
  int state = 0;    ///< 0 not yet known, 1 far, 2 near
  double far = 0.0; ///< the value of a far block's edge voxels (magnitude)
  /// d: the grid's value at q (at the band's edge: |d| = background).
  double at(double d, const Vec3d &q) {
    if (!f.exact_far || std::fabs(d) < double(f.design.background) * (1.0 - 1e-6)) return d;
    if (state == 0) {
      const double reach = f.tol + 0.5 * voxel, r = 3.5 * std::sqrt(3.0) * voxel;
      state = surface_distance_exact(f.design, centre) - r >= reach ? 1 : 2;
      far = std::max(double(f.design.background), reach);
    }
    const double e = state == 1 ? far : surface_distance_exact(f.design, q);
    return d < 0.0 ? -e : e;
  }
};

inline Vec3d block_centre(const swarf_stock &g, const Coord &o) {
  return g.origin + g.voxel * Vec3d(o.x() + 3.5, o.y() + 3.5, o.z() + 3.5);
}

/// Excess in one block of the stock's material.
void excess_block(const Frame &f, const Work &w, GridProbe &design, ConstAcc &dacc, Found &out) {
  const double v = f.s.voxel;
  if (w.leaf == nullptr && f.same_lattice && !f.exact_far &&
      dacc.probeConstLeaf(w.origin) == nullptr) {
    const double d = dacc.getValue(w.origin); // both tiles here
    out.volume =
        Leaf::SIZE * std::max(0.0, inside_fraction(w.tile, v) - inside_fraction(d - f.tol, v));
    const double h = d + vouched_radius(-double(w.tile), v);
    if (h > f.tol) out.depth = h, out.at = index_to_world(f.s, w.origin.offsetBy(4));
    out.clamped = w.tile < 0.0f && d > 0.0 && at_edge(d, f.design.background);
    return;
  }
  FarValues far{f, block_centre(f.s, w.origin), v};
  for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
    const double s = w.leaf ? w.leaf->getValue(n) : w.tile;
    if (!(s < 0.5 * v)) continue; // no material in this voxel
    const Coord ijk = w.origin + Leaf::offsetToLocalCoord(n);
    const Vec3d q = index_to_world(f.s, ijk);
    // one index space: the design's voxel ijk, as design.at(q) would round to
    const double raw = f.same_lattice ? double(design.at_index(ijk)) : design.at(q);
    const double d = far.at(raw, q);
    out.volume += std::max(0.0, inside_fraction(s, v) - inside_fraction(d - f.tol, v));
    if (!(s < 0.0)) continue;
    if (raw > 0.0 && at_edge(raw, f.design.background)) out.clamped = true;
    const double h = d + vouched_radius(-s, v);
    if (h > f.tol && h > out.depth) out.depth = h, out.at = q;
  }
}

/// Gouge (and missing) in one block of the design's interior.
void gouge_block(const Frame &f, const Work &w, GridProbe &stock, GridProbe *initial,
                 ConstAcc &sacc, Found &out) {
  const double v = f.design.voxel;
  if (w.leaf == nullptr && f.same_lattice && !f.exact_far && initial == nullptr &&
      sacc.probeConstLeaf(w.origin) == nullptr) {
    const double s = sacc.getValue(w.origin); // both tiles here
    out.volume =
        Leaf::SIZE * std::max(0.0, inside_fraction(w.tile + f.tol, v) - inside_fraction(s, v));
    const double g = -double(w.tile) + vouched_radius(s, v);
    if (s > 0.0 && g > f.tol)
      out.depth = g, out.at = index_to_world(f.design, w.origin.offsetBy(4));
    out.clamped = s > 0.0 && w.tile < 0.0f && at_edge(w.tile, f.design.background);
    return;
  }
  FarValues far{f, block_centre(f.design, w.origin), v};
  for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
    const double raw = w.leaf ? w.leaf->getValue(n) : w.tile;
    double d = raw;
    if (!f.exact_far && !(inside_fraction(d + f.tol, v) > 0.0)) continue;
    const Coord ijk = w.origin + Leaf::offsetToLocalCoord(n);
    const Vec3d q = index_to_world(f.design, ijk);
    // one index space: the voxel ijk, as at(q) would round to
    const double s = f.same_lattice ? double(stock.at_index(ijk)) : stock.at(q);
    const double s0 = !initial         ? -1e30
                      : f.initial_same ? double(initial->at_index(ijk))
                                       : initial->at(q);
    if (f.exact_far) {
      if (s <= -0.5 * f.s.voxel && s0 <= -0.5 * f.s.voxel)
        continue; // material there, before and after
      d = far.at(d, q);
    }
    const double in = inside_fraction(d + f.tol, v); // deeper than the tolerance
    if (!(in > 0.0)) continue;
    const double had = initial ? inside_fraction(s0, f.s.voxel) : 1.0;
    out.volume += std::max(0.0, std::min(in, had) - inside_fraction(s, f.s.voxel));
    out.missing += std::max(0.0, in - had);
    if (!(s > 0.0) || !(s0 < 0.0)) continue;
    if (raw < 0.0 && at_edge(raw, f.design.background)) out.clamped = true;
    const double g = -d + vouched_radius(std::min(s, -s0), f.s.voxel);
    if (g > f.tol && g > out.depth) out.depth = g, out.at = q;
  }
}

/// Run `fn` on every block in parallel and add the findings up in order
/// (each block's kept in `found`).
template <class Fn>
Found sum_blocks(const std::vector<Work> &blocks, Fn &&fn, std::vector<Found> &found) {
  found.assign(blocks.size(), Found());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks.size(), 16),
                    [&](const tbb::blocked_range<size_t> &r) {
                      auto state = fn.make();
                      for (size_t i = r.begin(); i != r.end(); ++i)
                        fn(*state, blocks[i], found[i]);
                    });
  Found total;
  for (const Found &b : found) {
    total.volume += b.volume, total.missing += b.missing;
    if (b.depth > total.depth) total.depth = b.depth, total.at = b.at;
  }
  return total;
}

/// A voxel near the band's edge: its depth is the exact distance to the
/// design's surface at q (`known`, the band's value, unless NaN: measured on
/// the triangles) plus r.
struct Beyond {
  Vec3d q;
  double r;
  double known;
};

/// The deepest point where the design's band ran out (a design read from a
/// mesh): blocks whose finding may be deeper than found, taken by decreasing
/// upper bound (the exact distance at the block's centre plus its radius and
/// a voxel), the voxels of those that can still beat the best measured
/// exactly. `collect(state, work, out)` lists a block's voxels near the
/// band's edge; `grid` is the one the blocks come from.
///
/// On one lattice (`by_clamp`) a block may be deeper than found when it read
/// the design at the band's edge (`clamped`); a finding deeper than the band
/// but of band values only is exact as it is, which keeps a narrow band
/// cheap. Its voxels' values are then those of a band wide enough
/// (surface_distance), each block's deepest its first in voxel order, and
/// the result the first deepest in block order: what the block pass gives
/// with such a band, where (ties) included. Otherwise (values interpolated
/// from eight voxels, which mixes the edge in unseen) a block may be deeper
/// when its finding reached the reach, and the deepest is the first found.
template <class Pass, class Collect>
Found beyond_band(const swarf_stock &design, const swarf_stock &grid,
                  const std::vector<Work> &blocks, const std::vector<Found> &found, Found total,
                  const Pass &pass, bool by_clamp, Collect collect) {
  const double reach = design.background, v = grid.voxel;
  auto dist = [&](const Vec3d &q) {
    return by_clamp ? surface_distance(design, q) : surface_distance_exact(design, q);
  };
  std::vector<size_t> idx;
  Found best; // the exact findings: blocks that stayed within the band
  for (size_t i = 0; i < found.size(); i++) {
    if (by_clamp ? found[i].clamped : found[i].depth >= reach)
      idx.push_back(i);
    else if (found[i].depth > best.depth)
      best.depth = found[i].depth, best.at = found[i].at;
  }
  if (idx.empty() || !design.surface) return total;
  std::vector<double> ub(idx.size()), lb(idx.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, idx.size(), 4),
                    [&](const tbb::blocked_range<size_t> &r) {
                      for (size_t k = r.begin(); k != r.end(); ++k) {
                        ub[k] = dist(block_centre(grid, blocks[idx[k]].origin)) +
                                (3.5 * std::sqrt(3.0) + 1.0) * v;
                        lb[k] = dist(found[idx[k]].at);
                      }
                    });
  std::vector<size_t> order(idx.size());
  for (size_t k = 0; k < order.size(); k++)
    order[k] = k;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return ub[a] > ub[b]; });
  auto state = pass.make();
  std::vector<Beyond> list;
  auto measure = [&](size_t k, Found &out) {
    list.clear();
    collect(*state, blocks[idx[k]], list);
    for (const Beyond &b : list) {
      const double d = (std::isnan(b.known) ? dist(b.q) : b.known) + b.r;
      if (d > out.depth) out.depth = d, out.at = b.q;
    }
  };
  if (!by_clamp) {
    for (size_t k = 0; k < idx.size(); k++)
      if (lb[k] > best.depth) best.depth = lb[k], best.at = found[idx[k]].at;
    for (size_t k : order) {
      if (ub[k] <= best.depth) break;
      measure(k, best);
    }
    total.depth = best.depth, total.at = best.at;
    return total;
  }
  double bound = best.depth; // the deepest is at least this
  for (size_t k = 0; k < idx.size(); k++)
    bound = std::max(bound, lb[k]);
  std::vector<Found> exact(idx.size()); // depth 0: passed over (it cannot reach the deepest)
  for (size_t k : order) {
    if (ub[k] < bound) break;
    measure(k, exact[k]);
    bound = std::max(bound, exact[k].depth);
  }
  Found deepest;
  for (size_t i = 0, k = 0; i < found.size(); i++) {
    const Found &b = k < idx.size() && idx[k] == i ? exact[k++] : found[i];
    if (b.depth > deepest.depth) deepest.depth = b.depth, deepest.at = b.at;
  }
  total.depth = deepest.depth, total.at = deepest.at;
  return total;
}

struct ExcessPass {
  const Frame &f;
  struct State {
    GridProbe design;
    ConstAcc dacc;
  };
  std::unique_ptr<State> make() const {
    return std::unique_ptr<State>(
        new State{GridProbe(f.design, f.s), ConstAcc(f.design.grid->constTree())});
  }
  void operator()(State &st, const Work &w, Found &out) const {
    excess_block(f, w, st.design, st.dacc, out);
  }
};

struct GougePass {
  const Frame &f;
  struct State {
    GridProbe stock;
    std::unique_ptr<GridProbe> initial;
    ConstAcc sacc;
  };
  std::unique_ptr<State> make() const {
    std::unique_ptr<State> st(
        new State{GridProbe(f.s, f.design), nullptr, ConstAcc(f.s.grid->constTree())});
    if (f.initial) st->initial.reset(new GridProbe(*f.initial, f.design));
    return st;
  }
  void operator()(State &st, const Work &w, Found &out) const {
    gouge_block(f, w, st.stock, st.initial.get(), st.sacc, out);
  }
};

void set_point(double out[3], const Vec3d &p, bool any) {
  for (int k = 0; k < 3; k++)
    out[k] = any ? p[k] : kNaN;
}

std::string box_text(const double lo[3], const double hi[3]) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "x %.3f..%.3f, y %.3f..%.3f, z %.3f..%.3f mm", lo[0], hi[0], lo[1],
                hi[1], lo[2], hi[2]);
  return buf;
}

} // namespace

/// Throw Error(ARG) unless the design's and the stock's bounds meet.
void check_design(const swarf_stock &s, const swarf_stock &design) {
  double a[3], b[3], c[3], d[3];
  swarf_stock_bounds(&s, a, b);
  swarf_stock_bounds(&design, c, d);
  if (!std::isfinite(a[0])) throw Error(SWARF_ERR_ARG, "the stock holds no material");
  if (!std::isfinite(c[0])) throw Error(SWARF_ERR_ARG, "the design holds no material");
  for (int k = 0; k < 3; k++)
    if (b[k] < c[k] || d[k] < a[k])
      throw Error(SWARF_ERR_ARG, "the design (" + box_text(c, d) +
                                     ") does not overlap the stock (" + box_text(a, b) +
                                     "): is it in the same frame and place?");
}

void compare(const swarf_stock &s, const swarf_stock &design, const swarf_stock *initial,
             double tol, swarf_stock_deviation &out) {
  check_design(s, design);
  const bool same = GridProbe::lattices_coincide(s, design) &&
                    (s.origin - design.origin).length() <= 1e-9 * s.voxel;
  const bool initial_same = initial != nullptr && GridProbe::lattices_coincide(*initial, design) &&
                            (initial->origin - design.origin).length() <= 1e-9 * s.voxel;
  const bool exact_far = design.surface != nullptr &&
                         exact_needed(double(design.background), tol, s.voxel, design.voxel,
                                      GridProbe::lattices_coincide(s, design));
  const Frame f{s, design, initial, tol, same, exact_far, initial_same};
  // Voxels within a voxel of the band's edge may be the deepest of a block
  // that reached it: they are measured on the triangles too.
  const double edge = double(design.background) - design.voxel;
  std::vector<Found> found;
  const std::vector<Work> sblocks = blocks_below(s, 0.0f), dblocks = blocks_below(design, 0.0f);
  const ExcessPass xp{f};
  Found ex = sum_blocks(sblocks, xp, found);
  // On one lattice a value inside the band is exact as it is (the band's).
  const bool aligned = GridProbe::lattices_coincide(s, design);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto known = [&](double d) {
    return aligned && !at_edge(d, design.background) ? std::fabs(d) : nan;
  };
  ex = beyond_band(design, s, sblocks, found, ex, xp, aligned,
                   [&](ExcessPass::State &st, const Work &w, std::vector<Beyond> &l) {
                     for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
                       const double sv = w.leaf ? w.leaf->getValue(n) : w.tile;
                       if (!(sv < 0.0)) continue;
                       const Vec3d q = index_to_world(s, w.origin + Leaf::offsetToLocalCoord(n));
                       const double d = st.design.at(q);
                       if (d >= edge) l.push_back({q, vouched_radius(-sv, s.voxel), known(d)});
                     }
                   });
  const GougePass gp{f};
  Found go = sum_blocks(dblocks, gp, found);
  go = beyond_band(design, design, dblocks, found, go, gp, aligned,
                   [&](GougePass::State &st, const Work &w, std::vector<Beyond> &l) {
                     for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
                       const double d = w.leaf ? w.leaf->getValue(n) : w.tile;
                       if (!(d <= -edge)) continue;
                       const Vec3d q =
                           index_to_world(design, w.origin + Leaf::offsetToLocalCoord(n));
                       const double sv = st.stock.at(q),
                                    s0 = st.initial ? st.initial->at(q) : -1e30;
                       if (sv > 0.0 && s0 < 0.0)
                         l.push_back({q, vouched_radius(std::min(sv, -s0), s.voxel), known(d)});
                     }
                   });
  // Beyond the band: exact when the design came from a mesh, else clamped to it.
  const double reach = design.surface ? std::numeric_limits<double>::infinity() : design.background;
  const double vs = std::pow(s.voxel, 3), vd = std::pow(design.voxel, 3);
  out.tolerance = tol;
  out.reach = reach;
  out.stock_volume = swarf_stock_volume(&s);
  out.design_volume = swarf_stock_volume(&design);
  out.excess_volume = ex.volume * vs;
  out.excess_clamped = ex.depth >= reach;
  out.excess_height = std::min(ex.depth, double(reach));
  set_point(out.excess_at, ex.at, ex.depth > 0.0);
  out.gouge_volume = go.volume * vd;
  out.missing_volume = go.missing * vd;
  out.gouge_clamped = go.depth >= reach;
  out.gouge_depth = std::min(go.depth, double(reach));
  set_point(out.gouge_at, go.at, go.depth > 0.0);
}

} // namespace swarf

extern "C" swarf_status swarf_stock_check_design(const swarf_stock *s, const swarf_stock *design,
                                                 swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || design == nullptr)
      throw swarf::Error(SWARF_ERR_ARG, "stock or design is NULL");
    swarf::check_design(*s, *design);
  });
}

extern "C" swarf_status swarf_stock_compare(const swarf_stock *s, const swarf_stock *design,
                                            const swarf_stock *initial, double tolerance,
                                            swarf_stock_deviation *out, swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || design == nullptr || out == nullptr)
      throw swarf::Error(SWARF_ERR_ARG, "stock, design or out is NULL");
    if (!std::isfinite(tolerance)) throw swarf::Error(SWARF_ERR_ARG, "tolerance must be finite");
    *out = swarf_stock_deviation{};
    swarf::compare(*s, *design, initial, tolerance > 0.0 ? tolerance : 0.5 * s->voxel, *out);
  });
}

extern "C" int swarf_stock_design_band(const swarf_stock *stock, double voxel, double tolerance,
                                       int views) {
  if (stock != nullptr) voxel = stock->voxel;
  if (!(voxel > 0.0) || !std::isfinite(voxel) || !std::isfinite(tolerance))
    return SWARF_STOCK_DESIGN_BAND;
  if (views) { // colours sample the design out to their range, 4 tolerances
    const double tol = tolerance > 0.0 ? tolerance : 0.5 * voxel;
    return std::clamp(int(std::ceil(4.0 * tol / voxel)) + 1, SWARF_STOCK_DESIGN_BAND, 64);
  }
  if (stock != nullptr) // a design read from a mesh has its origin at (0, 0, 0)
    for (int k = 0; k < 3; k++) {
      const double o = stock->origin[k] / voxel;
      if (!(std::fabs(o - std::round(o)) <= 1e-6)) return SWARF_STOCK_DESIGN_BAND;
    }
  const double tol = tolerance > 0.0 ? tolerance : 0.5 * voxel;
  int h = 1;
  while (h < 64 &&
         swarf::exact_needed(double(swarf::band_background(h, voxel)), tol, voxel, voxel, true))
    h++;
  return h;
}
