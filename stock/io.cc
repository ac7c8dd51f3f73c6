/// @file io.cc
/// @brief Files of the stock: reading a .vdb (untrusted input), writing a .vdb
/// and a binary STL of the zero isosurface, each written atomically.
///
/// Reading takes the float level-set grid named "stock", or else the first
/// float level-set grid of the file; every OpenVDB exception (truncated or
/// corrupt data) becomes a status and a message. Delayed loading is off, so
/// the whole grid is read (and checked by OpenVDB's reader) before returning.
/// OpenVDB's reader is not hardened against damaged files (some corrupt its
/// heap), so the file is read in a child process (isolate.h) that hands back
/// the grid re-serialized by OpenVDB's own writer.
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <memory>

#include "atomic_file.h"
#include "isolate.h"
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

/// Throw Error(OPEN) unless `path` names an existing regular file.
void check_readable(const char *path) {
  struct stat st;
  if (::stat(path, &st) != 0)
    throw Error(SWARF_ERR_OPEN, std::string("cannot open ") + path + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw Error(SWARF_ERR_OPEN, std::string("cannot read ") + path + ": not a regular file");
}

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

openvdb::FloatGrid::Ptr read_grid_here(const std::string &path) {
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

/// Address space (bytes) for the reading child: what the process maps now
/// plus room for the grid; 0 (no limit) under AddressSanitizer, which maps
/// terabytes of shadow memory.
size_t reader_address_space(const std::string &path) {
#if defined(__SANITIZE_ADDRESS__)
  return 0;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return 0;
#endif
#endif
  struct stat st;
  const size_t file = ::stat(path.c_str(), &st) == 0 ? size_t(st.st_size) : 0;
  size_t pages = 0;
  if (FILE *f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%zu", &pages) != 1) pages = 0;
    std::fclose(f);
  }
  if (pages == 0) return 0;
  return pages * size_t(::sysconf(_SC_PAGESIZE)) + (size_t(2) << 30) + 64 * file;
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

/// Read the stock grid of `path` in a child process (see the file comment),
/// unless the embedding program turned that off.
openvdb::FloatGrid::Ptr read_grid(const std::string &path) {
  if (!isolate_reads()) return read_grid_here(path);
  const IsolateLimits limits = {120, reader_address_space(path)};
  std::string bytes;
  run_isolated("reading " + path, limits, [&] {
    std::ostringstream os(std::ios::binary);
    openvdb::io::Stream(os).write(openvdb::GridCPtrVec{read_grid_here(path)});
    return os.str();
  }, bytes);
  std::istringstream is(bytes, std::ios::binary);
  openvdb::GridPtrVecPtr grids = openvdb::io::Stream(is).getGrids();
  openvdb::FloatGrid::Ptr grid;
  if (grids && grids->size() == 1) grid = openvdb::gridPtrCast<openvdb::FloatGrid>(grids->front());
  if (!grid) throw Error(SWARF_ERR_INTERNAL, path + ": the reader's copy did not arrive whole");
  return grid;
}

/// A shallow copy of the stock's grid (sharing its tree) with swarf's metadata.
openvdb::FloatGrid::Ptr grid_for_output(const swarf_stock &s) {
  openvdb::FloatGrid::Ptr g = s.grid->copy();
  g->setName("stock");
  g->setGridClass(openvdb::GRID_LEVEL_SET);
  g->setSaveFloatAsHalf(false);
  g->setCreator("swarf");
  g->insertMeta("swarf_voxel_mm", openvdb::DoubleMetadata(s.voxel));
  g->insertMeta("swarf_half_width_voxels", openvdb::Int32Metadata(s.half_width));
  g->insertMeta("swarf_units", openvdb::StringMetadata("mm"));
  return g;
}

void put_u32_le(unsigned char *p, uint32_t v) {
  for (int i = 0; i < 4; i++) p[i] = (unsigned char)(v >> (8 * i));
}

void put_f32_le(unsigned char *p, float f) {
  uint32_t v;
  std::memcpy(&v, &f, 4);
  put_u32_le(p, v);
}

/// One binary STL record (50 bytes): unit normal from the vertex order (right-
/// hand rule), the three vertices, a zero attribute count.
void put_triangle(unsigned char *p, const openvdb::Vec3s &a, const openvdb::Vec3s &b,
                  const openvdb::Vec3s &c) {
  openvdb::Vec3d n = (openvdb::Vec3d(b) - openvdb::Vec3d(a)).cross(openvdb::Vec3d(c) - openvdb::Vec3d(a));
  const double len = n.length();
  n = len > 0.0 ? n / len : openvdb::Vec3d(0.0);
  const openvdb::Vec3s *v[3] = {&a, &b, &c};
  for (int k = 0; k < 3; k++) put_f32_le(p + 4 * k, float(n[k]));
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) put_f32_le(p + 12 + 12 * i + 4 * k, (*v[i])[k]);
  p[48] = p[49] = 0;
}

/// The zero isosurface as triangles (quads split along their 0-2 diagonal),
/// ordered so that the right-hand normal points out of the material.
/// volumeToMesh collapses a quad's corners onto one point where the surface
/// pinches; the degenerate triangles that gives (two equal corners) are left
/// out, which keeps every edge matched by its reverse.
struct Mesh {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  std::vector<openvdb::Vec3I> out;  ///< the triangles written, outward order

  void add(unsigned i, unsigned j, unsigned k) {
    const openvdb::Vec3s &a = points[i], &b = points[j], &c = points[k];
    if (a == b || b == c || a == c) return;
    out.emplace_back(k, j, i);
  }
  /// volumeToMesh orders the vertices of its polygons clockwise seen from
  /// outside (the right-hand normal points into the material): each triangle
  /// is reversed (checked by tests/stock/test_stl.c).
  void triangulate() {
    out.clear();
    out.reserve(triangles.size() + 2 * quads.size());
    for (const openvdb::Vec3I &t : triangles) add(t[0], t[1], t[2]);
    for (const openvdb::Vec4I &q : quads) add(q[0], q[1], q[2]), add(q[0], q[2], q[3]);
  }
  size_t count() const { return out.size(); }
};

void write_stl_body(std::ostream &os, const Mesh &m) {
  unsigned char head[84] = {0};
  std::snprintf(reinterpret_cast<char *>(head), 80, "swarf stock: zero isosurface, mm");
  put_u32_le(head + 80, uint32_t(m.count()));
  os.write(reinterpret_cast<const char *>(head), 84);
  std::vector<unsigned char> buf;
  buf.reserve(50 * 4096);
  for (const openvdb::Vec3I &t : m.out) {
    buf.resize(buf.size() + 50);
    put_triangle(buf.data() + buf.size() - 50, m.points[t[0]], m.points[t[1]], m.points[t[2]]);
    if (buf.size() >= 50 * 4096) os.write(reinterpret_cast<const char *>(buf.data()), buf.size()), buf.clear();
  }
  os.write(reinterpret_cast<const char *>(buf.data()), buf.size());
}

}  // namespace
}  // namespace swarf

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

