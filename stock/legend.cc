/* SPDX-License-Identifier: MPL-2.0 */
/// @file legend.cc
/// @brief Deviation colours and the picture's legend (legend.h), with a
/// built-in 5 x 7 pixel font for the few characters the legend writes.
#include "legend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace swarf {
namespace {

/// A glyph: 7 rows of 5 bits, the leftmost pixel in bit 4.
struct Glyph {
  char c;
  unsigned char rows[7];
};

const Glyph kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
    {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
    {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
    {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
    {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
    {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'.', {0, 0, 0, 0, 0, 0x0C, 0x0C}},
    {'-', {0, 0, 0, 0x1F, 0, 0, 0}},
    {'+', {0, 0x04, 0x04, 0x1F, 0x04, 0x04, 0}},
    {' ', {0, 0, 0, 0, 0, 0, 0}},
    {'A', {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}},
    {'D', {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}},
    {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}},
    {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}},
    {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}},
    {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}},
    {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
    {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
    {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}},
    {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
    {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
};

const unsigned char *glyph(char c) {
  for (const Glyph &g : kFont)
    if (g.c == c) return g.rows;
  return kFont[13].rows; // unknown: blank
}

/// A picture to draw in.
struct Canvas {
  unsigned char *rgb;
  int w, h;
  void put(int x, int y, const float c[3]) {
    if (x < 0 || y < 0 || x >= w || y >= h) return;
    unsigned char *p = rgb + 3 * (size_t(y) * w + x);
    for (int k = 0; k < 3; k++)
      p[k] = (unsigned char)std::lround(255.0f * std::clamp(c[k], 0.0f, 1.0f));
  }
  void rect(int x0, int y0, int x1, int y1, const float c[3]) {
    for (int y = y0; y < y1; y++)
      for (int x = x0; x < x1; x++)
        put(x, y, c);
  }
  /// Text with its top left at (x, y), each font pixel `scale` pixels.
  void text(int x, int y, const char *s, int scale, const float c[3]) {
    for (; *s; s++, x += 6 * scale) {
      const unsigned char *rows = glyph(*s);
      for (int r = 0; r < 7; r++)
        for (int b = 0; b < 5; b++)
          if (rows[r] & (0x10 >> b))
            rect(x + b * scale, y + r * scale, x + (b + 1) * scale, y + (r + 1) * scale, c);
    }
  }
};

void mix(const float a[3], const float b[3], double t, float out[3]) {
  for (int k = 0; k < 3; k++)
    out[k] = float(a[k] + (b[k] - a[k]) * t);
}

} // namespace

void deviation_colour(double dev, double tol, double range, float rgb[3]) {
  static const float grey[3] = {0.6f, 0.6f, 0.6f}, green[3] = {0.30f, 0.72f, 0.35f};
  static const float yellow[3] = {0.98f, 0.85f, 0.25f}, red[3] = {0.80f, 0.10f, 0.10f};
  static const float cyan[3] = {0.35f, 0.75f, 0.95f}, blue[3] = {0.12f, 0.20f, 0.75f};
  if (std::isnan(dev)) return std::memcpy(rgb, grey, sizeof grey), void();
  const double a = std::fabs(dev);
  if (a <= tol) return std::memcpy(rgb, green, sizeof green), void();
  const double t = range > tol ? std::clamp((a - tol) / (range - tol), 0.0, 1.0) : 1.0;
  if (dev > 0)
    mix(yellow, red, t, rgb);
  else
    mix(cyan, blue, t, rgb);
}

void draw_legend(unsigned char *rgb, int width, int height, double tol, double range) {
  if (width < 240 || height < 160) return;
  Canvas cv{rgb, width, height};
  const int scale = height >= 600 ? 2 : 1, ch = 7 * scale, cw = 6 * scale;
  const int bar_w = 10 * scale, top = height / 6, bottom = height - height / 6;
  const int label_w = 7 * cw, x0 = width - (bar_w + label_w + 4 * scale + 8 * scale);
  static const float ink[3] = {0.1f, 0.1f, 0.12f}, paper[3] = {0.97f, 0.97f, 0.97f};
  cv.rect(x0 - 4 * scale, top - 3 * ch, width - 2 * scale, bottom + 3 * ch, paper);
  cv.text(x0, top - 2 * ch - ch / 2, "EXCESS", scale, ink);
  cv.text(x0, bottom + ch, "GOUGE", scale, ink);
  for (int y = top; y <= bottom; y++) { // +range at the top, -range at the bottom
    const double dev = range * (1.0 - 2.0 * (y - top) / double(bottom - top));
    float c[3];
    deviation_colour(dev, tol, range, c);
    cv.rect(x0, y, x0 + bar_w, y + 1, c);
  }
  const double marks[5] = {range, tol, 0.0, -tol, -range};
  for (double m : marks) {
    const int y = top + int(std::lround((1.0 - m / range) * 0.5 * (bottom - top)));
    char buf[32];
    if (m == 0.0)
      std::snprintf(buf, sizeof buf, "0 MM");
    else
      std::snprintf(buf, sizeof buf, "%+.*f", std::fabs(m) < 0.1 ? 3 : 2, m);
    cv.rect(x0 + bar_w, y, x0 + bar_w + 3 * scale, y + scale, ink);
    cv.text(x0 + bar_w + 5 * scale, y - ch / 2, buf, scale, ink);
  }
}

} // namespace swarf
