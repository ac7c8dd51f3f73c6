/* SPDX-License-Identifier: MPL-2.0 */
/// @file levelset.cc
/// @brief Stocks made from other shapes: a closed STL mesh (exact distances
/// in the band, mesh_sdf.h), a .vdb grid of swarf or another tool,
/// a stock resampled at another voxel size or placed for the next setup, and
/// designs for the comparison.
///
/// Every grid made here follows swarf's band: background b = the band's
/// half-width (band_background), a voxel is active iff |value| < b, inactive
/// values are exactly +-b (normalize_band). Grids read from files are brought
/// to that form too (values clamped into the band, NaN outside), so the
/// removal can rely on it whatever tool wrote them.
///
/// Placement and resampling: the new grid's origin is R o + t (o: the
/// source's origin), so that its voxel j maps back to the source's index
/// A j, A = (new voxel / old voxel) R^T: a rotation by quarter turns at the
/// same voxel permutes voxels (values copied bit for bit), anything else is
/// sampled trilinearly at A j. Where the source reads its band's edge (it
/// knows only that the surface is farther), the new grid reads its own.
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/parallel_for.h>

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "mesh_file.h"
#include "mesh_sdf.h"
#include "placement.h"
#include "stock_private.h"
#include "surface_file.h"

namespace swarf {
namespace {

using openvdb::Coord;
using openvdb::Vec3d;
using openvdb::Vec3I;
using openvdb::Vec3s;
using openvdb::Vec4I;
using Tree = openvdb::FloatTree;
using Leaf = Tree::LeafNodeType;

constexpr double kMaxIndex = 536870912.0; ///< 2^29 voxels from the origin
constexpr double kMaxBandVoxels = 4e9;

void check_grid_args(double voxel, int half_width) {
  if (!std::isfinite(voxel) || !(voxel > 0.0))
    throw Error(SWARF_ERR_ARG, "voxel must be finite and > 0");
  if (half_width < 1 || half_width > 64)
    throw Error(SWARF_ERR_ARG, "half_width must be 1 to 64 voxels");
}

/// Bring a level-set grid to swarf's band (see the file comment), background bg.
void normalize_band(openvdb::FloatGrid &g, float bg) {
  Tree &tree = g.tree();
  openvdb::tree::LeafManager<Tree> leaves(tree);
  leaves.foreach ([bg](Leaf &leaf, size_t) {
    for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
      const float v = leaf.getValue(n);
      if (v < bg && v > -bg)
        leaf.setValueOn(n);
      else
        leaf.setValueOff(n, v <= -bg ? -bg : bg); // NaN: outside
    }
  });
  auto it = tree.beginValueAll();
  it.setMaxDepth(Tree::ValueAllIter::LEAF_DEPTH - 1); // tiles only
  for (; it; ++it) {
    const float v = *it;
    it.setValue(v < 0.0f ? -bg : bg);
    it.setValueOff();
  }
  tree.root().setBackground(bg, /*updateChildNodes=*/false);
  openvdb::tools::pruneLevelSet(tree);
}

bool has_material(const openvdb::FloatGrid &g) {
  const Tree &tree = g.constTree();
  for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf)
    for (auto v = leaf->cbeginValueOn(); v; ++v)
      if (*v < 0.0f) return true;
  auto it = tree.cbeginValueAll();
  it.setMaxDepth(Tree::ValueAllCIter::LEAF_DEPTH - 1);
  for (; it; ++it)
    if (*it < 0.0f) return true;
  return false;
}

/// Name, class and storage of a grid the module hands out.
void set_stock_meta(openvdb::FloatGrid &g) {
  g.setName("stock");
  g.setGridClass(openvdb::GRID_LEVEL_SET);
  g.setSaveFloatAsHalf(false);
}

/// Refuse meshes out of the index range or whose band would not fit in memory.
void check_mesh_size(const std::vector<Vec3s> &pts, const std::vector<Vec3I> &tris,
                     const std::vector<Vec4I> &quads, double voxel, int half_width) {
  for (const Vec3s &p : pts)
    for (int k = 0; k < 3; k++)
      if (!(std::fabs(double(p[k])) / voxel < kMaxIndex))
        throw Error(SWARF_ERR_LIMIT,
                    "the mesh reaches too far from the origin for this voxel size");
  double area = 0.0;
  auto tri_area = [&](unsigned a, unsigned b, unsigned c) {
    const Vec3d e1 = Vec3d(pts[b]) - Vec3d(pts[a]), e2 = Vec3d(pts[c]) - Vec3d(pts[a]);
    area += 0.5 * e1.cross(e2).length();
  };
  for (const Vec3I &t : tris)
    tri_area(t[0], t[1], t[2]);
  for (const Vec4I &q : quads)
    tri_area(q[0], q[1], q[2]), tri_area(q[0], q[2], q[3]);
  if (area / (voxel * voxel) * (2.0 * half_width + 1.0) > kMaxBandVoxels)
    throw Error(SWARF_ERR_LIMIT,
                "the mesh's surface is too large for this voxel size (band over 4e9 voxels)");
}

