/* SPDX-License-Identifier: MPL-2.0 */
/// @file io.cc
/// @brief Files of the stock: reading a .vdb (untrusted input), writing a .vdb
/// and a binary STL of the zero isosurface, each written atomically.
///
/// Reading takes the float level-set grid named "stock", or else the first
/// float level-set grid of the file; every OpenVDB exception (truncated or
/// corrupt data) becomes a status and a message. Delayed loading is off, so
/// the whole grid is read (and checked by OpenVDB's reader) before returning.
/// OpenVDB's reader is not hardened against damaged files (some corrupt its
/// heap), so the file is read by the reader program (swarf-vdb-read,
/// vdb_reader.cc) in a child process (isolate.h), which hands back the grid
/// re-serialized by OpenVDB's own writer.
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/tools/Interpolation.h>

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <sstream>

#include "atomic_file.h"
#include "isolate.h"
#include "legend.h"
#include "mesh_file.h"
#include "mesh_tets.h"
#include "stock_private.h"

namespace swarf {
namespace {

/// Writes grids into a caller's stream (io::File does the same into its own
/// std::ofstream, but does not report write errors).
class StreamArchive : public openvdb::io::Archive {
public:
  void write_to(std::ostream &os, const openvdb::GridCPtrVec &grids) const {
    openvdb::io::Archive::write(os, grids, /*seekable=*/true, openvdb::MetaMap());
  }
};

bool is_float_level_set(const openvdb::GridBase &g) {
  return g.isType<openvdb::FloatGrid>() && g.getGridClass() == openvdb::GRID_LEVEL_SET;
}

/// Unique name (in the file's own sense) of the grid to read, or "" if none fits.
std::string pick_grid(openvdb::io::File &file) {
  std::string first;
  for (auto it = file.beginName(); it != file.endName(); ++it) {
    const std::string unique = it.gridName();
    openvdb::GridBase::ConstPtr meta = file.readGridMetadata(unique);
    if (!is_float_level_set(*meta)) continue;
    if (meta->getName() == "stock") return unique;
    if (first.empty()) first = unique;
  }
  return first;
}

/// The grid to use from an open file; every exception of OpenVDB's reader
/// (corrupt or truncated data) becomes Error(FORMAT).
openvdb::FloatGrid::Ptr read_open_file(openvdb::io::File &file, const std::string &path) {
  const std::string name = pick_grid(file);
  if (name.empty()) throw Error(SWARF_ERR_FORMAT, path + ": no float level-set grid");
  openvdb::FloatGrid::Ptr grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(name));
  file.close();
  if (!grid || !is_float_level_set(*grid))
    throw Error(SWARF_ERR_FORMAT, path + ": no float level-set grid");
  return grid;
}

/// Bounds on a grid read as a stock, so that the work done on it (bounds,
/// volumes, meshing, rendering) follows its content and stays in seconds: a
/// root table of at most kMaxRootEntries nodes and tiles (each covers 4096^3
/// voxels: a stock's narrow band needs a few), at most kMaxActiveTiles
/// active tiles (iterating them costs OpenVDB time quadratic in the root
/// table: 2^19 of them took 20 s), and material within
/// kMaxExtentVoxels voxels along each axis (2^20: 210 m at 0.2 mm). A grid
/// of 2^20 root tiles or two voxels 5e8 mm apart is refused, not walked.
constexpr size_t kMaxRootEntries = size_t(1) << 16;
constexpr long long kMaxExtentVoxels = 1LL << 20;
constexpr openvdb::Index64 kMaxActiveTiles =
    4096; // a level set has none; OpenVDB walks them slowly

} // namespace

void check_stock_grid(const openvdb::FloatGrid &grid, const std::string &path) {
  const size_t root = grid.tree().root().getTableSize();
  if (root > kMaxRootEntries)
    throw Error(SWARF_ERR_LIMIT, path + ": " + std::to_string(root) +
                                     " root nodes and tiles, more than the " +
                                     std::to_string(kMaxRootEntries) + " a stock may have");
  const openvdb::Index64 tiles = grid.tree().activeTileCount(); // linear in the nodes
  if (tiles > kMaxActiveTiles)
    throw Error(SWARF_ERR_LIMIT,
                path + ": " + std::to_string(tiles) + " active tiles, more than the " +
                    std::to_string(kMaxActiveTiles) + " accepted (a level-set stock has none)");
  for (auto v = grid.cbeginValueAll(); v; ++v) // a NaN compares as neither inside nor out
    if (!std::isfinite(*v)) {
      const openvdb::Coord c = v.getCoord();
      throw Error(SWARF_ERR_FORMAT, path + ": a value that is not a number (" + std::to_string(*v) +
                                        ") at voxel " + std::to_string(c.x()) + "," +
                                        std::to_string(c.y()) + "," + std::to_string(c.z()) +
                                        ": not a level set");
    }
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  if (box.empty()) return;
  for (int k = 0; k < 3; k++) {
    const long long span = (long long)box.max()[k] - (long long)box.min()[k] + 1;
    if (span > kMaxExtentVoxels)
      throw Error(SWARF_ERR_LIMIT, path + ": the material spans " + std::to_string(span) +
                                       " voxels along " + "xyz"[k] + ", more than the " +
                                       std::to_string(kMaxExtentVoxels) +
                                       " a stock may span (work would follow the extent)");
  }
}

