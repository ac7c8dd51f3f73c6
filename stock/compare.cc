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
  constexpr uint64_t kMaxBlocks = uint64_t(1) << 27;  // 6.9e10 voxels
  std::vector<Work> w;
  const Tree &tree = g.grid->constTree();
  for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) w.push_back({leaf->origin(), &*leaf, 0.0f});
  auto it = tree.cbeginValueAll();
  it.setMaxDepth(Tree::ValueAllCIter::LEAF_DEPTH - 1);
  for (; it; ++it) {
    if (!(*it < limit)) continue;
    const openvdb::CoordBBox b = it.getBoundingBox();
    if (w.size() + b.volume() / 512 > kMaxBlocks)
      throw Error(SWARF_ERR_LIMIT, "the grid's material is too large to compare (over 6.9e10 voxels)");
    for (int x = b.min()[0]; x <= b.max()[0]; x += 8)
      for (int y = b.min()[1]; y <= b.max()[1]; y += 8)
        for (int z = b.min()[2]; z <= b.max()[2]; z += 8) w.push_back({Coord(x, y, z), nullptr, *it});
  }
  return w;
}

/// One block's findings.
struct Found {
  double volume = 0.0, missing = 0.0;  ///< inside fractions, voxels
  double depth = 0.0;                  ///< deepest (mm), 0 none
  Vec3d at = Vec3d(0.0);
};

/// What the passes share.
struct Frame {
  const swarf_stock &s, &design;
  const swarf_stock *initial;
  double tol;
  bool same_lattice;  ///< design and stock: same voxel and origin
};

/// Excess in one block of the stock's material.
void excess_block(const Frame &f, const Work &w, GridProbe &design, ConstAcc &dacc, Found &out) {
  const double v = f.s.voxel;
  if (w.leaf == nullptr && f.same_lattice && dacc.probeConstLeaf(w.origin) == nullptr) {
    const double d = dacc.getValue(w.origin);  // both tiles here
    out.volume = Leaf::SIZE * std::max(0.0, inside_fraction(w.tile, v) - inside_fraction(d - f.tol, v));
    const double h = d + vouched_radius(-double(w.tile), v);
    if (h > f.tol) out.depth = h, out.at = index_to_world(f.s, w.origin.offsetBy(4));
    return;
  }
  for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
    const double s = w.leaf ? w.leaf->getValue(n) : w.tile;
    if (!(s < 0.5 * v)) continue;  // no material in this voxel
    const Vec3d q = index_to_world(f.s, w.origin + Leaf::offsetToLocalCoord(n));
    const double d = design.at(q);
    out.volume += std::max(0.0, inside_fraction(s, v) - inside_fraction(d - f.tol, v));
    if (!(s < 0.0)) continue;
    const double h = d + vouched_radius(-s, v);
    if (h > f.tol && h > out.depth) out.depth = h, out.at = q;
  }
}

/// Gouge (and missing) in one block of the design's interior.
void gouge_block(const Frame &f, const Work &w, GridProbe &stock, GridProbe *initial, ConstAcc &sacc,
                 Found &out) {
  const double v = f.design.voxel;
  if (w.leaf == nullptr && f.same_lattice && initial == nullptr && sacc.probeConstLeaf(w.origin) == nullptr) {
    const double s = sacc.getValue(w.origin);  // both tiles here
    out.volume = Leaf::SIZE * std::max(0.0, inside_fraction(w.tile + f.tol, v) - inside_fraction(s, v));
    const double g = -double(w.tile) + vouched_radius(s, v);
    if (s > 0.0 && g > f.tol) out.depth = g, out.at = index_to_world(f.design, w.origin.offsetBy(4));
    return;
  }
  for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
    const double d = w.leaf ? w.leaf->getValue(n) : w.tile;
    const double in = inside_fraction(d + f.tol, v);  // deeper than the tolerance
    if (!(in > 0.0)) continue;
    const Vec3d q = index_to_world(f.design, w.origin + Leaf::offsetToLocalCoord(n));
    const double s = stock.at(q), s0 = initial ? initial->at(q) : -1e30;
    const double had = initial ? inside_fraction(s0, f.s.voxel) : 1.0;
    out.volume += std::max(0.0, std::min(in, had) - inside_fraction(s, f.s.voxel));
    out.missing += std::max(0.0, in - had);
    if (!(s > 0.0) || !(s0 < 0.0)) continue;
    const double g = -d + vouched_radius(std::min(s, -s0), f.s.voxel);
    if (g > f.tol && g > out.depth) out.depth = g, out.at = q;
  }
}

