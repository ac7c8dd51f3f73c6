/* SPDX-License-Identifier: MPL-2.0 */
/// @file placement.h
/// @brief A stock's placement (stock.h, swarf_stock_placement) as a matrix,
/// without OpenVDB: x' = R x + t, R = Rz Ry Rx, rotations by whole quarter
/// turns exact (0 and +-1, not cos(pi/2) = 6e-17).
#ifndef SWARF_STOCK_PLACEMENT_H
#define SWARF_STOCK_PLACEMENT_H

#include "stock.h"

namespace swarf {

/// The rigid map of a placement: rot (row-major 3 x 3) and t (mm).
struct Rigid {
  double rot[9];
  double t[3];
  /// x' = R x + t
  void apply(const double x[3], double y[3]) const;
  /// x = R^T (x' - t)
  void invert(const double y[3], double x[3]) const;
};

/// The map of a placement; throws Error(SWARF_ERR_ARG) for non-finite values.
Rigid placement_map(const swarf_stock_placement &p);

/// True if the placement is the identity (all zero).
bool placement_is_identity(const swarf_stock_placement &p);

} // namespace swarf

#endif