namespace {

openvdb::FloatGrid::Ptr read_grid_checked(const std::string &path);

openvdb::FloatGrid::Ptr read_grid_here(const std::string &path) {
  openvdb::FloatGrid::Ptr grid = read_grid_checked(path);
  check_stock_grid(*grid, path);
  return grid;
}

openvdb::FloatGrid::Ptr read_grid_checked(const std::string &path) {
  openvdb::io::File file(path);
  try {
    file.open(/*delayLoad=*/false);
  } catch (const std::bad_alloc &) {
    throw;
  } catch (const std::exception &e) {
    throw Error(SWARF_ERR_FORMAT, path + ": not a readable VDB file (" + e.what() + ")");
  }
  try {
    return read_open_file(file, path);
  } catch (const Error &) {
    throw;
  } catch (const std::bad_alloc &) {
    throw;
  } catch (const std::exception &e) {
    throw Error(SWARF_ERR_FORMAT, path + ": corrupt or truncated VDB file (" + e.what() + ")");
  }
}

/// Room (bytes) for the reading child beyond what it maps once started: 256
/// MB and 64 times the file (a damaged 20 kB file that makes OpenVDB allocate
/// gigabytes is stopped at 256 MB).
size_t reader_room(const std::string &path) {
  struct stat st;
  const size_t file = ::stat(path.c_str(), &st) == 0 ? size_t(st.st_size) : 0;
  return (size_t(256) << 20) + 64 * file;
}

/// Whether reads run in a child: -1 follow SWARF_VDB_ISOLATE (default on),
/// 0 off, 1 on (swarf_stock_set_read_isolation).
std::atomic<int> read_isolation{-1};

bool isolate_reads() {
  const int set = read_isolation.load();
  if (set >= 0) return set != 0;
  const char *env = std::getenv("SWARF_VDB_ISOLATE");
  return env == nullptr || std::strcmp(env, "0") != 0;
}

} // namespace