/// Run `fn` on every block in parallel and add the findings up in order.
template <class Fn> Found sum_blocks(const std::vector<Work> &blocks, Fn &&fn) {
  std::vector<Found> found(blocks.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks.size(), 16), [&](const tbb::blocked_range<size_t> &r) {
    auto state = fn.make();
    for (size_t i = r.begin(); i != r.end(); ++i) fn(*state, blocks[i], found[i]);
  });
  Found total;
  for (const Found &b : found) {
    total.volume += b.volume, total.missing += b.missing;
    if (b.depth > total.depth) total.depth = b.depth, total.at = b.at;
  }
  return total;
}

struct ExcessPass {
  const Frame &f;
  struct State {
    GridProbe design;
    ConstAcc dacc;
  };
  std::unique_ptr<State> make() const {
    return std::unique_ptr<State>(new State{GridProbe(f.design, f.s), ConstAcc(f.design.grid->constTree())});
  }
  void operator()(State &st, const Work &w, Found &out) const { excess_block(f, w, st.design, st.dacc, out); }
};

struct GougePass {
  const Frame &f;
  struct State {
    GridProbe stock;
    std::unique_ptr<GridProbe> initial;
    ConstAcc sacc;
  };
  std::unique_ptr<State> make() const {
    std::unique_ptr<State> st(new State{GridProbe(f.s, f.design), nullptr, ConstAcc(f.s.grid->constTree())});
    if (f.initial) st->initial.reset(new GridProbe(*f.initial, f.design));
    return st;
  }
  void operator()(State &st, const Work &w, Found &out) const { gouge_block(f, w, st.stock, st.initial.get(), st.sacc, out); }
};

void set_point(double out[3], const Vec3d &p, bool any) {
  for (int k = 0; k < 3; k++) out[k] = any ? p[k] : kNaN;
}

std::string box_text(const double lo[3], const double hi[3]) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "x %.3f..%.3f, y %.3f..%.3f, z %.3f..%.3f mm", lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]);
  return buf;
}

}  // namespace

/// Throw Error(ARG) unless the design's and the stock's bounds meet.
void check_design(const swarf_stock &s, const swarf_stock &design) {
  double a[3], b[3], c[3], d[3];
  swarf_stock_bounds(&s, a, b);
  swarf_stock_bounds(&design, c, d);
  if (!std::isfinite(a[0])) throw Error(SWARF_ERR_ARG, "the stock holds no material");
  if (!std::isfinite(c[0])) throw Error(SWARF_ERR_ARG, "the design holds no material");
  for (int k = 0; k < 3; k++)
    if (b[k] < c[k] || d[k] < a[k])
      throw Error(SWARF_ERR_ARG, "the design (" + box_text(c, d) + ") does not overlap the stock (" +
                                           box_text(a, b) + "): is it in the same frame and place?");
}

void compare(const swarf_stock &s, const swarf_stock &design, const swarf_stock *initial, double tol,
             swarf_stock_deviation &out) {
  check_design(s, design);
  const bool same = GridProbe::lattices_coincide(s, design) && (s.origin - design.origin).length() <= 1e-9 * s.voxel;
  const Frame f{s, design, initial, tol, same};
  const Found ex = sum_blocks(blocks_below(s, 0.0f), ExcessPass{f});
  const Found go = sum_blocks(blocks_below(design, 0.0f), GougePass{f});
  const double reach = design.background, vs = std::pow(s.voxel, 3), vd = std::pow(design.voxel, 3);
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

}  // namespace swarf

extern "C" swarf_status swarf_stock_check_design(const swarf_stock *s, const swarf_stock *design,
                                                 swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || design == nullptr) throw swarf::Error(SWARF_ERR_ARG, "stock or design is NULL");
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
