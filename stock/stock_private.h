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

#include <cstdint>
#include <new>
#include <string>
#include <vector>

#include "stock.h"
#include "stock_error.h"

namespace swarf {

/// One (block, cut) pair of a removal: the index origin of a leaf-aligned 8^3
/// block and the number of a cut whose padded bounds meet it.
struct BlockCut {
  int32_t x, y, z;
  uint32_t cut;
};

/// A block of a removal and what the removal does to it.
struct Block {
  openvdb::Coord origin;  ///< index origin of the 8^3 block
  uint32_t begin, count;  ///< its cuts: pairs[begin, begin + count) after classification
  uint8_t action;         ///< see remove.cc
  float tile;             ///< value of the tile replacing the block when it collapses
};

/// Buffers of the removal, kept in the handle so that a removal allocates nothing
/// once they have grown (one removal at a time per handle).
struct RemoveScratch {
  std::vector<BlockCut> pairs;
  std::vector<double> centre_sdf;  ///< sdf (mm) at the block centre, one per pair
  std::vector<Block> blocks;
  std::vector<uint32_t> visit;     ///< blocks whose voxels are visited
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

}  // namespace swarf

/// The stock: a float narrow-band level set (negative inside material).
struct swarf_stock {
  openvdb::FloatGrid::Ptr grid;
  double voxel;                 ///< voxel edge, mm
  openvdb::Vec3d origin;        ///< world position (mm) of the voxel centre at index (0,0,0)
  float background;             ///< band half-width in mm: inactive values are +-background
  int half_width;               ///< band half-width in voxels (background / voxel, rounded)
  openvdb::CoordBBox content;   ///< index box holding all material and band; never grows
  swarf::RemoveScratch scratch;
};

namespace swarf {

/// Wrap a float level-set grid into a new handle, after checking what the rest
/// of the module relies on: linear transform, uniform axis-aligned positive
/// scale, finite positive voxel and background, index box within +-2^30.
/// Throws Error(SWARF_ERR_FORMAT) with the reason otherwise.
swarf_stock *wrap_grid(openvdb::FloatGrid::Ptr grid);

/// Apply stock = max(stock, -sdf) for every cut (remove.cc). Arguments are
/// assumed checked. On an exception the stock may be partly cut but stays a
/// valid narrow band.
void remove_cuts(swarf_stock &s, const swarf_stock_cut *cuts, size_t ncuts);

/// True if the cut (checked) overlaps the material deeper than depth (mm):
/// a voxel centre, returned in where, lies that deep inside both (remove.cc).
bool cut_overlaps(const swarf_stock &s, const swarf_stock_cut &cut, double depth,
                  openvdb::Vec3d &where);

/// True if the cut (checked) penetrates the material by more than depth (mm):
/// a voxel centre inside both where the two depths add up to more (remove.cc).
bool cut_penetrates(const swarf_stock &s, const swarf_stock_cut &cut, const swarf_stock_cut *clear,
                    size_t nclear, double depth, openvdb::Vec3d &where);

/// World position (mm) of the centre of voxel ijk.
inline openvdb::Vec3d index_to_world(const swarf_stock &s, const openvdb::Coord &ijk) {
  return s.origin + s.voxel * ijk.asVec3d();
}

}  // namespace swarf

#endif