/// Throw Error(SWARF_ERR_OPEN) unless `path` names an existing regular file.
void check_readable(const char *path) {
  struct stat st;
  if (::stat(path, &st) != 0)
    throw Error(SWARF_ERR_OPEN, std::string("cannot open ") + path + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw Error(SWARF_ERR_OPEN, std::string("cannot read ") + path + ": not a regular file");
}

/// The reader program's work (isolate.h): the checked grid, serialized.
std::string read_grid_serialized(const std::string &path) {
  init_openvdb();
  std::ostringstream os(std::ios::binary);
  openvdb::io::Stream(os).write(openvdb::GridCPtrVec{read_grid_here(path)});
  return os.str();
}

/// Read the stock grid of `path` with the reader program in a child process
/// (see the file comment), unless the embedding program turned that off.
openvdb::FloatGrid::Ptr read_grid(const std::string &path) {
  if (!isolate_reads()) return read_grid_here(path);
  const IsolateLimits limits = {60, reader_room(path)};
  std::string bytes;
  run_reader("reading " + path, path, limits, bytes);
  std::istringstream is(bytes, std::ios::binary);
  openvdb::GridPtrVecPtr grids = openvdb::io::Stream(is).getGrids();
  openvdb::FloatGrid::Ptr grid;
  if (grids && grids->size() == 1) grid = openvdb::gridPtrCast<openvdb::FloatGrid>(grids->front());
  if (!grid) throw Error(SWARF_ERR_INTERNAL, path + ": the reader's copy did not arrive whole");
  check_stock_grid(*grid, path); // the parent trusts nothing it did not check
  return grid;
}

namespace {

/// A shallow copy of the stock's grid (sharing its tree) with swarf's metadata.
openvdb::FloatGrid::Ptr grid_for_output(const swarf_stock &s) {
  openvdb::FloatGrid::Ptr g = leaf_parallel_copy(s);
  g->setName("stock");
  g->setGridClass(openvdb::GRID_LEVEL_SET);
  g->setSaveFloatAsHalf(false);
  g->setCreator("swarf");
  g->insertMeta("swarf_voxel_mm", openvdb::DoubleMetadata(s.voxel));
  g->insertMeta("swarf_half_width_voxels", openvdb::Int32Metadata(s.half_width));
  g->insertMeta("swarf_units", openvdb::StringMetadata("mm"));
  return g;
}

/// Write the zero isosurface in `format`, with deviation colours when opt has
/// a design and the format holds them (see stock.h).
size_t write_mesh_file(const swarf_stock &s, const char *path, const swarf_stock_output &opt,
                       MeshFormat format) {
  double tol = 0.0, range = 0.0;
  output_scale(s, opt, tol, range);
  IsoMesh m; // closed: every edge shared by two triangles (mesh_tets.h)
  iso_mesh(*s.grid, m);
  std::vector<unsigned char> rgb;
  std::vector<float> dev;
  if (opt.design && format == MeshFormat::kPly) {
    const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(
        *opt.design->grid);
    rgb.resize(3 * m.points.size());
    dev.resize(m.points.size());
    for (size_t i = 0; i < m.points.size(); i++) {
      double d = sampler.wsSample(openvdb::Vec3d(m.points[i]));
      // Near or beyond the band of a design read from a mesh: its triangles.
      if (opt.design->surface && std::fabs(d) > double(opt.design->background) - opt.design->voxel)
        d = std::copysign(surface_distance_exact(*opt.design, openvdb::Vec3d(m.points[i])), d);
      dev[i] = float(d);
      float c[3];
      deviation_colour(dev[i], tol, range, c);
      for (int k = 0; k < 3; k++)
        rgb[3 * i + k] = (unsigned char)std::lround(255.0f * c[k]);
    }
  }
  static_assert(sizeof(openvdb::Vec3s) == 3 * sizeof(float) &&
                    sizeof(openvdb::Vec3I) == 3 * sizeof(uint32_t),
                "packed vectors");
  const MeshView view{reinterpret_cast<const float *>(m.points.data()),
                      m.points.size(),
                      reinterpret_cast<const uint32_t *>(m.triangles.data()),
                      m.triangles.size(),
                      rgb.empty() ? nullptr : rgb.data(),
                      dev.empty() ? nullptr : dev.data()};
  write_atomic(path, [&](std::ostream &os) { write_mesh(os, view, format); });
  return m.triangles.size();
}

} // namespace
} // namespace swarf

using swarf::Error;

extern "C" swarf_status swarf_stock_read(const char *path, swarf_stock **out, swarf_error *err) {
  if (out == nullptr) return swarf::set_error(err, SWARF_ERR_ARG, path, "out is NULL");
  *out = nullptr;
  return swarf::guard(err, path, [&] {
    swarf::check_path(path);
    swarf::check_readable(path);
    swarf::init_openvdb();
    *out = swarf::wrap_grid(swarf::read_grid(path));
  });
}

extern "C" void swarf_stock_set_read_isolation(int on) {
  swarf::read_isolation.store(on ? 1 : 0);
}

extern "C" int swarf_stock_read_isolation(void) {
  return swarf::isolate_reads() ? 1 : 0;
}

extern "C" swarf_status swarf_stock_write_vdb(const swarf_stock *s, const char *path,
                                              swarf_error *err) {
  return swarf::guard(err, path, [&] {
    if (s == nullptr) throw Error(SWARF_ERR_ARG, "stock is NULL");
    swarf::check_path(path);
    const openvdb::GridCPtrVec grids{swarf::grid_for_output(*s)};
    swarf::write_atomic(path,
                        [&](std::ostream &os) { swarf::StreamArchive().write_to(os, grids); });
  });
}

extern "C" swarf_status swarf_stock_write_stl(const swarf_stock *s, const char *path, size_t *ntri,
                                              swarf_error *err) {
  if (ntri) *ntri = 0;
  return swarf::guard(err, path, [&] {
    if (s == nullptr) throw Error(SWARF_ERR_ARG, "stock is NULL");
    const size_t n =
        swarf::write_mesh_file(*s, path, swarf_stock_output{}, swarf::MeshFormat::kStl);
    if (ntri) *ntri = n;
  });
}

extern "C" swarf_status swarf_stock_write_mesh(const swarf_stock *s, const char *path,
                                               const swarf_stock_output *opt, size_t *ntri,
                                               swarf_error *err) {
  if (ntri) *ntri = 0;
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr) throw Error(SWARF_ERR_ARG, "stock is NULL");
    const size_t n = swarf::write_mesh_file(*s, path, opt ? *opt : swarf_stock_output{},
                                            swarf::mesh_format(path));
    if (ntri) *ntri = n;
  });
}
