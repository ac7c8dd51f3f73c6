/* SPDX-License-Identifier: MPL-2.0 */
/// @file legend.h
/// @brief Deviation colours (for pictures and meshes) and the legend drawn
/// into a picture, without OpenVDB.
///
/// Colours: green within +-tolerance; outside the design (excess) from
/// yellow at the tolerance to red at +range; inside it (gouge) from cyan at
/// the tolerance to blue at -range; saturated beyond the range.
#ifndef SWARF_STOCK_LEGEND_H
#define SWARF_STOCK_LEGEND_H

namespace swarf {

/// The colour (0..1 each) of a signed deviation (mm); grey for NaN.
void deviation_colour(double dev, double tol, double range, float rgb[3]);

/// Draw the colour scale with its values in mm, and the words EXCESS and
/// GOUGE, at the right edge of an 8-bit RGB picture (rows top to bottom).
/// Pictures smaller than 240 x 160 pixels get none.
void draw_legend(unsigned char *rgb, int width, int height, double tol, double range);

} // namespace swarf

#endif
