/* SPDX-License-Identifier: MPL-2.0 */
/// @file band_file.cc
/// @brief A stock's grid in swarf's own file (swarf_stock_write_band and
/// swarf_stock_read_band), read in-process: the design cache keeps a
/// design's band so. Reading it back as a .vdb goes through OpenVDB's parser
/// in a child process (io.cc), which re-serializes the grid for the parent
/// to parse again: 0.3 s CPU a warm run for bear's design at 0.2 mm, against
/// a few hundredths here.
///
/// The file: an 80-byte header (the magic "swarfBND", version 1, the band in
/// voxels, the voxel, the transform's translation, the background, the
/// counts of tiles and leaves, a 64-bit checksum of all that follows), then
/// the tiles that are not the background (24 bytes: level, origin, value,
/// active), then the leaves: origin and kind (16 bytes), the active mask (64),
/// and either the signs of the inactive voxels (64: each is -background or
/// +background) and the active values, or, when an inactive value is
/// anything else, all 512 values. Native byte order (a cache is local to its
/// machine). Parsing checks every count against the file's size, every
/// origin's alignment and range, and the grid as swarf_stock_read does
/// (io.cc's check_stock_grid), so any bytes that pass make a sound stock.
#include "band_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "atomic_file.h"
#include "stock_private.h"

