/* SPDX-License-Identifier: MPL-2.0 */
/// @file render.cc
/// @brief A PNG picture of the stock, ray traced with OpenVDB's LevelSetRayTracer.
///
/// The iso view's camera (perspective, 44 degree horizontal field) looks at the
/// centre of the active bounding box from the direction (-1, -1.3, 1.6), world
/// z up, at the distance that frames the whole box. The six axis views are
/// orthographic, framing the box's projection with a margin. With a design,
/// the albedo is the colour of the signed deviation (legend.h) at the hit
/// point, sampled trilinearly in the design, and the legend is drawn. The shader is made for
/// reading machined shapes: a key light from the upper left of the camera with cast shadows (a
/// second ray toward the light, so pocket walls shadow the floors), a weaker fill light, and a tint
/// by height (top faces pale, deep floors blue-grey) so that floors at different depths differ even
/// where they face the light alike. The background is a neutral vertical gradient.
#include <openvdb/tools/RayTracer.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "atomic_file.h"
#include "legend.h"
#include "png.h"
#include "stock_private.h"

namespace swarf {
namespace {

using openvdb::Vec3R;
using openvdb::tools::Film;
using Intersector = openvdb::tools::LevelSetRayIntersector<openvdb::FloatGrid>;

constexpr int kMaxSide = 16384;       ///< pixels
constexpr long kMaxPixels = 1L << 26; ///< the film holds 16 bytes per pixel

/// World box (mm) of the active voxel centres (the band holds the surface).
bool world_box(const swarf_stock &s, Vec3R &lo, Vec3R &hi) {
  openvdb::CoordBBox box;
  if (!s.grid->constTree().evalActiveVoxelBoundingBox(box)) return false;
  lo = index_to_world(s, box.min());
  hi = index_to_world(s, box.max());
  return true;
}

/// Diffuse key light with cast shadows, fill light, ambient, height tint.
class StockShader : public openvdb::tools::BaseShader {
public:
  StockShader(const openvdb::FloatGrid &grid, const Vec3R &key, double zlo, double zhi,
              double offset, const openvdb::FloatGrid *design, double tol, double range)
      : mShadow(grid), mKey(key), mZlo(zlo), mZspan(std::max(zhi - zlo, 1e-9)), mOffset(offset),
        mDesign(design), mTol(tol), mRange(range) {}
  StockShader(const StockShader &) = default;

  Film::RGBA operator()(const Vec3R &xyz, const Vec3R &nml, const Vec3R &dir) const override {
    const Vec3R n = nml.dot(dir) > 0.0 ? -nml : nml; // face the viewer
    const Vec3R albedo = mDesign ? deviation_albedo(xyz) : height_albedo(xyz);
    double key = std::max(0.0, n.dot(mKey));
    if (key > 0.0 && lit_is_blocked(xyz, n)) key *= 0.25;
    const double fill = std::max(0.0, n.dot(kFill));
    const double light = 0.22 + 0.78 * key + 0.28 * fill;
    const Vec3R c = albedo * light;
    return Film::RGBA(std::min(c.x(), 1.0), std::min(c.y(), 1.0), std::min(c.z(), 1.0));
  }
  openvdb::tools::BaseShader *copy() const override { return new StockShader(*this); }

private:
  Vec3R height_albedo(const Vec3R &xyz) const {
    const double t = std::clamp((xyz.z() - mZlo) / mZspan, 0.0, 1.0);
    const Vec3R deep(0.42, 0.52, 0.68), top(0.86, 0.85, 0.80);
    return deep + (top - deep) * std::pow(t, 1.5);
  }
  Vec3R deviation_albedo(const Vec3R &xyz) const {
    const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(
        *mDesign);
    float c[3];
    deviation_colour(sampler.wsSample(xyz), mTol, mRange, c);
    return Vec3R(c[0], c[1], c[2]) * 1.15;
  }
  /// True if the surface point sees the stock toward the key light.
  bool lit_is_blocked(const Vec3R &xyz, const Vec3R &n) const {
    const openvdb::math::Ray<double> ray(xyz + n * mOffset, mKey, 0.0);
    return mShadow.intersectsWS(ray);
  }

