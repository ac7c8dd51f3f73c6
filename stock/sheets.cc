/* SPDX-License-Identifier: MPL-2.0 */
/// @file sheets.cc
/// @brief Sheets of no thickness cleared: a cut that ends exactly on a stock
/// face (stock.h, swarf_stock_clear_sheets).
///
/// A box's faces on the lattice hold exactly 0 at their voxels' centres. A
/// cut whose surface passes through the same centres (a slot to Z-10 through
/// a block from Z-10) leaves max(0, 0) = 0 there: the level set keeps a sheet
/// of no thickness, which the volume counts as half a voxel a voxel (4948.8
/// instead of 5000 mm^3 for a D10 slot through 50 x 40 x 10 mm at 0.2 mm),
/// the mesh draws and the design comparison calls excess. A voxel on the
/// surface (|value| within 1e-9 voxel) whose two neighbours along one axis
/// are both air a full voxel away (value >= the voxel, to float rounding)
/// has no material on either side along that axis: a sheet of no thickness,
/// which becomes air half a voxel out. A face of real material has material
/// on one side (a negative neighbour); a floor thinner than a voxel brings
/// the air on its open side nearer than a voxel (0.1 mm left at 0.2 mm
/// voxels: a neighbour at +0.1), so it stays; so do edges and corners.
#include <openvdb/tree/LeafManager.h>
#include <tbb/parallel_reduce.h>

#include <cmath>
#include <vector>

#include "stock_private.h"

namespace swarf {
namespace {

using Acc = openvdb::FloatGrid::ConstAccessor;

/// True if along some axis both neighbours of ijk are air a voxel away.
bool sheet_across(Acc &acc, const openvdb::Coord &ijk, float full) {
  for (int k = 0; k < 3; k++) {
    openvdb::Coord a = ijk, b = ijk;
    a[k] -= 1, b[k] += 1;
    if (acc.getValue(a) >= full && acc.getValue(b) >= full) return true;
  }
  return false;
}

/// The sheet voxels of the grid, found before any is changed.
std::vector<openvdb::Coord> find_sheets(const swarf_stock &s, float tie, float full) {
  using LeafRange = openvdb::tree::LeafManager<const openvdb::FloatTree>::LeafRange;
  openvdb::tree::LeafManager<const openvdb::FloatTree> leaves(s.grid->constTree());
  return tbb::parallel_reduce(
      leaves.leafRange(), std::vector<openvdb::Coord>(),
      [&](const LeafRange &r, std::vector<openvdb::Coord> found) {
        Acc acc(s.grid->constTree());
        for (auto leaf = r.begin(); leaf; ++leaf)
          for (auto v = leaf->cbeginValueOn(); v; ++v)
            if (std::fabs(*v) <= tie && sheet_across(acc, v.getCoord(), full))
              found.push_back(v.getCoord());
        return found;
      },
      [](std::vector<openvdb::Coord> a, const std::vector<openvdb::Coord> &b) {
        a.insert(a.end(), b.begin(), b.end());
        return a;
      });
}

} // namespace
} // namespace swarf

extern "C" swarf_status swarf_stock_clear_sheets(swarf_stock *s, long long *cleared,
                                                 swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr) throw swarf::Error(SWARF_ERR_ARG, "stock is NULL");
    const float tie = float(1e-9 * s->voxel), air = float(0.5 * s->voxel);
    const float full = float(s->voxel * (1.0 - 1e-6));
    const std::vector<openvdb::Coord> sheets = swarf::find_sheets(*s, tie, full);
    openvdb::FloatGrid::Accessor acc(s->grid->tree());
    for (const openvdb::Coord &c : sheets)
      acc.setValueOn(c, air);
    if (cleared != nullptr) *cleared = (long long)sheets.size();
  });
}
