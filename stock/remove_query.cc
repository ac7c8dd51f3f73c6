/* SPDX-License-Identifier: MPL-2.0 */
/// @file remove_query.cc
/// @brief Read-only questions about a cut against the stock, by the blocks
/// and bounds of a removal (remove_pass.h): does it overlap the material
/// deeper than a depth, does it penetrate it beyond what was cleared, how
/// deep does it gouge the design. Nothing is changed.
#include <algorithm>
#include <limits>

#include "remove_pass.h"

namespace swarf {
namespace removal {

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

/// Whether hit(origin) holds for some 8^3 block of the cut's bounds, in the
/// stock's scan order (blocks x, y, z), stopping at the first.
template <class Hit> bool any_block(Pass &p, const swarf_stock_cut &cut, Hit hit) {
  Coord a, b;
  if (!cut_blocks(p, cut, a, b)) return false;
  for (int x = a.x(); x <= b.x(); x += 8)
    for (int y = a.y(); y <= b.y(); y += 8)
      for (int z = a.z(); z <= b.z(); z += 8)
        if (hit(Coord(x, y, z))) return true;
  return false;
}

} // namespace removal

using namespace removal;

/// True if the cut penetrates the material by more than depth (see stock.h).
bool cut_penetrates(const swarf_stock &s, const swarf_stock_cut &cut, const swarf_stock_cut *clear,
                    size_t nclear, double depth, Vec3d &where) {
  Pass p{const_cast<swarf_stock &>(s), &cut, s.voxel, s.background, 0.0, {}, {}, {}};
  init_pass(p);
  ConstAcc acc(s.grid->constTree());
  return any_block(p, cut, [&](const Coord &o) {
    return block_penetrates(p, clear, nclear, acc, o, depth, where);
  });
}

/// True if the cut overlaps the material deeper than depth (see stock.h).
bool cut_overlaps(const swarf_stock &s, const swarf_stock_cut &cut, double depth, Vec3d &where) {
  Pass p{const_cast<swarf_stock &>(s), &cut, s.voxel, s.background, 0.0, {}, {}, {}};
  init_pass(p);
  ConstAcc acc(s.grid->constTree());
  return any_block(p, cut, [&](const Coord &o) { return block_overlap(p, acc, o, depth, where); });
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

} // namespace swarf

extern "C" swarf_status swarf_stock_overlaps(const swarf_stock *s, const swarf_stock_cut *cut,
                                             double depth, int *hit, double where[3],
                                             swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || cut == nullptr || hit == nullptr)
      throw swarf::Error(SWARF_ERR_ARG, "stock, cut or hit is NULL");
    *hit = 0;
    swarf::removal::check_cut(*cut, 0);
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
    swarf::removal::check_cut(*cut, 0);
    if (!(depth >= 0.0 && std::isfinite(depth)))
      throw swarf::Error(SWARF_ERR_ARG, "depth must be finite and >= 0");
    openvdb::Vec3d q;
    if (nclear > 0 && clear == nullptr) throw swarf::Error(SWARF_ERR_ARG, "clear is NULL");
    for (size_t i = 0; i < nclear; i++)
      swarf::removal::check_cut(clear[i], i);
    *hit = swarf::cut_penetrates(*s, *cut, clear, nclear, depth, q) ? 1 : 0;
    if (*hit && where != nullptr)
      for (int k = 0; k < 3; k++)
        where[k] = q[k];
  });
}

extern "C" swarf_status swarf_stock_gouge(const swarf_stock *s, const swarf_stock *design,
                                          const swarf_stock_cut *cut, double tolerance,
                                          double *depth, double where[3], swarf_error *err) {
  if (depth) *depth = 0.0;
  if (where) where[0] = where[1] = where[2] = std::numeric_limits<double>::quiet_NaN();
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || design == nullptr || cut == nullptr || depth == nullptr)
      throw swarf::Error(SWARF_ERR_ARG, "stock, design, cut or depth is NULL");
    swarf::removal::check_cut(*cut, 0);
    if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
      throw swarf::Error(SWARF_ERR_ARG, "tolerance must be finite and >= 0");
    openvdb::Vec3d q;
    *depth = swarf::cut_gouge(*s, *design, *cut, tolerance, q);
    if (*depth > 0.0 && where != nullptr)
      for (int k = 0; k < 3; k++)
        where[k] = q[k];
  });
}
