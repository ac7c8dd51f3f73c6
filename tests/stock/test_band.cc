/* SPDX-License-Identifier: MPL-2.0 */
/* test_band.cc -- swarf's own band file (swarf_stock_write_band and
 * swarf_stock_read_band, stock/band_file.cc), the design cache's copy of a
 * design's band.
 *
 * Truth: what is read back is the grid written, value for value: every
 * voxel of its box (tiles included) bit for bit, and the same as the .vdb
 * of the same stock read through OpenVDB's reader; transform, band and
 * background alike. A leaf whose inactive values are not +-background (the
 * file's full kind) comes back bit for bit too. Every damaged or crafted
 * file is refused with SWARF_ERR_FORMAT and a message (those past the
 * checksum are built with the file's own checksum), never a crash; a
 * missing file is SWARF_ERR_OPEN.
 */
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "band_file.h"
#include "check.h"
#pragma GCC diagnostic push // shapes.h is C: its {0} initialisers are C's
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include "shapes.h"
#pragma GCC diagnostic pop
#include "stl_box.h"

namespace {

/// Every voxel of the union of both stocks' boxes, bit for bit.
bool same_values(const swarf_stock *a, const swarf_stock *b) {
  int lo[3], dims[3], lo2[3], dims2[3];
  double o[3];
  swarf_stock_dense_box(a, lo, dims, o);
  swarf_stock_dense_box(b, lo2, dims2, o);
  for (int k = 0; k < 3; k++) {
    const int hi = std::max(lo[k] + dims[k], lo2[k] + dims2[k]) + 8;
    lo[k] = std::min(lo[k], lo2[k]) - 8;
    dims[k] = hi - lo[k];
  }
  const size_t n = size_t(dims[0]) * dims[1] * dims[2];
  std::vector<float> va(n), vb(n);
  swarf_error err = {};
  if (swarf_stock_to_dense(a, lo, dims, va.data(), &err) != SWARF_OK ||
      swarf_stock_to_dense(b, lo, dims, vb.data(), &err) != SWARF_OK)
    return false;
  return std::memcmp(va.data(), vb.data(), n * sizeof(float)) == 0;
}

/// Voxel, origin, band and background (the content box of a stock read
/// back is its tree's: compare it between two read back).
bool same_frame(const swarf_stock *a, const swarf_stock *b) {
  return a->voxel == b->voxel && a->origin == b->origin && a->half_width == b->half_width &&
         a->background == b->background;
}

swarf_stock *cut_box() {
  const double lo[3] = {0.0, 0.0, -3.0}, hi[3] = {6.0, 5.0, 0.0};
  swarf_stock *s = nullptr;
  swarf_error err = {};
  CHECK(swarf_stock_new_box(lo, hi, 0.1, 3, &s, &err) == SWARF_OK, "box: %s", err.message);
  capsule_shape slot = {{1.0, 2.5, 0.5}, {5.0, 2.5, 0.5}, 1.2};
  swarf_stock_cut cut = capsule_cut(&slot);
  CHECK(s && swarf_stock_remove_batch(s, &cut, 1, &err) == SWARF_OK, "slot: %s", err.message);
  return s;
}

/// s written as a band and as a .vdb, both read back: the same grid.
void round_trip(const swarf_stock *s, const char *what) {
  swarf_error err = {};
  swarf_stock *band = nullptr, *vdb = nullptr;
  CHECK(swarf_stock_write_band(s, "band_test.band", &err) == SWARF_OK, "%s: write: %s", what,
        err.message);
  CHECK(swarf_stock_read_band("band_test.band", &band, &err) == SWARF_OK, "%s: read: %s", what,
        err.message);
  CHECK(swarf_stock_write_vdb(s, "band_test.vdb", &err) == SWARF_OK &&
            swarf_stock_read("band_test.vdb", &vdb, &err) == SWARF_OK,
        "%s: .vdb: %s", what, err.message);
  if (band && vdb) {
    CHECK(same_frame(s, band) && same_frame(vdb, band) && vdb->content == band->content,
          "%s: voxel, origin, band, box", what);
    CHECK(same_values(s, band) && same_values(vdb, band), "%s: every voxel bit for bit", what);
    CHECK(swarf_stock_volume(band) == swarf_stock_volume(s), "%s: the same volume", what);
    CHECK(swarf_stock_check(band, &err) == SWARF_OK, "%s: a valid level set: %s", what,
          err.message);
  }
  swarf_stock_free(band);
  swarf_stock_free(vdb);
}

/// A leaf whose inactive values are not +-background: written in full.
void full_leaf() {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.3f);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  auto acc = grid->getAccessor();
  for (int i = 0; i < 8; i++)
    acc.setValueOn(openvdb::Coord(i, 2, 3), 0.1f - 0.05f * float(i));
  acc.setValueOff(openvdb::Coord(0, 7, 7), 0.0123f);               // neither +bg nor -bg
  acc.setValueOff(openvdb::Coord(16, 0, 0), -0.3f);                // a compact leaf beside it
  grid->tree().addTile(1, openvdb::Coord(-8, 0, 0), -0.3f, false); // an inside tile
  std::unique_ptr<swarf_stock> s(swarf::wrap_grid(grid));
  swarf::write_band_file("band_full.band", *s);
  std::unique_ptr<swarf_stock> r(swarf::read_band_file("band_full.band"));
  CHECK(same_frame(s.get(), r.get()), "full leaf: frame");
  const auto *a = s->grid->constTree().probeConstLeaf(openvdb::Coord(0));
  const auto *b = r->grid->constTree().probeConstLeaf(openvdb::Coord(0));
  CHECK(a && b && std::memcmp(a->buffer().data(), b->buffer().data(), 512 * sizeof(float)) == 0 &&
            a->getValueMask() == b->getValueMask(),
        "full leaf: its 512 values and mask bit for bit");
  CHECK(r->grid->constTree().getValue(openvdb::Coord(-5, 3, 3)) == -0.3f, "the inside tile");
  CHECK(r->grid->constTree().getValue(openvdb::Coord(16, 0, 0)) == -0.3f, "the compact leaf");
  CHECK(same_values(s.get(), r.get()), "full leaf: every voxel");
}