namespace swarf {
namespace {

using Tree = openvdb::FloatTree;
using Leaf = Tree::LeafNodeType;
using Mask = Leaf::NodeMaskType;

constexpr char kMagic[8] = {'s', 'w', 'a', 'r', 'f', 'B', 'N', 'D'};
constexpr uint32_t kVersion = 1;
constexpr int32_t kLimit = 1 << 30;   ///< origins within +-2^30 voxels (wrap_grid's bound)
constexpr int32_t kMaxHalfWidth = 64; ///< voxels, as stock.cc's

struct Header {
  char magic[8];
  uint32_t version;
  int32_t half_width;
  double voxel;
  double translation[3];
  float background;
  uint32_t reserved;
  uint64_t tiles, leaves;
  uint64_t checksum;
};
static_assert(sizeof(Header) == 80, "packed header");

struct TileRecord {
  int32_t level, xyz[3];
  float value;
  uint32_t active;
};
static_assert(sizeof(TileRecord) == 24, "packed tile");

struct LeafHead {
  int32_t xyz[3];
  uint32_t full; ///< 0: signs and active values; 1: all 512 values
};
static_assert(sizeof(LeafHead) == 16, "packed leaf head");
static_assert(sizeof(Mask) == 64, "an 8^3 mask is 64 bytes");

template <class T> void put(std::string &out, const T &v) {
  out.append(reinterpret_cast<const char *>(&v), sizeof v);
}

/// One leaf's record: compact when every inactive value is +-background.
void put_leaf(std::string &out, const Leaf &leaf, float bg) {
  const Mask &active = leaf.getValueMask();
  Mask negative;
  bool compact = true;
  for (openvdb::Index n = 0; n < Leaf::SIZE; n++) {
    if (active.isOn(n)) continue;
    const float v = leaf.getValue(n); // bg > 0: equal values are equal bits
    if (v == -bg)
      negative.setOn(n);
    else if (v != bg)
      compact = false;
  }
  const openvdb::Coord o = leaf.origin();
  put(out, LeafHead{{o.x(), o.y(), o.z()}, compact ? 0u : 1u});
  out.append(reinterpret_cast<const char *>(&active), sizeof active);
  if (!compact) {
    out.append(reinterpret_cast<const char *>(leaf.buffer().data()), Leaf::SIZE * sizeof(float));
    return;
  }
  out.append(reinterpret_cast<const char *>(&negative), sizeof negative);
  for (auto v = leaf.cbeginValueOn(); v; ++v)
    put(out, *v);
}

/// A cursor over the body that refuses to read past its end.
struct Reader {
  const char *p, *end;
  void take(void *dst, size_t n) {
    if (size_t(end - p) < n) throw Error(SWARF_ERR_FORMAT, "a band file: shorter than its counts");
    std::memcpy(dst, p, n);
    p += n;
  }
};

void check_origin(const int32_t xyz[3], int32_t align) {
  for (int k = 0; k < 3; k++)
    if (xyz[k] % align != 0 || xyz[k] <= -kLimit || xyz[k] >= kLimit)
      throw Error(SWARF_ERR_FORMAT, "a band file: a node's origin is out of range or unaligned");
}

void check_header(const Header &h, uint64_t body) {
  if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0 || h.version != kVersion || h.reserved)
    throw Error(SWARF_ERR_FORMAT, "not a band file of this version");
  if (!std::isfinite(h.voxel) || !(h.voxel > 0.0) || !std::isfinite(h.background) ||
      !(h.background > 0.0f) || h.half_width < 1 || h.half_width > kMaxHalfWidth)
    throw Error(SWARF_ERR_FORMAT, "a band file: its voxel, band or background is out of range");
  for (double t : h.translation)
    if (!std::isfinite(t)) throw Error(SWARF_ERR_FORMAT, "a band file: its origin is not finite");
  if (h.tiles > body / sizeof(TileRecord) ||
      h.leaves > body / (sizeof(LeafHead) + 2 * sizeof(Mask)))
    throw Error(SWARF_ERR_FORMAT, "a band file: its counts do not fit its size");
}

void add_tiles(Reader &r, uint64_t n, Tree &tree) {
  for (uint64_t i = 0; i < n; i++) {
    TileRecord t;
    r.take(&t, sizeof t);
    if (t.level < 1 || t.level > 3 || t.active > 1)
      throw Error(SWARF_ERR_FORMAT, "a band file: a tile of no level a tree has");
    check_origin(t.xyz, t.level == 1 ? 8 : t.level == 2 ? 128 : 4096);
    tree.addTile(openvdb::Index(t.level), openvdb::Coord(t.xyz[0], t.xyz[1], t.xyz[2]), t.value,
                 t.active != 0);
  }
}

void add_leaves(Reader &r, uint64_t n, float bg, Tree &tree) {
  for (uint64_t i = 0; i < n; i++) {
    LeafHead h;
    Mask active, negative;
    r.take(&h, sizeof h);
    if (h.full > 1) throw Error(SWARF_ERR_FORMAT, "a band file: a leaf of no known kind");
    check_origin(h.xyz, 8);
    const openvdb::Coord o(h.xyz[0], h.xyz[1], h.xyz[2]);
    if (tree.probeConstLeaf(o) != nullptr)
      throw Error(SWARF_ERR_FORMAT, "a band file: two leaves at one origin");
    r.take(&active, sizeof active);
    auto leaf = std::make_unique<Leaf>(o, bg);
    float *v = leaf->buffer().data();
    if (h.full) {
      r.take(v, Leaf::SIZE * sizeof(float));
    } else {
      r.take(&negative, sizeof negative);
      for (openvdb::Index k = 0; k < Leaf::SIZE; k++)
        if (active.isOn(k))
          r.take(&v[k], sizeof(float));
        else if (negative.isOn(k))
          v[k] = -bg;
    }
    leaf->setValueMask(active);
    tree.addLeaf(leaf.release());
  }
}

} // namespace

