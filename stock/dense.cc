/* SPDX-License-Identifier: MPL-2.0 */
/// @file dense.cc
/// @brief The stock as a dense array of signed distances and back (stock.h):
/// for NumPy and other array code that wants the values on a box of voxel
/// centres rather than a sparse tree.
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tree/ValueAccessor.h>

#include <cmath>
#include <limits>
#include <string>

#include "stock_private.h"

namespace {

using swarf::Error;

/// The dims' product, refused when not positive or over 2^31 values.
size_t dense_size(const int dims[3]) {
  if (dims == nullptr) throw Error(SWARF_ERR_ARG, "dims is NULL");
  double n = 1.0;
  for (int k = 0; k < 3; k++) {
    if (dims[k] < 1) throw Error(SWARF_ERR_ARG, "dims must be >= 1 on every axis");
    n *= dims[k];
  }
  if (n > 2147483648.0) throw Error(SWARF_ERR_LIMIT, "more than 2^31 values in the box");
  return size_t(n);
}

} // namespace

extern "C" void swarf_stock_dense_box(const swarf_stock *s, int lo[3], int dims[3],
                                      double origin[3]) {
  for (int k = 0; k < 3; k++)
    lo[k] = 0, dims[k] = 0, origin[k] = std::numeric_limits<double>::quiet_NaN();
  if (s == nullptr) return;
  const openvdb::CoordBBox b = s->grid->evalActiveVoxelBoundingBox();
  for (int k = 0; k < 3; k++) {
    origin[k] = s->origin[k];
    if (!b.empty()) lo[k] = b.min()[k], dims[k] = b.max()[k] - b.min()[k] + 1;
  }
}

extern "C" swarf_status swarf_stock_to_dense(const swarf_stock *s, const int lo[3],
                                             const int dims[3], float *out, swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || lo == nullptr || out == nullptr)
      throw Error(SWARF_ERR_ARG, "stock, lo or out is NULL");
    dense_size(dims);
    openvdb::tree::ValueAccessor<const openvdb::FloatTree> acc(s->grid->constTree());
    size_t n = 0;
    for (int i = 0; i < dims[0]; i++)
      for (int j = 0; j < dims[1]; j++)
        for (int k = 0; k < dims[2]; k++)
          out[n++] = acc.getValue(openvdb::Coord(lo[0] + i, lo[1] + j, lo[2] + k));
  });
}

extern "C" swarf_status swarf_stock_from_dense(const double origin[3], double voxel,
                                               const int dims[3], const float *values,
                                               int half_width, swarf_stock **out,
                                               swarf_error *err) {
  if (out != nullptr) *out = nullptr;
  return swarf::guard(err, nullptr, [&] {
    if (origin == nullptr || values == nullptr || out == nullptr)
      throw Error(SWARF_ERR_ARG, "origin, values or out is NULL");
    if (!std::isfinite(voxel) || !(voxel >= 1e-3 && voxel <= 1000))
      throw Error(SWARF_ERR_ARG, "voxel must be 0.001 to 1000 mm");
    if (half_width < 3 || half_width > 64) throw Error(SWARF_ERR_ARG, "half_width must be 3 to 64");
    for (int k = 0; k < 3; k++)
      if (!std::isfinite(origin[k]) || std::fabs(origin[k]) > 1e9)
        throw Error(SWARF_ERR_ARG, "origin must be finite");
    const size_t total = dense_size(dims);
    swarf::init_openvdb();
    const float bg = float(half_width * voxel);
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(bg);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
    grid->transform().postTranslate(openvdb::Vec3d(origin[0], origin[1], origin[2]));
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    grid->setName("stock");
    openvdb::tree::ValueAccessor<openvdb::FloatTree> acc(grid->tree());
    size_t n = 0;
    for (int i = 0; i < dims[0]; i++)
      for (int j = 0; j < dims[1]; j++)
        for (int k = 0; k < dims[2]; k++, n++) {
          const float v = values[n];
          if (!std::isfinite(v))
            throw Error(SWARF_ERR_ARG, "values[" + std::to_string(n) + "] is not finite");
          if (std::fabs(v) < bg) acc.setValueOn(openvdb::Coord(i, j, k), v);
        }
    (void)total;
    openvdb::tools::signedFloodFill(grid->tree());
    *out = swarf::wrap_grid(grid);
  });
}
