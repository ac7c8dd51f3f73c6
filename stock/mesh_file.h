/* SPDX-License-Identifier: MPL-2.0 */
/// @file mesh_file.h
/// @brief Triangle meshes as files, without OpenVDB: reading STL (binary or
/// ASCII, untrusted input) into a welded mesh checked to bound a solid, and
/// writing a mesh as binary STL, OBJ or binary PLY (with per-vertex colours
/// and deviations).
///
/// Units are the file's (mm for swarf). Reading welds vertices with equal
/// coordinates (bit for bit, -0 = +0), drops triangles with two equal corners,
/// and refuses, with Error(SWARF_ERR_FORMAT) naming the place: no
/// triangles, a non-finite coordinate, a boundary edge (an open mesh), an edge
/// of more than two triangles (non-manifold), two triangles running along an
/// edge the same way (inconsistent orientation), no enclosed volume. A mesh
/// that is consistently oriented inward (negative volume) is turned outward.
#ifndef SWARF_STOCK_MESH_FILE_H
#define SWARF_STOCK_MESH_FILE_H

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace swarf {

/// An indexed triangle mesh: xyz holds 3 floats a vertex, tri 3 indices a
/// triangle, corners counter-clockwise seen from outside.
struct TriMesh {
  std::vector<float> xyz;
  std::vector<uint32_t> tri;
  size_t vertices() const { return xyz.size() / 3; }
  size_t triangles() const { return tri.size() / 3; }
};

/// Most triangles a file may hold (50 bytes each in binary STL: 2.5 GB).
constexpr size_t kMaxStlTriangles = 50000000;

/// Parse the bytes of an STL file (`name` for messages) into a welded mesh
/// (not yet checked). Binary when the size is 84 + 50 n for the count n in the
/// header, ASCII when it starts with "solid" otherwise. Throws Error(FORMAT)
/// ("name: ..." or "name:LINE: ..." for ASCII).
void parse_stl(const char *data, size_t len, const std::string &name, TriMesh &out);

/// Check that the mesh bounds a solid (see the file comment) and orient it
/// outward. Throws Error(FORMAT) ("name: ...").
void check_solid(TriMesh &m, const std::string &name);

/// Read, parse and check an STL file. A file that cannot be opened is
/// Error(SWARF_ERR_OPEN).
void read_stl_file(const char *path, TriMesh &out);

/// What a mesh writer needs; rgb (3 bytes a vertex) and deviation (1 float a
/// vertex) may be null.
struct MeshView {
  const float *xyz;
  size_t nvertices;
  const uint32_t *tri;
  size_t ntriangles;
  const unsigned char *rgb;
  const float *deviation;
};

enum class MeshFormat { kStl, kObj, kPly };

/// The format for a file name's extension (case-insensitive .stl, .obj,
/// .ply); throws Error(SWARF_ERR_ARG) for any other.
MeshFormat mesh_format(const char *path);

/// Write the mesh to the stream in the format (STL ignores colours).
void write_mesh(std::ostream &os, const MeshView &m, MeshFormat f);

} // namespace swarf

#endif
