/* SPDX-License-Identifier: MPL-2.0 */
/// @file surface_file.h
/// @brief A design's triangles kept in a file as its exact distances search
/// them (surface_file.cc), and the STL reading they replace (levelset.cc).
#ifndef SWARF_STOCK_SURFACE_FILE_H
#define SWARF_STOCK_SURFACE_FILE_H

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "mesh_sdf.h"

namespace swarf {

/// The surface of the STL at path for a design of `voxel` mm, to be read
/// when called (mesh_surface_lazy): checks the path now and notes the file's
/// identity (inode, size, modification time); the call throws
/// Error(SWARF_ERR_IO) if the file is no longer the one noted.
std::function<std::shared_ptr<MeshSurface>()> stl_surface_loader(const char *path, double voxel);

/// Write m's ordered triangles (mesh_surface_corners) for a design of
/// `voxel` mm to path, atomically.
void write_surface_file(const char *path, MeshSurface &m, double voxel);

/// The surface in the bytes of a surface file made for `voxel` mm, ready
/// for queries. Throws Error(SWARF_ERR_FORMAT) for anything else: another
/// magic, version or voxel, a size that is not the header's count, a
/// checksum that does not match.
std::shared_ptr<MeshSurface> parse_surface_file(const char *data, size_t len, double voxel);

/// parse_surface_file on the file at path, read straight into the surface's
/// storage (Error(SWARF_ERR_OPEN) if it cannot be opened).
std::shared_ptr<MeshSurface> read_surface_file(const char *path, double voxel);

} // namespace swarf

#endif