/// World points (mm) in index space (voxels), as the band and the surface take them.
std::vector<Vec3s> index_points(const std::vector<Vec3s> &pts, double voxel) {
  std::vector<Vec3s> ip(pts.size());
  for (size_t i = 0; i < pts.size(); i++)
    ip[i] = Vec3s(float(pts[i][0] / voxel), float(pts[i][1] / voxel), float(pts[i][2] / voxel));
  return ip;
}

/// A stock from a closed polygon mesh (world points, mm): the exact signed
/// distance in swarf's band (mesh_sdf.h: winding-number signs, closest-point
/// distances; no meshToVolume, whose band expansion costs ten times more and
/// is a voxel off near edges). keep_surface: keep the triangles (designs).
swarf_stock *mesh_stock(const std::vector<Vec3s> &pts, const std::vector<Vec3I> &tris,
                        const std::vector<Vec4I> &quads, double voxel, int half_width,
                        bool keep_surface = false) {
  check_mesh_size(pts, tris, quads, voxel, half_width);
  init_openvdb();
  std::vector<Vec3s> ip = index_points(pts, voxel);
  std::vector<Vec3I> t(tris);
  for (const Vec4I &q : quads)
    t.emplace_back(q[0], q[1], q[2]), t.emplace_back(q[0], q[2], q[3]);
  const float bg = band_background(half_width, voxel);
  openvdb::FloatGrid::Ptr grid = mesh_band(ip, t, voxel, half_width, bg);
  set_stock_meta(*grid);
  normalize_band(*grid, bg);
  if (!has_material(*grid))
    throw Error(SWARF_ERR_FORMAT,
                "the mesh holds no voxel centre at this voxel size (thinner than a voxel)");
  swarf_stock *s = wrap_grid(grid);
  if (keep_surface) s->surface = mesh_surface(std::move(ip), std::move(t));
  return s;
}

/// ---- Placement by resampling ----

/// The source's index of the new grid's voxel j: A j, A = (new voxel / old
/// voxel) R^T (the new grid's origin is R o + t).
struct Resampler {
  const swarf_stock &src;
  double rt[9]; ///< A, row-major
  bool exact;   ///< A is a signed permutation: voxels map onto voxels
  float bg;     ///< the new band; source values at the source's band read as +-bg

  Vec3d source_index(const Vec3d &j) const {
    return Vec3d(rt[0] * j[0] + rt[1] * j[1] + rt[2] * j[2],
                 rt[3] * j[0] + rt[4] * j[1] + rt[5] * j[2],
                 rt[6] * j[0] + rt[7] * j[1] + rt[8] * j[2]);
  }
  template <class Acc> float value(Acc &acc, const Vec3d &j) const {
    const Vec3d i = source_index(j);
    const float v = exact ? acc.getValue(Coord(int(std::lround(i[0])), int(std::lround(i[1])),
                                               int(std::lround(i[2]))))
                          : float(openvdb::tools::BoxSampler::sample(acc, i));
    if (v >= src.background) return bg; // beyond what the source knows: outside the band
    if (v <= -src.background) return -bg;
    return v;
  }
  /// True if the source holds no leaf under the block at j0 (its footprint,
  /// padded by one voxel for interpolation): the block is one tile.
  template <class Acc> bool uniform(Acc &acc, const Coord &j0) const {
    Vec3d lo(1e300), hi(-1e300);
    for (int c = 0; c < 8; c++) {
      const Vec3d i = source_index(
          Vec3d(j0[0] + (c & 1 ? 7 : 0), j0[1] + (c & 2 ? 7 : 0), j0[2] + (c & 4 ? 7 : 0)));
      lo = openvdb::math::minComponent(lo, i), hi = openvdb::math::maxComponent(hi, i);
    }
    const Coord a(int(std::floor(lo[0])) - 1, int(std::floor(lo[1])) - 1,
                  int(std::floor(lo[2])) - 1);
    const Coord b(int(std::ceil(hi[0])) + 1, int(std::ceil(hi[1])) + 1, int(std::ceil(hi[2])) + 1);
    for (int x = a[0] & ~7; x <= b[0]; x += 8)
      for (int y = a[1] & ~7; y <= b[1]; y += 8)
        for (int z = a[2] & ~7; z <= b[2]; z += 8)
          if (acc.probeConstLeaf(Coord(x, y, z))) return false;
    return true;
  }
};