  static const Vec3R kFill;
  Intersector mShadow;
  Vec3R mKey; ///< toward the key light
  double mZlo, mZspan, mOffset;
  const openvdb::FloatGrid *mDesign; ///< NULL: tint by height
  double mTol, mRange;
};

/// The iso view's key light: from the upper left of its camera.
const Vec3R kIsoKey = Vec3R(-0.55, -0.75, 1.25).unit();
const Vec3R StockShader::kFill = Vec3R(0.9, -0.35, 0.45).unit();

/// Camera distance (mm) from the box centre along `back` that fits the box in
/// a field of half-widths tan_x, tan_y (with a margin).
double framing_distance(const Vec3R &lo, const Vec3R &hi, const Vec3R &back, double tan_x,
                        double tan_y) {
  const Vec3R c = 0.5 * (lo + hi), up(0.0, 0.0, 1.0);
  const Vec3R right = up.cross(back).unit(), cam_up = back.cross(right);
  double d = 0.0;
  for (int i = 0; i < 8; i++) {
    const Vec3R p(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
    const Vec3R r = p - c;
    d = std::max(d, r.dot(back) + std::fabs(r.dot(right)) / (0.9 * tan_x));
    d = std::max(d, r.dot(back) + std::fabs(r.dot(cam_up)) / (0.9 * tan_y));
  }
  return d;
}

void fill_background(Film &film) {
  for (size_t j = 0; j < film.height(); j++) {
    const float t = float(j) / float(std::max<size_t>(film.height() - 1, 1));
    const float g = 0.93f - 0.18f * t;
    for (size_t i = 0; i < film.width(); i++)
      film.pixel(i, j) = Film::RGBA(g, g, g + 0.01f);
  }
}

/// Direction from the scene to an axis view's camera, and the camera's up.
void axis_view(swarf_stock_view v, Vec3R &back, Vec3R &up) {
  up = Vec3R(0.0, 0.0, 1.0);
  switch (v) {
  case SWARF_VIEW_TOP:
    back = Vec3R(0, 0, 1), up = Vec3R(0, 1, 0);
    break;
  case SWARF_VIEW_BOTTOM:
    back = Vec3R(0, 0, -1), up = Vec3R(0, 1, 0);
    break;
  case SWARF_VIEW_FRONT:
    back = Vec3R(0, -1, 0);
    break;
  case SWARF_VIEW_BACK:
    back = Vec3R(0, 1, 0);
    break;
  case SWARF_VIEW_LEFT:
    back = Vec3R(-1, 0, 0);
    break;
  default:
    back = Vec3R(1, 0, 0);
    break; // right
  }
}

/// What a picture shows and how.
struct Picture {
  swarf_stock_view view;
  const swarf_stock *design;
  double tol, range;
};

void trace(const swarf_stock &s, Film &film, const Picture &pic) {
  Vec3R lo, hi;
  if (!world_box(s, lo, hi)) return;
  const Vec3R centre = 0.5 * (lo + hi);
  std::unique_ptr<openvdb::tools::BaseCamera> camera;
  Vec3R key = kIsoKey;
  if (pic.view == SWARF_VIEW_ISO) {
    const double focal = 50.0, aperture = 41.2136; // mm of the camera, Houdini's default
    const double tan_x = 0.5 * aperture / focal, tan_y = tan_x * film.height() / film.width();
    const Vec3R back = Vec3R(-1.0, -1.3, 1.6).unit();
    const double dist = framing_distance(lo, hi, back, tan_x, tan_y);
    camera.reset(new openvdb::tools::PerspectiveCamera(film, Vec3R(0.0), centre + back * dist,
                                                       focal, aperture));
    camera->lookAt(centre, Vec3R(0.0, 0.0, 1.0));
  } else {
    Vec3R back, up;
    axis_view(pic.view, back, up);
    const Vec3R right = up.cross(back), ext = hi - lo;
    key = (back + 0.45 * up - 0.35 * right).unit(); // over the viewer's left shoulder
    const double wide = std::fabs(ext.dot(right)), tall = std::fabs(ext.dot(up));
    const double frame =
        1.08 * std::max({wide, tall * film.width() / double(film.height()), 4.0 * s.voxel});
    const double dist = ext.length() + 10.0 * s.voxel;
    camera.reset(
        new openvdb::tools::OrthographicCamera(film, Vec3R(0.0), centre + back * dist, frame));
    camera->lookAt(centre, up);
  }
  const StockShader shader(*s.grid, key, lo.z(), hi.z(), 2.0 * s.voxel,
                           pic.design ? pic.design->grid.get() : nullptr, pic.tol, pic.range);
  openvdb::tools::LevelSetRayTracer<openvdb::FloatGrid> tracer(*s.grid, shader, *camera, 1);
  tracer.render(/*threaded=*/true);
}

std::vector<unsigned char> to_rgb8(const Film &film) {
  std::vector<unsigned char> rgb(film.width() * film.height() * 3);
  unsigned char *p = rgb.data();
  for (size_t j = 0; j < film.height(); j++)
    for (size_t i = 0; i < film.width(); i++) {
      const Film::RGBA &c = film.pixel(i, j);
      for (float v : {c.r, c.g, c.b})
        *p++ = (unsigned char)std::lround(255.0f * std::clamp(v, 0.0f, 1.0f));
    }
  return rgb;
}

} // namespace
} // namespace swarf

namespace swarf {
namespace {

void write_picture(const swarf_stock &s, const char *path, int width, int height,
                   const Picture &pic) {
  check_path(path);
  if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide)
    throw Error(SWARF_ERR_ARG, "image size must be 1 to 16384 pixels a side");
  if (long(width) * height > kMaxPixels)
    throw Error(SWARF_ERR_ARG, "image larger than 2^26 pixels");
  Film film{static_cast<size_t>(width), static_cast<size_t>(height)};
  fill_background(film);
  trace(s, film, pic);
  std::vector<unsigned char> rgb = to_rgb8(film);
  if (pic.design) draw_legend(rgb.data(), width, height, pic.tol, pic.range);
  const std::string png = png_encode_rgb(rgb.data(), unsigned(width), unsigned(height));
  write_atomic(path, [&](std::ostream &os) { os.write(png.data(), std::streamsize(png.size())); });
}

} // namespace

/// Tolerance and colour range of an output's options, defaults filled (stock.h).
void output_scale(const swarf_stock &s, const swarf_stock_output &o, double &tol, double &range) {
  if (!std::isfinite(o.tolerance) || !std::isfinite(o.range))
    throw Error(SWARF_ERR_ARG, "tolerance and range must be finite");
  tol = o.tolerance > 0.0 ? o.tolerance : 0.5 * s.voxel;
  range = o.range > 0.0 ? o.range : 4.0 * tol;
  if (!(range > tol)) throw Error(SWARF_ERR_ARG, "the colour range must exceed the tolerance");
}

} // namespace swarf

