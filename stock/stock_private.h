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

/// Copy `text` into msg (at most msglen bytes, NUL-terminated); NULL msg is fine.
void set_message(char *msg, size_t msglen, const std::string &text);

/// Run `body` and translate every exception into a status and a message; on
/// success msg is set to the empty string. Never throws.
template <class F> int guard(char *msg, size_t msglen, F &&body) noexcept {
  try {
    try {
      body();
      set_message(msg, msglen, "");
      return SWARF_STOCK_OK;
    } catch (const Error &e) {
      set_message(msg, msglen, e.what());
      return e.status;
    } catch (const std::bad_alloc &) {
      set_message(msg, msglen, "out of memory");
      return SWARF_STOCK_ERR_MEMORY;
    } catch (const openvdb::Exception &e) {
      set_message(msg, msglen, std::string("OpenVDB: ") + e.what());
      return SWARF_STOCK_ERR_INTERNAL;
    } catch (const std::exception &e) {
      set_message(msg, msglen, std::string("internal error: ") + e.what());
      return SWARF_STOCK_ERR_INTERNAL;
    }
  } catch (...) {
    set_message(msg, msglen, "internal error: unknown exception");
    return SWARF_STOCK_ERR_INTERNAL;
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
/// Throws Error(SWARF_STOCK_ERR_FORMAT) with the reason otherwise.
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