/// What the placed grid gets at one block.
struct PlacedBlock {
  Coord origin;
  int kind; ///< 0 outside (nothing), 1 inside tile, 2 leaf to sample
};

/// Index box (block-aligned) of the new grid: R / scale applied to the source's content box.
openvdb::CoordBBox placed_box(const swarf_stock &s, const double rot[9], double scale) {
  const openvdb::CoordBBox &c = s.content;
  Vec3d lo(1e300), hi(-1e300);
  for (int k = 0; k < 8; k++) {
    const Vec3d i(k & 1 ? c.max()[0] : c.min()[0], k & 2 ? c.max()[1] : c.min()[1],
                  k & 4 ? c.max()[2] : c.min()[2]);
    const Vec3d j = Vec3d(rot[0] * i[0] + rot[1] * i[1] + rot[2] * i[2],
                          rot[3] * i[0] + rot[4] * i[1] + rot[5] * i[2],
                          rot[6] * i[0] + rot[7] * i[1] + rot[8] * i[2]) /
                    scale;
    lo = openvdb::math::minComponent(lo, j), hi = openvdb::math::maxComponent(hi, j);
  }
  int a[3], b[3];
  for (int k = 0; k < 3; k++) {
    if (!(std::fabs(lo[k]) < kMaxIndex && std::fabs(hi[k]) < kMaxIndex))
      throw Error(SWARF_ERR_ARG, "the placed stock reaches beyond 2^29 voxels from its origin");
    a[k] = (int(std::floor(lo[k])) - 2) & ~7;
    b[k] = int(std::ceil(hi[k])) + 2;
  }
  return openvdb::CoordBBox(Coord(a[0], a[1], a[2]), Coord(b[0], b[1], b[2]));
}

/// The stock placed by m and sampled at `voxel` mm with a band of `half_width`
/// voxels (see the file comment).
swarf_stock *resample(const swarf_stock &s, const Rigid &m, double voxel, int half_width) {
  init_openvdb();
  check_grid_args(voxel, half_width);
  const double scale = voxel / s.voxel;
  const float bg = band_background(half_width, voxel);
  bool identity = scale == 1.0 && bg == s.background;
  for (int k = 0; k < 9; k++)
    identity = identity && m.rot[k] == (k % 4 == 0 ? 1.0 : 0.0);
  for (int k = 0; k < 3; k++)
    identity = identity && m.t[k] == 0.0;
  if (identity) return wrap_grid(s.grid->deepCopy()); // a copy, bit for bit
  if (!(scale > 1e-3 && scale < 1e3))
    throw Error(SWARF_ERR_ARG, "the new voxel is too far from the old one");
  Resampler rs{s, {}, scale == 1.0, bg};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      rs.rt[3 * i + j] = scale * m.rot[3 * j + i];
      const double a = std::fabs(m.rot[3 * i + j]);
      if (a != 0.0 && a != 1.0) rs.exact = false;
    }
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(bg);
  set_stock_meta(*grid);
  openvdb::math::Transform::Ptr xf = openvdb::math::Transform::createLinearTransform(voxel);
  double o[3] = {s.origin[0], s.origin[1], s.origin[2]}, ot[3];
  m.apply(o, ot);
  xf->postTranslate(Vec3d(ot[0], ot[1], ot[2]));
  grid->setTransform(xf);
  std::vector<PlacedBlock> blocks;
  if (!s.content.empty()) {
    const openvdb::CoordBBox box = placed_box(s, m.rot, scale);
    if (box.volume() / 512 > (uint64_t(1) << 27))
      throw Error(SWARF_ERR_LIMIT,
                  "the stock is too large to place or resample (over 6.9e10 voxels)");
    for (int x = box.min()[0]; x <= box.max()[0]; x += 8)
      for (int y = box.min()[1]; y <= box.max()[1]; y += 8)
        for (int z = box.min()[2]; z <= box.max()[2]; z += 8)
          blocks.push_back({Coord(x, y, z), 0});
  }
  const Tree &src = s.grid->constTree();
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, blocks.size(), 64), [&](const tbb::blocked_range<size_t> &r) {
        openvdb::tree::ValueAccessor<const Tree> acc(src);
        for (size_t i = r.begin(); i != r.end(); ++i) {
          PlacedBlock &b = blocks[i];
          if (!rs.uniform(acc, b.origin))
            b.kind = 2;
          else
            b.kind =
                rs.value(acc, Vec3d(b.origin[0] + 3.5, b.origin[1] + 3.5, b.origin[2] + 3.5)) < 0.0f
                    ? 1
                    : 0;
        }
      });
  Tree &tree = grid->tree();
  std::vector<Leaf *> dense;
  for (const PlacedBlock &b : blocks) {
    if (b.kind == 1) tree.addTile(1, b.origin, -bg, false);
    if (b.kind == 2) dense.push_back(tree.touchLeaf(b.origin));
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, dense.size(), 4),
                    [&](const tbb::blocked_range<size_t> &r) {
                      openvdb::tree::ValueAccessor<const Tree> acc(src);
                      for (size_t i = r.begin(); i != r.end(); ++i) {
                        Leaf &leaf = *dense[i];
                        const Coord o = leaf.origin();
                        for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
                          const Coord j = o + Leaf::offsetToLocalCoord(n);
                          leaf.setValueOnly(n, rs.value(acc, Vec3d(j[0], j[1], j[2])));
                        }
                      }
                    });
  normalize_band(*grid, bg);
  return wrap_grid(grid);
}