void write_band_file(const char *path, const swarf_stock &s) {
  const Tree &tree = s.grid->constTree();
  const float bg = tree.background();
  std::string body;
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.version = kVersion;
  h.half_width = s.half_width;
  h.voxel = s.voxel;
  const openvdb::Vec3d t =
      s.grid->transform().baseMap()->getAffineMap()->getMat4().getTranslation();
  for (int k = 0; k < 3; k++)
    h.translation[k] = t[k];
  h.background = bg;
  auto it = tree.cbeginValueAll();
  it.setMaxDepth(Tree::ValueAllCIter::LEAF_DEPTH - 1);
  for (; it; ++it) // the background's tiles are what a new tree has
    if (it.isValueOn() || std::memcmp(&*it, &bg, sizeof bg) != 0) {
      const openvdb::Coord c = it.getCoord();
      put(body,
          TileRecord{int32_t(it.getLevel()), {c.x(), c.y(), c.z()}, *it, it.isValueOn() ? 1u : 0u});
      h.tiles++;
    }
  for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf, h.leaves++)
    put_leaf(body, *leaf, bg);
  h.checksum = file_checksum(body.data(), body.size());
  write_atomic(path, [&](std::ostream &os) {
    os.write(reinterpret_cast<const char *>(&h), sizeof h);
    os.write(body.data(), std::streamsize(body.size()));
  });
}

swarf_stock *parse_band_file(const char *data, size_t len) {
  Header h;
  if (len < sizeof h) throw Error(SWARF_ERR_FORMAT, "a band file: too short for its header");
  std::memcpy(&h, data, sizeof h);
  check_header(h, len - sizeof h);
  Reader r{data + sizeof h, data + len};
  if (file_checksum(r.p, size_t(r.end - r.p)) != h.checksum)
    throw Error(SWARF_ERR_FORMAT, "a band file: damaged (its checksum does not match)");
  init_openvdb();
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(h.background);
  grid->setName("stock");
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  grid->setSaveFloatAsHalf(false);
  openvdb::math::Transform::Ptr xf = openvdb::math::Transform::createLinearTransform(h.voxel);
  xf->postTranslate(openvdb::Vec3d(h.translation[0], h.translation[1], h.translation[2]));
  grid->setTransform(xf);
  add_tiles(r, h.tiles, grid->tree());
  add_leaves(r, h.leaves, h.background, grid->tree());
  if (r.p != r.end) throw Error(SWARF_ERR_FORMAT, "a band file: bytes beyond its counts");
  check_stock_grid(*grid, "a band file");
  std::unique_ptr<swarf_stock> s(wrap_grid(grid));
  if (s->half_width != h.half_width)
    throw Error(SWARF_ERR_FORMAT, "a band file: its band is not its background's");
  return s.release();
}

swarf_stock *read_band_file(const char *path) {
  std::FILE *f = std::fopen(path, "rb");
  if (f == nullptr)
    throw Error(SWARF_ERR_OPEN, std::string("cannot open ") + path + ": " + std::strerror(errno));
  std::unique_ptr<std::FILE, int (*)(std::FILE *)> closer(f, std::fclose);
  struct stat st;
  if (::fstat(::fileno(f), &st) != 0 || !S_ISREG(st.st_mode))
    throw Error(SWARF_ERR_FORMAT, std::string(path) + ": not a band file");
  std::string bytes(size_t(st.st_size), '\0');
  if (std::fread(&bytes[0], 1, bytes.size(), f) != bytes.size() || std::fgetc(f) != EOF)
    throw Error(SWARF_ERR_FORMAT, std::string(path) + ": it changed while read");
  return parse_band_file(bytes.data(), bytes.size());
}

} // namespace swarf

extern "C" swarf_status swarf_stock_write_band(const swarf_stock *s, const char *path,
                                               swarf_error *err) {
  return swarf::guard(err, path, [&] {
    if (s == nullptr) throw swarf::Error(SWARF_ERR_ARG, "stock is NULL");
    swarf::check_path(path);
    swarf::write_band_file(path, *s);
  });
}

extern "C" swarf_status swarf_stock_read_band(const char *path, swarf_stock **out,
                                              swarf_error *err) {
  if (out == nullptr) return swarf::set_error(err, SWARF_ERR_ARG, path, "out is NULL");
  *out = nullptr;
  return swarf::guard(err, path, [&] {
    swarf::check_path(path);
    swarf::check_readable(path);
    *out = swarf::read_band_file(path);
  });
}
