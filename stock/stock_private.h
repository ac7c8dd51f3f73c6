/* SPDX-License-Identifier: MPL-2.0 */
/// @file stock_private.h
/// @brief The swarf_stock handle and the helpers shared by the stock/*.cc files
/// (the C++ behind stock.h). Only the stock module includes this header.
///
/// Frames: a voxel's index coordinate ijk (integers) and its centre in world
/// units (mm) are related by world = origin + voxel * ijk. Grids made here have
/// origin (0, 0, 0); grids read from files may carry a translation (never a
/// rotation or a non-uniform scale: those are refused when reading).
#ifndef SWARF_STOCK_PRIVATE_H
#define SWARF_STOCK_PRIVATE_H

#include <openvdb/openvdb.h>

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "stock.h"
#include "stock_error.h"

namespace swarf {

struct MeshSurface; // mesh_sdf.h

/// Exact distance (mm, >= 0) from world point w to the surface of design d
/// (d.surface non-null; mesh_surface.cc).
double surface_distance_exact(const swarf_stock &d, const openvdb::Vec3d &w);
/// The same at a voxel centre w of d, rounded as a band of
/// SWARF_STOCK_DESIGN_BAND voxels stores it within that band (a float, from
/// the float squared distance): a design read with a narrower band (its
/// values beyond measured here) gives the depths, and their ties, of one read
/// with that band bit for bit; exact (double) beyond.
double surface_distance(const swarf_stock &d, const openvdb::Vec3d &w);

/// One (block, cut) pair of a removal: the index origin of a leaf-aligned 8^3
/// block and the number of a cut whose padded bounds meet it.
struct BlockCut {
  int32_t x, y, z;
  uint32_t cut;
};

/// A block of a removal and what the removal does to it.
struct Block {
  openvdb::Coord origin; ///< index origin of the 8^3 block
  uint32_t begin, count; ///< its cuts: pairs[begin, begin + count) after classification
  uint8_t action;        ///< see remove.cc
  float tile;            ///< value of the tile replacing the block when it collapses; for a
                         ///< block that was a tile, that tile's value until then
  bool tile_on;          ///< a block that was a tile: that tile's active state
};

/// An allocator that default-initializes what a vector grows by: a vector of
/// a trivial type resized gets its new elements unwritten, not zeroed. For
/// scratch the removal writes in parallel before it reads it: zeroing the
/// first batch's pairs and centre planes on the calling thread alone (and
/// the page faults that come with it) took ~0.1 s of bear at 0.1 mm.
template <typename T> struct UninitAlloc : std::allocator<T> {
  template <typename U> struct rebind { using other = UninitAlloc<U>; };
  UninitAlloc() = default;
  template <typename U> UninitAlloc(const UninitAlloc<U> &) noexcept {}
  template <typename U> void construct(U *p) { ::new (static_cast<void *>(p)) U; }
  template <typename U, typename... A> void construct(U *p, A &&...a) {
    ::new (static_cast<void *>(p)) U(std::forward<A>(a)...);
  }
};
/// A vector whose growth writes nothing (UninitAlloc).
template <typename T> using ScratchVector = std::vector<T, UninitAlloc<T>>;

/// Buffers of the removal, kept in the handle so that a removal allocates nothing
/// once they have grown (one removal at a time per handle).
struct RemoveScratch {
  ScratchVector<BlockCut> pairs;
  ScratchVector<double> centre_sdf; ///< sdf (mm) at the block centre, one per pair
  /// Per pair, where the cut has a supporting plane at the block centre
  /// (swarf_stock_support_fn): its unit normal; else a NaN first component.
  ScratchVector<openvdb::Vec3d> centre_plane;
  std::vector<Block> blocks;
  std::vector<uint32_t> visit; ///< blocks whose voxels are visited
  /// Per visited block that was a tile: its leaf, made by the visit and put
  /// in the tree after it (null where it collapsed back to a tile).
  std::vector<std::unique_ptr<openvdb::FloatTree::LeafNodeType>> fresh;
  /// Measured removals only, one per pair: what the pair's cut did in the block.
  std::vector<double> removed; ///< inside fraction removed (voxels, not yet mm^3)
  std::vector<double> gouge;   ///< deepest gouge (mm), 0 if none
  std::vector<openvdb::Vec3d> gouge_at;
};

/// What a measured removal measures (remove_cuts).
struct Measure {
  const swarf_stock *design;       ///< may be NULL: no gouges
  double tolerance;                ///< mm
  swarf_stock_cut_effect *effects; ///< one per cut, filled
  /// false: the gouges only (swarf_stock_remove_batch_gouges_support): no
  /// volumes (removed left 0), and voxels that cannot gouge are not replayed
  bool volumes = true;
};

/// Call openvdb::initialize() once per process (thread-safe).
void init_openvdb();

/// Fill err (may be NULL) with a failure: cleared, then the status, the
/// message `text` and the file (NULL: none). Returns status.
swarf_status set_error(swarf_error *err, swarf_status status, const char *file,
                       const std::string &text) noexcept;

/// Run `body` and translate every exception into a status and err (may be
/// NULL; `file`, may be NULL, is the file the call reads or writes). err is
/// left as it is on success. Never throws.
template <class F> swarf_status guard(swarf_error *err, const char *file, F &&body) noexcept {
  try {
    try {
      body();
      return SWARF_OK;
    } catch (const Error &e) {
      return set_error(err, e.status, file, e.what());
    } catch (const std::bad_alloc &) {
      return set_error(err, SWARF_ERR_MEMORY, file, "out of memory");
    } catch (const openvdb::Exception &e) {
      return set_error(err, SWARF_ERR_INTERNAL, file, std::string("OpenVDB: ") + e.what());
    } catch (const std::exception &e) {
      return set_error(err, SWARF_ERR_INTERNAL, file, std::string("internal error: ") + e.what());
    }
  } catch (...) {
    return set_error(err, SWARF_ERR_INTERNAL, file, "internal error: unknown exception");
  }
}

} // namespace swarf