std::unique_ptr<swarf_stock> read_vdb(const char *path, const swarf_stock_placement *p,
                                      double voxel, int half_width) {
  check_path(path);
  check_readable(path);
  if (!(voxel >= 0.0) || !std::isfinite(voxel))
    throw Error(SWARF_ERR_ARG, "voxel must be 0 (the file's) or > 0");
  init_openvdb();
  openvdb::FloatGrid::Ptr grid = read_grid(path);
  std::unique_ptr<swarf_stock> s(wrap_grid(grid)); // checks the transform and the background
  normalize_band(*grid, s->background);
  s.reset(wrap_grid(grid));
  if (!has_material(*grid)) throw Error(SWARF_ERR_FORMAT, "the grid holds no material");
  const bool revoxel = voxel > 0.0 && std::fabs(voxel - s->voxel) > 1e-9 * voxel;
  if (revoxel || (p && !placement_is_identity(*p))) {
    const int hw = half_width > 0 ? half_width : std::max(3, s->half_width);
    s.reset(resample(*s, placement_map(p ? *p : swarf_stock_placement{}),
                     revoxel ? voxel : s->voxel, revoxel ? hw : s->half_width));
  }
  return s;
}

std::string lower_extension(const char *path) {
  const char *dot = std::strrchr(path, '.'), *slash = std::strrchr(path, '/');
  std::string ext = dot && (!slash || dot > slash) ? dot + 1 : "";
  for (char &c : ext)
    c = char(std::tolower((unsigned char)c));
  return ext;
}

/// An STL file's points (placed by p, mm) and triangles.
void load_stl(const char *path, const swarf_stock_placement *p, std::vector<Vec3s> &pts,
              std::vector<Vec3I> &tris) {
  const Rigid m = placement_map(p ? *p : swarf_stock_placement{});
  TriMesh mesh;
  read_stl_file(path, mesh);
  pts.resize(mesh.vertices());
  for (size_t i = 0; i < pts.size(); i++) {
    const double x[3] = {mesh.xyz[3 * i], mesh.xyz[3 * i + 1], mesh.xyz[3 * i + 2]};
    double y[3];
    m.apply(x, y);
    pts[i] = Vec3s(float(y[0]), float(y[1]), float(y[2]));
  }
  tris.resize(mesh.triangles());
  for (size_t t = 0; t < tris.size(); t++)
    tris[t] = Vec3I(mesh.tri[3 * t], mesh.tri[3 * t + 1], mesh.tri[3 * t + 2]);
}

swarf_stock *read_stl(const char *path, const swarf_stock_placement *p, double voxel,
                      int half_width, bool keep_surface = false) {
  check_grid_args(voxel, half_width);
  std::vector<Vec3s> pts;
  std::vector<Vec3I> tris;
  load_stl(path, p, pts, tris);
  return mesh_stock(pts, tris, {}, voxel, half_width, keep_surface); // the guard names the path
}

} // namespace
} // namespace swarf

