/* SPDX-License-Identifier: MPL-2.0 */
// fuzz_stock.cc -- the fuzz entry of the stock's untrusted readers: STL meshes
// (as stocks and designs), .vdb files read as stocks (placed, resampled),
// placement specifications, and the design cache's own files.
//
// The first byte picks the reader, the rest is the input:
//   0: STL bytes, parsed and checked in memory (mesh_file.h); a mesh that
//      passes and is small is also read as a stock through the file API;
//   1: .vdb bytes, written to a file and read with swarf_stock_read_vdb,
//      placed or resampled as the second byte says;
//   2: a --stock-transform string;
//   3: a design's triangles file (the design cache's .tri, surface_file.h),
//      parsed for a 0.1 mm design; what passes, and the bytes after the
//      header taken as triangles whatever the checksum says, are searched;
//   4: a band file (the design cache's .band, band_file.h), parsed as it is
//      and again with its checksum made to match (so that mutations reach
//      past it); what passes is used as a stock.
// Every accepted stock is used as the simulator would (volume, check, a cut, a
// comparison with itself, a mesh written). A refusal must come with a status
// and a message; anything else (a crash, a sanitizer report, another
// exception) is a bug. libFuzzer entry (stock_fuzz, clang) and plain entry
// (fuzz_stock_smoke) alike.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "band_file.h"
#include "mesh_file.h"
#include "mesh_sdf.h"
#include "stock.h"
#include "stock_error.h"
#include "surface_file.h"