extern "C" swarf_status swarf_stock_write_png(const swarf_stock *s, const char *path, int width,
                                              int height, swarf_error *err) {
  return swarf::guard(err, path, [&] {
    if (s == nullptr) throw swarf::Error(SWARF_ERR_ARG, "stock is NULL");
    swarf::write_picture(*s, path, width, height,
                         swarf::Picture{SWARF_VIEW_ISO, nullptr, 0.0, 0.0});
  });
}

extern "C" swarf_status swarf_stock_write_image(const swarf_stock *s, const char *path,
                                                const swarf_stock_output *opt, swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr) throw swarf::Error(SWARF_ERR_ARG, "stock is NULL");
    const swarf_stock_output o = opt ? *opt : swarf_stock_output{};
    if (unsigned(o.view) > SWARF_VIEW_BOTTOM) throw swarf::Error(SWARF_ERR_ARG, "unknown view");
    swarf::Picture pic{o.view, o.design, 0.0, 0.0};
    swarf::output_scale(*s, o, pic.tol, pic.range);
    swarf::write_picture(*s, path, o.width > 0 ? o.width : 1024, o.height > 0 ? o.height : 768,
                         pic);
  });
}

extern "C" swarf_status swarf_stock_view_parse(const char *name, swarf_stock_view *out,
                                               swarf_error *err) {
  static const char *names[] = {"iso", "top", "front", "back", "left", "right", "bottom"};
  swarf_error_init(err);
  for (int i = 0; name != nullptr && out != nullptr && i < 7; i++)
    if (std::strcmp(name, names[i]) == 0) return *out = swarf_stock_view(i), SWARF_OK;
  return swarf_error_set(err, SWARF_ERR_ARG,
                         "unknown view \"%s\"; give iso, top, front, back, left, right or bottom",
                         name ? name : "");
}