using swarf::Error;

extern "C" swarf_status swarf_stock_read_stl(const char *path, const swarf_stock_placement *place,
                                             double voxel, int half_width, swarf_stock **out,
                                             swarf_error *err) {
  if (out) *out = nullptr;
  return swarf::guard(err, path, [&] {
    if (out == nullptr) throw Error(SWARF_ERR_ARG, "out is NULL");
    *out = swarf::read_stl(path, place, voxel, half_width);
  });
}

extern "C" swarf_status swarf_stock_read_vdb(const char *path, const swarf_stock_placement *place,
                                             double voxel, int half_width, swarf_stock **out,
                                             swarf_error *err) {
  if (out) *out = nullptr;
  return swarf::guard(err, path, [&] {
    if (out == nullptr) throw Error(SWARF_ERR_ARG, "out is NULL");
    *out = swarf::read_vdb(path, place, voxel, half_width).release();
  });
}

extern "C" swarf_status swarf_stock_place(const swarf_stock *s, const swarf_stock_placement *p,
                                          swarf_stock **out, swarf_error *err) {
  if (out) *out = nullptr;
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || p == nullptr || out == nullptr)
      throw Error(SWARF_ERR_ARG, "stock, placement or out is NULL");
    *out = swarf::resample(*s, swarf::placement_map(*p), s->voxel, s->half_width);
  });
}

extern "C" swarf_status swarf_stock_resample(const swarf_stock *s, double voxel, int half_width,
                                             swarf_stock **out, swarf_error *err) {
  if (out) *out = nullptr;
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || out == nullptr) throw Error(SWARF_ERR_ARG, "stock or out is NULL");
    *out = swarf::resample(*s, swarf::placement_map(swarf_stock_placement{}), voxel, half_width);
  });
}

extern "C" swarf_status swarf_stock_read_design(const char *path, double voxel, swarf_stock **out,
                                                swarf_error *err) {
  return swarf_stock_read_design_band(path, voxel, SWARF_STOCK_DESIGN_BAND, out, err);
}

namespace swarf {

std::function<std::shared_ptr<MeshSurface>()> stl_surface_loader(const char *path, double voxel) {
  check_path(path);
  if (lower_extension(path) != "stl") throw Error(SWARF_ERR_ARG, "not a .stl file");
  struct stat was;
  if (stat(path, &was) != 0)
    throw Error(SWARF_ERR_IO, std::string("cannot read ") + path + ": " + std::strerror(errno));
  const std::string file(path);
  return [file, voxel, was] {
    struct stat now;
    if (stat(file.c_str(), &now) != 0 || now.st_ino != was.st_ino || now.st_size != was.st_size ||
        now.st_mtim.tv_sec != was.st_mtim.tv_sec || now.st_mtim.tv_nsec != was.st_mtim.tv_nsec)
      throw Error(SWARF_ERR_IO,
                  "the design " + file + " changed during the run: run again on the new one");
    std::vector<Vec3s> world;
    std::vector<Vec3I> tris;
    load_stl(file.c_str(), nullptr, world, tris);
    return mesh_surface(index_points(world, voxel), std::move(tris));
  };
}

} // namespace swarf

extern "C" swarf_status swarf_stock_design_surface(swarf_stock *design, const char *path,
                                                   swarf_error *err) {
  return swarf::guard(err, path, [&] {
    if (design == nullptr) throw Error(SWARF_ERR_ARG, "design is NULL");
    // read at the first depth beyond the band, if one comes
    design->surface = swarf::mesh_surface_lazy(swarf::stl_surface_loader(path, design->voxel));
  });
}

extern "C" swarf_status swarf_stock_read_design_band(const char *path, double voxel, int half_width,
                                                     swarf_stock **out, swarf_error *err) {
  if (out) *out = nullptr;
  return swarf::guard(err, path, [&] {
    if (out == nullptr) throw Error(SWARF_ERR_ARG, "out is NULL");
    swarf::check_path(path);
    const std::string ext = swarf::lower_extension(path);
    if (ext == "stl") {
      *out = swarf::read_stl(path, nullptr, voxel, half_width, /*keep_surface=*/true);
    } else if (ext == "vdb") {
      *out = swarf::read_vdb(path, nullptr, voxel, 0).release();
    } else {
      throw Error(SWARF_ERR_ARG, "a design is a .stl or a .vdb file");
    }
  });
}