/// The stock: a float narrow-band level set (negative inside material).
struct swarf_stock {
  openvdb::FloatGrid::Ptr grid;
  double voxel;               ///< voxel edge, mm
  openvdb::Vec3d origin;      ///< world position (mm) of the voxel centre at index (0,0,0)
  float background;           ///< band half-width in mm: inactive values are +-background
  int half_width;             ///< band half-width in voxels (background / voxel, rounded)
  openvdb::CoordBBox content; ///< index box holding all material and band; never grows
  swarf::RemoveScratch scratch;
  /// A design read from a mesh: its triangles (index space of this grid),
  /// for exact distances beyond the band (mesh_sdf.h); null otherwise.
  std::shared_ptr<swarf::MeshSurface> surface;
  int threads = 0;                        ///< swarf_stock_set_threads: 0 all cores
  std::shared_ptr<tbb::task_arena> arena; ///< the removal's threads when threads > 0
  swarf_stock_tick_fn tick = nullptr;     ///< swarf_stock_set_tick
  void *tick_user = nullptr;
  double tick_every = 0.0; ///< seconds
  /// swarf_stock_set_region: removal and queries only in the blocks whose
  /// origin lies in [region_lo, region_hi] (block origins, multiples of 8).
  bool has_region = false;
  openvdb::Coord region_lo, region_hi;
  /// swarf_stock_set_tally: cuts visiting each block of a box of blocks
  /// (origin tally_lo, tally_n blocks a side; the caller's array).
  unsigned long long *tally = nullptr;
  openvdb::Coord tally_lo, tally_n;
};

