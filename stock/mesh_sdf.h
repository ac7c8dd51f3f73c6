/* SPDX-License-Identifier: MPL-2.0 */
/// @file mesh_sdf.h
/// @brief The narrow band of a closed triangle mesh's signed distance, made
/// without OpenVDB's meshToVolume (mesh_sdf.cc): signs from winding numbers
/// along voxel columns, distances exact (closest points on the triangles)
/// wherever they are below the band's half-width. Used for STL stocks and
/// designs (levelset.cc).
#ifndef SWARF_STOCK_MESH_SDF_H
#define SWARF_STOCK_MESH_SDF_H

#include <openvdb/openvdb.h>

#include <functional>
#include <memory>
#include <vector>

namespace swarf {

/// A mesh's triangles kept for exact distance queries far from the surface,
/// where a band holds only +-its half-width (designs: deepest gouges and
/// largest excesses beyond the band). Index space, as mesh_band's points
/// (mesh_surface.cc).
struct MeshSurface;

/// The surface of the mesh (index-space points, triangles), for queries;
/// ordered for them at the first query (mesh_surface_distance).
std::shared_ptr<MeshSurface> mesh_surface(std::vector<openvdb::Vec3s> points,
                                          std::vector<openvdb::Vec3I> triangles);

/// A surface read only when the first query comes (most designs are never
/// asked beyond their band): load gives it then (mesh_surface's or
/// mesh_surface_ordered's); what it throws, that query and every later one
/// throw.
std::shared_ptr<MeshSurface> mesh_surface_lazy(std::function<std::shared_ptr<MeshSurface>()> load);

/// m's triangles in the order its queries search them (read and ordered
/// first if they are not yet): *count of them, 9 floats each (three corners
/// in index space), valid while m lives.
const float *mesh_surface_corners(MeshSurface &m, size_t *count);

/// A surface of `count` triangles already in that order: fill writes them
/// (9 floats each) into the storage it is given, and may throw. Its queries
/// need no sort, and give what the original's give, bit for bit.
std::shared_ptr<MeshSurface> mesh_surface_ordered(size_t count,
                                                  const std::function<void(float *)> &fill);

/// Exact distance (index units) from the index-space point p to the surface:
/// triangles in chunks of 32 along a Morton curve (sorted at the first call,
/// thread-safe) under a binary tree of bounding boxes, searched depth first,
/// nearer box first, boxes no nearer than the best found skipped (bear's
/// design at 0.2 mm, 1.36 M triangles: ~10^4 queries/s a thread near the
/// surface, where a scan of all chunks managed ~500).
double mesh_surface_distance(MeshSurface &m, const openvdb::Vec3d &p);

/// A level set of the solid bounded by the mesh: points in index space
/// (world mm / voxel; voxel centres at integer points), triangles
/// counter-clockwise seen from outside, the mesh closed and consistently
/// oriented (mesh_file.h's check_solid). The grid has a linear transform of
/// `voxel` mm, background bg (mm, >= half_width * voxel); voxels whose
/// distance to the surface is below half_width voxels hold it exactly
/// (negative inside, mm) and are active, all others hold +-bg, inactive
/// (tiles by signed flood fill). Throws Error(SWARF_ERR_LIMIT) when the
/// triangles' bounding boxes span too many blocks.
openvdb::FloatGrid::Ptr mesh_band(const std::vector<openvdb::Vec3s> &points,
                                  const std::vector<openvdb::Vec3I> &triangles, double voxel,
                                  int half_width, float bg);

} // namespace swarf

#endif