std::string slurp(const char *path) {
  std::string b;
  FILE *f = std::fopen(path, "rb");
  if (!f) return b;
  char buf[65536];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
    b.append(buf, n);
  std::fclose(f);
  return b;
}

/// bytes refused with SWARF_ERR_FORMAT and a message containing `why`.
void refused(const std::string &bytes, const char *why, const char *what) {
  FILE *f = std::fopen("band_bad.band", "wb");
  if (f) std::fwrite(bytes.data(), 1, bytes.size(), f), std::fclose(f);
  swarf_stock *s = nullptr;
  swarf_error err = {};
  const swarf_status st = swarf_stock_read_band("band_bad.band", &s, &err);
  CHECK(st == SWARF_ERR_FORMAT && s == nullptr && std::strstr(err.message, why) != nullptr,
        "%s: refused (%d: %s)", what, int(st), err.message);
  swarf_stock_free(s);
}

/// bytes with the checksum (at 72) made to match their body again.
std::string resealed(std::string b) {
  const uint64_t sum = swarf::file_checksum(b.data() + 80, b.size() - 80);
  std::memcpy(&b[72], &sum, 8);
  return b;
}

void bad_files() {
  const std::string good = slurp("band_test.band");
  CHECK(good.size() > 200, "the band file: %zu bytes", good.size());
  if (good.size() <= 200) return;
  refused("", "too short", "empty");
  refused(good.substr(0, 79), "too short", "a part of the header");
  refused(good.substr(0, good.size() / 2), "band file", "truncated");
  std::string b = good;
  b[0] = 'S';
  refused(b, "not a band file", "another magic");
  b = good, b[good.size() / 2] ^= 0x40;
  refused(b, "checksum", "a damaged byte");
  refused(good + "x", "checksum", "a byte more");
  refused(resealed(good + "x"), "beyond", "a byte more, resealed");
  b = good, std::memset(&b[16], 0xff, 8); // voxel NaN
  refused(b, "voxel", "a voxel that is not a number");
  // the first record after the header: tiles come first, then leaves
  uint64_t tiles, leaves;
  std::memcpy(&tiles, &good[56], 8), std::memcpy(&leaves, &good[64], 8);
  const size_t leaf0 = 80 + 24 * tiles;
  CHECK(tiles > 0 && leaves > 1, "a box has inside tiles (%llu) and leaves (%llu)",
        (unsigned long long)tiles, (unsigned long long)leaves);
  b = good, b[80 + 4] ^= 1; // a tile's x off its lattice
  refused(resealed(b), "unaligned", "a tile off its lattice");
  b = good, b[80] = 7; // a tile of level 7
  refused(resealed(b), "level", "a tile of no level");
  b = good, b[leaf0] ^= 3; // a leaf's x off the 8-lattice
  refused(resealed(b), "unaligned", "a leaf off its lattice");
  b = good, b[leaf0 + 12] = 9; // a leaf of kind 9
  refused(resealed(b), "kind", "a leaf of no kind");
  b = good, leaves++, std::memcpy(&b[64], &leaves, 8); // one leaf more than there is
  refused(resealed(b), "count", "a count too large");
  // the first leaf's record once more at the end
  uint32_t kind;
  std::memcpy(&kind, &good[leaf0 + 12], 4);
  size_t len = 16 + 64 + 2048;
  if (kind == 0) {
    len = 16 + 128;
    for (size_t i = 0; i < 64; i++)
      len += 4 * size_t(__builtin_popcount(unsigned(uint8_t(good[leaf0 + 16 + i]))));
  }
  b = good + good.substr(leaf0, len);
  std::memcpy(&leaves, &good[64], 8), leaves++, std::memcpy(&b[64], &leaves, 8);
  refused(resealed(b), "two leaves", "a leaf twice");
  swarf_stock *s = nullptr;
  swarf_error err = {};
  CHECK(swarf_stock_read_band("band_missing.band", &s, &err) == SWARF_ERR_OPEN && s == nullptr,
        "a missing file: SWARF_ERR_OPEN (%s)", err.message);
  CHECK(swarf_stock_read_band(".", &s, &err) != SWARF_OK && s == nullptr, "a directory: %s",
        err.message);
  CHECK(swarf_stock_read_band("band_test.band", nullptr, &err) == SWARF_ERR_ARG, "out NULL");
  CHECK(swarf_stock_write_band(nullptr, "band_x.band", &err) == SWARF_ERR_ARG, "stock NULL");
}

} // namespace

int main() {
  swarf_stock *s = cut_box();
  if (s) round_trip(s, "a cut box");
  swarf_stock_free(s);
  const double lo[3] = {-1, -1.5, -2}, hi[3] = {2.3, 1.7, 0.4};
  stl_box_write("band_design.stl", lo, hi, 0, STL_GOOD);
  swarf_stock *d = nullptr;
  swarf_error err = {};
  CHECK(swarf_stock_read_design_band("band_design.stl", 0.1, 5, &d, &err) == SWARF_OK, "design: %s",
        err.message);
  if (d) round_trip(d, "a design's band");
  swarf_stock_free(d);
  full_leaf();
  s = cut_box();
  if (s) swarf_stock_write_band(s, "band_test.band", nullptr);
  swarf_stock_free(s);
  bad_files();
  return check_done();
}