namespace swarf {

/// Wrap a float level-set grid into a new handle, after checking what the rest
/// of the module relies on: linear transform, uniform axis-aligned positive
/// scale, finite positive voxel and background, index box within +-2^30.
/// Throws Error(SWARF_ERR_FORMAT) with the reason otherwise.
swarf_stock *wrap_grid(openvdb::FloatGrid::Ptr grid);

/// Run f on the stock's threads (swarf_stock_set_threads; all cores unless set).
template <class F> void in_arena(swarf_stock &s, F &&f) {
  if (s.arena)
    s.arena->execute(f);
  else
    f();
}

/// A shallow copy of s's grid (the tree shared) for io::Archive::write that
/// compresses its leaves on s's threads, the bytes those of OpenVDB's own
/// serial loop (write_leaves.cc).
openvdb::FloatGrid::Ptr leaf_parallel_copy(const swarf_stock &s);

/// A box stock's faces (mm): box_outside's context (stock.cc).
struct ShapeBox {
  double lo[3], hi[3];
  /// How far coordinate p on axis k lies beyond the nearer of the box's two
  /// faces across that axis (negative between them).
  double beyond(int k, double p) const { return std::max(lo[k] - p, p - hi[k]); }
  /// The box's exact signed distance from a point's beyond() on the three axes.
  static double distance(double qx, double qy, double qz) {
    double out2 = 0.0;
    if (qx > 0.0) out2 += qx * qx;
    if (qy > 0.0) out2 += qy * qy;
    if (qz > 0.0) out2 += qz * qz;
    return out2 > 0.0 ? std::sqrt(out2) : std::max(std::max(qx, qy), qz);
  }
};

/// The band of a new stock holding -background in the block-aligned index
/// box `blocks` (and nothing else): as removing the cut {outside < 0} there
/// (shape.cc; bit for bit what remove_cuts gives). box: where outside is a
/// box's (box_outside), its faces, which fill the blocks row by row.
void fill_shape(swarf_stock &s, swarf_stock_sdf_fn outside, const void *ctx,
                const openvdb::CoordBBox &blocks, const ShapeBox *box = nullptr);

/// Apply stock = max(stock, -sdf) for every cut (remove.cc). Arguments are
/// assumed checked. On an exception the stock may be partly cut but stays a
/// valid narrow band.
void remove_cuts(swarf_stock &s, const swarf_stock_cut *cuts, size_t ncuts,
                 const Measure *measure = nullptr, const swarf_stock_support_fn *support = nullptr);

/// Tolerance and colour range (mm) of an output's options with the defaults
/// of stock.h filled in (render.cc). Throws Error(ARG) for bad values.
void output_scale(const swarf_stock &s, const swarf_stock_output &o, double &tol, double &range);

/// Throw Error(ARG) unless the design's and the stock's bounds meet (compare.cc).
void check_design(const swarf_stock &s, const swarf_stock &design);

/// Deepest gouge of the cut (see swarf_stock_gouge; arguments checked):
/// depth (0 if not deeper than the tolerance) and where (remove.cc).
double cut_gouge(const swarf_stock &s, const swarf_stock &design, const swarf_stock_cut &cut,
                 double tolerance, openvdb::Vec3d &where);

/// True if the cut (checked) overlaps the material deeper than depth (mm):
/// a voxel centre, returned in where, lies that deep inside both (remove.cc).
bool cut_overlaps(const swarf_stock &s, const swarf_stock_cut &cut, double depth,
                  openvdb::Vec3d &where);

/// The band half-width in mm for `half_width` voxels of `voxel` mm, as a float
/// background: the smallest float with background / voxel >= half_width in
/// double (OpenVDB's checkLevelSet tests exactly that; float(3 * 0.3) = 0.9f
/// is below 3 * 0.3 and failed it).
float band_background(int half_width, double voxel);

/// Throw Error(SWARF_ERR_OPEN) unless `path` names an existing regular file (io.cc).
void check_readable(const char *path);

/// The float level set of a .vdb file ("stock", or the first), read in a
/// child process (io.cc; untrusted input). Throws Error(FORMAT) otherwise.
openvdb::FloatGrid::Ptr read_grid(const std::string &path);

/// The bounds on a grid read as a stock (io.cc): its root table, active
/// tiles, finite values and extent. Throws Error(FORMAT or LIMIT) naming `what`.
void check_stock_grid(const openvdb::FloatGrid &grid, const std::string &what);

/// A 64-bit checksum of the bytes of a file the design cache keeps
/// (surface_file.cc): a damaged byte changes it.
uint64_t file_checksum(const char *p, size_t len);
/// True if the cut (checked) penetrates the material by more than depth (mm):
/// a voxel centre inside both where the two depths add up to more (remove.cc).
bool cut_penetrates(const swarf_stock &s, const swarf_stock_cut &cut, const swarf_stock_cut *clear,
                    size_t nclear, double depth, openvdb::Vec3d &where);

/// World position (mm) of the centre of voxel ijk.
inline openvdb::Vec3d index_to_world(const swarf_stock &s, const openvdb::Coord &ijk) {
  return s.origin + s.voxel * ijk.asVec3d();
}

/// A voxel's value as stored: float, clamped to the band (remove.cc, shape.cc).
inline float stored(double m, float bgf) {
  const float v = float(m);
  return v >= bgf ? bgf : v <= -bgf ? -bgf : v;
}

/// Inside fraction of a voxel whose value is phi (mm): a ramp one voxel wide,
/// exact for a plane parallel to a voxel face at any offset; NaN counts as outside.
inline double inside_fraction(double phi, double voxel) {
  const double t = 0.5 - phi / voxel;
  return t > 1.0 ? 1.0 : t > 0.0 ? t : 0.0;
}

/// Reads a level set (a design, another stock) at the voxel centres of a
/// grid `frame`: the stored values when both lattices coincide (same voxel,
/// origins whole voxels apart), trilinear interpolation otherwise. One per
/// thread (it holds a value accessor). Outside its content: its background.
class GridProbe {
public:
  GridProbe(const swarf_stock &g, const swarf_stock &frame)
      : g_(g), acc_(g.grid->constTree()), aligned_(lattices_coincide(g, frame)) {}
  /// Value (mm) at world point w (a voxel centre of frame).
  double at(const openvdb::Vec3d &w) {
    const openvdb::Vec3d i = (w - g_.origin) / g_.voxel;
    if (aligned_)
      return acc_.getValue(
          openvdb::Coord(int(std::lround(i[0])), int(std::lround(i[1])), int(std::lround(i[2]))));
    return trilinear(i);
  }
  /// Value at the frame's voxel whose index in g is ijk (aligned probes only).
  float at_index(const openvdb::Coord &ijk) { return acc_.getValue(ijk); }
  bool aligned() const { return aligned_; }
  /// The index in g of a world point, rounded (aligned probes only).
  openvdb::Coord index_of(const openvdb::Vec3d &w) const {
    const openvdb::Vec3d i = (w - g_.origin) / g_.voxel;
    return openvdb::Coord(int(std::lround(i[0])), int(std::lround(i[1])), int(std::lround(i[2])));
  }
  static bool lattices_coincide(const swarf_stock &a, const swarf_stock &b) {
    if (std::fabs(a.voxel - b.voxel) > 1e-9 * a.voxel) return false;
    for (int k = 0; k < 3; k++) {
      const double d = (a.origin[k] - b.origin[k]) / a.voxel;
      if (std::fabs(d - std::round(d)) > 1e-6) return false;
    }
    return true;
  }

private:
  double trilinear(const openvdb::Vec3d &i) {
    const double fx = std::floor(i[0]), fy = std::floor(i[1]), fz = std::floor(i[2]);
    if (!(std::fabs(fx) < 1e9 && std::fabs(fy) < 1e9 && std::fabs(fz) < 1e9)) return g_.background;
    const openvdb::Coord c(static_cast<int>(fx), static_cast<int>(fy), static_cast<int>(fz));
    const double u = i[0] - fx, v = i[1] - fy, w = i[2] - fz;
    double r = 0.0;
    for (int k = 0; k < 8; k++) {
      const double wt = (k & 1 ? u : 1 - u) * (k & 2 ? v : 1 - v) * (k & 4 ? w : 1 - w);
      if (wt != 0.0) r += wt * acc_.getValue(c.offsetBy(k & 1, (k >> 1) & 1, (k >> 2) & 1));
    }
    return r;
  }
  const swarf_stock &g_;
  openvdb::tree::ValueAccessor<const openvdb::FloatTree> acc_;
  bool aligned_;
};

/// How far (mm) the region a voxel centre vouches for reaches beyond it: the
/// radius of the ball the region is known to hold (|value| of the grids
/// bounding it), capped at one voxel (the estimate of stock.h's depths).
inline double vouched_radius(double r, double voxel) {
  return r < voxel ? r : voxel;
}

} // namespace swarf

#endif
