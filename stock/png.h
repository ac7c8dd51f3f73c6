/* SPDX-License-Identifier: MPL-2.0 */
/// @file png.h
/// @brief A minimal PNG encoder (8-bit RGB, no interlace, filter 0 on every
/// row, one zlib IDAT chunk): enough for the stock's pictures.
#ifndef SWARF_STOCK_PNG_H
#define SWARF_STOCK_PNG_H

#include <string>

namespace swarf {

/// The bytes of a PNG file holding `width` x `height` pixels (pixels) given as
/// rows from top to bottom, 3 bytes (R, G, B) per pixel. Throws
/// Error(SWARF_ERR_ARG) for an empty or oversized image, std::bad_alloc
/// when memory runs out.
std::string png_encode_rgb(const unsigned char *rgb, unsigned width, unsigned height);

} // namespace swarf

#endif