namespace {

std::string temp_name(const char *ext) {
  return std::string("stock_fuzz_") + std::to_string(long(::getpid())) + ext;
}

void write_file(const std::string &path, const uint8_t *data, size_t size) {
  FILE *f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) std::abort();
  if (size && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
}

double ball_sdf(const void *, double x, double y, double z) {
  return std::sqrt(x * x + y * y + z * z) - 0.7;
}

void refused(swarf_status st, const swarf_error &e) {
  if (st == SWARF_OK) return;
  if (e.message[0] == '\0') std::abort(); // a refusal says why
}

/// Use a stock the way the simulator and the comparison do (small ones: a
/// damaged file may hold a valid but huge grid, which only costs time).
void exercise(swarf_stock *s) {
  swarf_error err;
  double lo[3], hi[3], cells = 1.0;
  swarf_stock_bounds(s, lo, hi);
  for (int k = 0; k < 3; k++)
    cells *= (hi[k] - lo[k]) / swarf_stock_voxel(s) + 1.0;
  if (!(cells < 4e6)) return;
  (void)swarf_stock_volume(s);
  (void)swarf_stock_check(s, NULL);
  static const swarf_stock_placement same = {{0, 0, 0}, {0, 0, 0}};
  swarf_stock *design = nullptr;
  refused(swarf_stock_place(s, &same, &design, &err), err);
  if (design == nullptr) return;
  swarf_stock_cut cut = {{-0.7, -0.7, -0.7}, {0.7, 0.7, 0.7}, ball_sdf, nullptr, nullptr, nullptr};
  swarf_stock_deviation dev;
  refused(swarf_stock_compare(s, design, nullptr, 0.0, &dev, &err), err);
  double depth;
  refused(swarf_stock_gouge(s, design, &cut, 0.0, &depth, nullptr, &err), err);
  swarf_stock_cut_effect e;
  refused(swarf_stock_remove_batch_measured(s, &cut, 1, design, 0.0, &e, &err), err);
  refused(swarf_stock_remove_batch_gouges_support(s, &cut, nullptr, 1, design, 0.0, &e, &err), err);
  swarf_stock_free(design);
  const std::string mesh = temp_name(".ply");
  refused(swarf_stock_write_mesh(s, mesh.c_str(), nullptr, nullptr, &err), err);
  ::unlink(mesh.c_str());
}

void fuzz_stl(const uint8_t *data, size_t size) {
  swarf::TriMesh m;
  try {
    swarf::parse_stl(reinterpret_cast<const char *>(data), size, "fuzz.stl", m);
    swarf::check_solid(m, "fuzz.stl");
  } catch (const swarf::Error &e) {
    if (e.what()[0] == '\0') std::abort();
    return;
  }
  if (m.triangles() > 2000) return;
  for (float c : m.xyz)
    if (!(std::fabs(c) < 50.0f)) return; // keep the grids small
  const std::string path = temp_name(".stl");
  write_file(path, data, size);
  swarf_stock *s = nullptr;
  swarf_error err;
  const swarf_status st = swarf_stock_read_stl(path.c_str(), nullptr, 0.5, 3, &s, &err);
  ::unlink(path.c_str());
  refused(st, err);
  if (s) exercise(s), swarf_stock_free(s);
}

void fuzz_vdb(const uint8_t *data, size_t size) {
  if (size < 1) return;
  const uint8_t how = data[0];
  const std::string path = temp_name(".vdb");
  write_file(path, data + 1, size - 1);
  swarf_stock_placement p = {{0, 0, 0}, {0, 0, 0}};
  if (how & 1) p.r[2] = 90;
  if (how & 2) p.r[0] = 30, p.t[2] = 1.5;
  const double voxel = how & 4 ? 0.3 : 0.0;
  swarf_stock *s = nullptr, *t = nullptr;
  swarf_error err;
  swarf_status st = swarf_stock_read_vdb(path.c_str(), nullptr, 0.0, 0, &s, &err);
  ::unlink(path.c_str());
  refused(st, err);
  if (s == nullptr) return;
  double lo[3], hi[3], cells = 1.0;
  swarf_stock_bounds(s, lo, hi);
  for (int k = 0; k < 3; k++)
    cells *= (hi[k] - lo[k]) / swarf_stock_voxel(s) + 1.0;
  if (cells < 4e6 && (how & 7)) { // placed, resampled: what read_vdb does with them
    st = voxel > 0 ? swarf_stock_resample(s, voxel, 3, &t, &err)
                   : swarf_stock_place(s, &p, &t, &err);
    refused(st, err);
    if (t) swarf_stock_free(s), s = t;
  }
  exercise(s);
  swarf_stock_free(s);
}

void fuzz_placement(const uint8_t *data, size_t size) {
  const std::string text(reinterpret_cast<const char *>(data), size);
  swarf_stock_placement p;
  swarf_error err;
  refused(swarf_stock_placement_parse(text.c_str(), &p, &err), err);
}

/// Distances from a few points to a surface: no crash, no hang, whatever its
/// floats (NaN, infinities, huge).
void search(swarf::MeshSurface &m) {
  for (double x : {-1.0, 0.5, 1e6})
    (void)swarf::mesh_surface_distance(m, openvdb::Vec3d(x, 0.25, -x));
}

void fuzz_surface(const uint8_t *data, size_t size) {
  const char *bytes = reinterpret_cast<const char *>(data);
  try {
    search(*swarf::parse_surface_file(bytes, size, 0.1));
  } catch (const swarf::Error &e) {
    if (e.what()[0] == '\0') std::abort(); // a refusal says why
  }
  // the bytes after the header as triangles, whatever the checksum says
  if (size > 40 && size - 40 <= 36 * 4096) {
    const size_t n = (size - 40) / 36;
    search(
        *swarf::mesh_surface_ordered(n, [&](float *dst) { std::memcpy(dst, bytes + 40, 36 * n); }));
  }
}

void fuzz_band(const uint8_t *data, size_t size) {
  std::string b(reinterpret_cast<const char *>(data), size);
  for (int pass = 0; pass < 2; pass++) {
    if (pass == 1) { // resealed: the checksum (bytes 72-79) of the bytes after the header
      if (b.size() < 80) return;
      const uint64_t sum = swarf::file_checksum(b.data() + 80, b.size() - 80);
      std::memcpy(&b[72], &sum, sizeof sum);
    }
    swarf_stock *s = nullptr;
    try {
      s = swarf::parse_band_file(b.data(), b.size());
    } catch (const swarf::Error &e) {
      if (e.what()[0] == '\0') std::abort(); // a refusal says why
      continue;
    }
    exercise(s);
    swarf_stock_free(s);
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 1) return 0;
  switch (data[0] % 5) {
  case 0:
    fuzz_stl(data + 1, size - 1);
    break;
  case 1:
    fuzz_vdb(data + 1, size - 1);
    break;
  case 2:
    fuzz_placement(data + 1, size - 1);
    break;
  case 3:
    fuzz_surface(data + 1, size - 1);
    break;
  default:
    fuzz_band(data + 1, size - 1);
    break;
  }
  return 0;
}
