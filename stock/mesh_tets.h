/* SPDX-License-Identifier: MPL-2.0 */
/// @file mesh_tets.h
/// @brief The stock's zero isosurface as a closed triangle mesh (marching
/// tetrahedra, mesh_tets.cc): every edge of the result is shared by exactly
/// two triangles, at every voxel size, and every lattice point the grid holds
/// inside the material or on its surface (value <= 0) lies inside the mesh,
/// so features thinner than a voxel are kept as the grid holds them.
#ifndef SWARF_STOCK_MESH_TETS_H
#define SWARF_STOCK_MESH_TETS_H

#include <openvdb/openvdb.h>

#include <vector>

namespace swarf {

/// An indexed mesh in world units (the grid's transform), triangles
/// counter-clockwise seen from outside (the right-hand normal points out of
/// the material).
struct IsoMesh {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
};

/// The zero isosurface of the level set `grid` (negative inside). Every
/// lattice cube with a corner in an allocated leaf node is meshed; a sign
/// change between two tiles with no leaf (not a valid narrow band) is not.
void iso_mesh(const openvdb::FloatGrid &grid, IsoMesh &out);

} // namespace swarf

#endif