extern "C" void swarf_stock_set_read_isolation(int on) { swarf::read_isolation.store(on ? 1 : 0); }

extern "C" int swarf_stock_read_isolation(void) { return swarf::isolate_reads() ? 1 : 0; }

extern "C" swarf_status swarf_stock_write_vdb(const swarf_stock *s, const char *path,
                                              swarf_error *err) {
  return swarf::guard(err, path, [&] {
    if (s == nullptr) throw Error(SWARF_ERR_ARG, "stock is NULL");
    swarf::check_path(path);
    const openvdb::GridCPtrVec grids{swarf::grid_for_output(*s)};
    swarf::write_atomic(path, [&](std::ostream &os) { swarf::StreamArchive().write_to(os, grids); });
  });
}

extern "C" swarf_status swarf_stock_write_stl(const swarf_stock *s, const char *path, size_t *ntri,
                                              swarf_error *err) {
  if (ntri) *ntri = 0;
  return swarf::guard(err, path, [&] {
    if (s == nullptr) throw Error(SWARF_ERR_ARG, "stock is NULL");
    swarf::check_path(path);
    swarf::Mesh m;
    openvdb::tools::volumeToMesh(*s->grid, m.points, m.triangles, m.quads, 0.0, 0.0);
    m.triangulate();
    if (m.count() > UINT32_MAX) throw Error(SWARF_ERR_ARG, "mesh has too many triangles for STL");
    swarf::write_atomic(path, [&](std::ostream &os) { swarf::write_stl_body(os, m); });
    if (ntri) *ntri = m.count();
  });
}
