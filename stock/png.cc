/* SPDX-License-Identifier: MPL-2.0 */
/// @file png.cc
/// @brief A minimal PNG encoder (see png.h): signature, IHDR, IDAT (zlib), IEND,
/// each chunk with its CRC-32 (zlib's crc32).
#include "png.h"

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <new>
#include <vector>

#include "stock_error.h"

namespace swarf {
namespace {

void put_u32_be(std::string &out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8)
    out.push_back(char((v >> shift) & 0xff));
}

void put_chunk(std::string &out, const char type[4], const unsigned char *data, size_t len) {
  put_u32_be(out, uint32_t(len));
  const size_t start = out.size();
  out.append(type, 4);
  if (len > 0) out.append(reinterpret_cast<const char *>(data), len);
  uLong crc = crc32(0L, Z_NULL, 0);
  crc = crc32(crc, reinterpret_cast<const Bytef *>(out.data() + start), uInt(len + 4));
  put_u32_be(out, uint32_t(crc));
}

/// The zlib stream of the rows, each preceded by its filter byte (0: none).
std::vector<unsigned char> deflate_rows(const unsigned char *rgb, unsigned width, unsigned height) {
  const size_t row = size_t(width) * 3;
  std::vector<unsigned char> raw((row + 1) * height);
  for (unsigned y = 0; y < height; y++) {
    raw[y * (row + 1)] = 0;
    std::copy(rgb + y * row, rgb + (y + 1) * row, raw.begin() + y * (row + 1) + 1);
  }
  uLongf len = compressBound(uLong(raw.size()));
  std::vector<unsigned char> z(len);
  const int rc = compress2(z.data(), &len, raw.data(), uLong(raw.size()), 6);
  if (rc == Z_MEM_ERROR) throw std::bad_alloc();
  if (rc != Z_OK) throw Error(SWARF_ERR_INTERNAL, "zlib compress2 failed");
  z.resize(len);
  return z;
}

} // namespace

std::string png_encode_rgb(const unsigned char *rgb, unsigned width, unsigned height) {
  if (rgb == nullptr || width == 0 || height == 0 || uint64_t(width) * height > (1u << 28))
    throw Error(SWARF_ERR_ARG, "PNG: empty or oversized image");
  static const char signature[] = "\x89PNG\r\n\x1a\n";
  std::string out(signature, 8);
  unsigned char ihdr[13];
  for (int i = 0; i < 4; i++) {
    ihdr[i] = (unsigned char)(width >> (24 - 8 * i));
    ihdr[4 + i] = (unsigned char)(height >> (24 - 8 * i));
  }
  ihdr[8] = 8;  // bits per sample
  ihdr[9] = 2;  // colour type: RGB
  ihdr[10] = 0; // compression: deflate
  ihdr[11] = 0; // filter method 0
  ihdr[12] = 0; // no interlace
  put_chunk(out, "IHDR", ihdr, sizeof ihdr);
  const std::vector<unsigned char> z = deflate_rows(rgb, width, height);
  put_chunk(out, "IDAT", z.data(), z.size());
  put_chunk(out, "IEND", nullptr, 0);
  return out;
}

} // namespace swarf
