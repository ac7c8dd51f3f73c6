/* SPDX-License-Identifier: MPL-2.0 */
/// @file surface_file.cc
/// @brief A design's triangles as its exact distances search them, kept in a
/// file beside the design cache's band (swarf_stock_design_surface_save and
/// _cached). A warm run then reads 36 bytes a triangle back instead of the
/// STL: parsing, welding and checking it, and sorting the triangles along a
/// Morton curve took 0.9 s CPU for bear's 1.36 M-triangle design.
///
/// The file: a 40-byte header (the magic "swarfTRI", version 2, floats per
/// triangle 9, the count, the design's voxel, a 64-bit checksum of the
/// triangles' bytes), then the triangles, native floats (a cache is local to
/// its machine). A file that is not exactly that is refused: the caller reads
/// the STL instead. The triangles carry no indices, so any bytes that pass
/// make a surface that is safe to search.
#include "surface_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "atomic_file.h"
#include "mesh_file.h"
#include "stock_private.h"

namespace swarf {
namespace {

constexpr char kMagic[8] = {'s', 'w', 'a', 'r', 'f', 'T', 'R', 'I'};
constexpr uint32_t kVersion = 2, kFloats = 9; // 2: the four-lane checksum

struct Header {
  char magic[8];
  uint32_t version, floats;
  uint64_t count;
  double voxel;
  uint64_t checksum;
};
static_assert(sizeof(Header) == 40, "packed header");

} // namespace

/// FNV-1a over 8-byte words, with a multiply-xorshift finish per word, in
/// four lanes (32 bytes a step: the multiplies overlap, 4x the speed of one
/// chain) folded into one: a damaged byte changes it (not a defence against
/// a crafted file, which can only make the distances wrong: the caller owns
/// its cache folder).
uint64_t file_checksum(const char *p, size_t len) {
  constexpr uint64_t kPrime = 0x100000001b3ULL;
  uint64_t lane[4] = {0xcbf29ce484222325ULL, 0x9e3779b97f4a7c15ULL, 0xbf58476d1ce4e5b9ULL,
                      0x94d049bb133111ebULL};
  size_t i = 0;
  for (; i + 32 <= len; i += 32)
    for (int k = 0; k < 4; k++) {
      uint64_t w;
      std::memcpy(&w, p + i + 8 * k, 8);
      lane[k] = (lane[k] ^ w) * kPrime;
      lane[k] ^= lane[k] >> 29;
    }
  uint64_t h = lane[0];
  for (int k = 1; k < 4; k++) {
    h = (h ^ lane[k]) * kPrime;
    h ^= h >> 29;
  }
  for (; i < len; i++)
    h = (h ^ uint8_t(p[i])) * kPrime;
  return h ^ len;
}

void write_surface_file(const char *path, MeshSurface &m, double voxel) {
  size_t count = 0;
  const float *corners = mesh_surface_corners(m, &count);
  const char *bytes = reinterpret_cast<const char *>(corners);
  const size_t len = count * kFloats * sizeof(float);
  Header h;
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.version = kVersion;
  h.floats = kFloats;
  h.count = count;
  h.voxel = voxel;
  h.checksum = file_checksum(bytes, len);
  write_atomic(path, [&](std::ostream &os) {
    os.write(reinterpret_cast<const char *>(&h), sizeof h);
    if (len > 0) os.write(bytes, std::streamsize(len));
  });
}

namespace {

/// Throws Error(SWARF_ERR_FORMAT) unless h heads a surface file of `voxel`
/// mm whose triangles take `body` bytes.
void check_header(const Header &h, uint64_t body, double voxel) {
  if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0 || h.version != kVersion ||
      h.floats != kFloats)
    throw Error(SWARF_ERR_FORMAT, "not a surface file of this version");
  if (h.count > kMaxStlTriangles || body != h.count * kFloats * sizeof(float))
    throw Error(SWARF_ERR_FORMAT, "a surface file: its size is not its count's");
  if (!(h.voxel == voxel)) throw Error(SWARF_ERR_FORMAT, "a surface file of another voxel");
}

void check_sum(const Header &h, const float *corners) {
  if (file_checksum(reinterpret_cast<const char *>(corners), h.count * kFloats * sizeof(float)) !=
      h.checksum)
    throw Error(SWARF_ERR_FORMAT, "a surface file: damaged (its checksum does not match)");
}

} // namespace

std::shared_ptr<MeshSurface> parse_surface_file(const char *data, size_t len, double voxel) {
  Header h;
  if (len < sizeof h) throw Error(SWARF_ERR_FORMAT, "a surface file: too short for its header");
  std::memcpy(&h, data, sizeof h);
  check_header(h, len - sizeof h, voxel);
  return mesh_surface_ordered(size_t(h.count), [&](float *dst) {
    std::memcpy(dst, data + sizeof h, size_t(h.count) * kFloats * sizeof(float));
    check_sum(h, dst);
  });
}

std::shared_ptr<MeshSurface> read_surface_file(const char *path, double voxel) {
  check_path(path);
  std::FILE *f = std::fopen(path, "rb");
  if (f == nullptr)
    throw Error(SWARF_ERR_OPEN, std::string("cannot open ") + path + ": " + std::strerror(errno));
  std::unique_ptr<std::FILE, int (*)(std::FILE *)> closer(f, std::fclose);
  struct stat st;
  Header h;
  if (::fstat(::fileno(f), &st) != 0 || !S_ISREG(st.st_mode) || uint64_t(st.st_size) < sizeof h ||
      std::fread(&h, sizeof h, 1, f) != 1)
    throw Error(SWARF_ERR_FORMAT, std::string(path) + ": not a surface file");
  check_header(h, uint64_t(st.st_size) - sizeof h, voxel);
  // read straight into the surface's storage
  return mesh_surface_ordered(size_t(h.count), [&](float *dst) {
    const size_t n = size_t(h.count) * kFloats;
    if (std::fread(dst, sizeof(float), n, f) != n || std::fgetc(f) != EOF)
      throw Error(SWARF_ERR_FORMAT, std::string(path) + ": it changed while read");
    check_sum(h, dst);
  });
}

} // namespace swarf

extern "C" swarf_status swarf_stock_design_surface_save(const swarf_stock *design, const char *path,
                                                        swarf_error *err) {
  return swarf::guard(err, path, [&] {
    if (design == nullptr) throw swarf::Error(SWARF_ERR_ARG, "design is NULL");
    swarf::check_path(path);
    if (!design->surface)
      throw swarf::Error(SWARF_ERR_ARG, "the design was not read from a mesh: no triangles");
    swarf::write_surface_file(path, *design->surface, design->voxel);
  });
}

extern "C" swarf_status swarf_stock_design_surface_cached(swarf_stock *design, const char *cached,
                                                          const char *stl, swarf_error *err) {
  return swarf::guard(err, stl, [&] {
    if (design == nullptr) throw swarf::Error(SWARF_ERR_ARG, "design is NULL");
    swarf::check_path(cached);
    auto from_stl = swarf::stl_surface_loader(stl, design->voxel);
    const std::string file(cached);
    const double voxel = design->voxel;
    // At the first depth beyond the band: the cached triangles, or, if that
    // file cannot be read or is damaged, the STL's (the file goes).
    design->surface = swarf::mesh_surface_lazy([file, voxel, from_stl] {
      try {
        return swarf::read_surface_file(file.c_str(), voxel);
      } catch (const swarf::Error &) {
        ::unlink(file.c_str());
        return from_stl();
      }
    });
  });
}
