/// @file render.cc
/// @brief A PNG picture of the stock, ray traced with OpenVDB's LevelSetRayTracer.
///
/// The camera (perspective, 44 degree horizontal field) looks at the centre of
/// the active bounding box from the direction (-1, -1.3, 1.6), world z up,
/// at the distance that frames the whole box. The shader is made for reading
/// machined shapes: a key light from the upper left of the camera with cast
/// shadows (a second ray toward the light, so pocket walls shadow the floors),
/// a weaker fill light, and a tint by height (top faces pale, deep floors
/// blue-grey) so that floors at different depths differ even where they face
/// the light alike. The background is a neutral vertical gradient.
#include <openvdb/tools/RayTracer.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "atomic_file.h"
#include "png.h"
#include "stock_private.h"

namespace swarf {
namespace {

using openvdb::Vec3R;
using openvdb::tools::Film;
using Intersector = openvdb::tools::LevelSetRayIntersector<openvdb::FloatGrid>;

constexpr int kMaxSide = 16384;         ///< pixels
constexpr long kMaxPixels = 1L << 26;   ///< the film holds 16 bytes per pixel

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
  StockShader(const openvdb::FloatGrid &grid, double zlo, double zhi, double offset)
      : mShadow(grid), mZlo(zlo), mZspan(std::max(zhi - zlo, 1e-9)), mOffset(offset) {}
  StockShader(const StockShader &) = default;

  Film::RGBA operator()(const Vec3R &xyz, const Vec3R &nml, const Vec3R &dir) const override {
    const Vec3R n = nml.dot(dir) > 0.0 ? -nml : nml;  // face the viewer
    const double t = std::clamp((xyz.z() - mZlo) / mZspan, 0.0, 1.0);
    const Vec3R deep(0.42, 0.52, 0.68), top(0.86, 0.85, 0.80);
    const Vec3R albedo = deep + (top - deep) * std::pow(t, 1.5);
    double key = std::max(0.0, n.dot(kKey));
    if (key > 0.0 && lit_is_blocked(xyz, n)) key *= 0.25;
    const double fill = std::max(0.0, n.dot(kFill));
    const double light = 0.22 + 0.78 * key + 0.28 * fill;
    const Vec3R c = albedo * light;
    return Film::RGBA(std::min(c.x(), 1.0), std::min(c.y(), 1.0), std::min(c.z(), 1.0));
  }
  openvdb::tools::BaseShader *copy() const override { return new StockShader(*this); }

private:
  /// True if the surface point sees the stock toward the key light.
  bool lit_is_blocked(const Vec3R &xyz, const Vec3R &n) const {
    const openvdb::math::Ray<double> ray(xyz + n * mOffset, kKey, 0.0);
    return mShadow.intersectsWS(ray);
  }

  static const Vec3R kKey, kFill;
  Intersector mShadow;
  double mZlo, mZspan, mOffset;
};

const Vec3R StockShader::kKey = Vec3R(-0.55, -0.75, 1.25).unit();
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
    for (size_t i = 0; i < film.width(); i++) film.pixel(i, j) = Film::RGBA(g, g, g + 0.01f);
  }
}

void trace(const swarf_stock &s, Film &film) {
  Vec3R lo, hi;
  if (!world_box(s, lo, hi)) return;
  const double focal = 50.0, aperture = 41.2136;  // mm of the camera, Houdini's default
  const double tan_x = 0.5 * aperture / focal, tan_y = tan_x * film.height() / film.width();
  const Vec3R back = Vec3R(-1.0, -1.3, 1.6).unit(), centre = 0.5 * (lo + hi);
  const double dist = framing_distance(lo, hi, back, tan_x, tan_y);
  openvdb::tools::PerspectiveCamera camera(film, Vec3R(0.0), centre + back * dist, focal, aperture);
  camera.lookAt(centre, Vec3R(0.0, 0.0, 1.0));
  const StockShader shader(*s.grid, lo.z(), hi.z(), 2.0 * s.voxel);
  openvdb::tools::LevelSetRayTracer<openvdb::FloatGrid> tracer(*s.grid, shader, camera, 1);
  tracer.render(/*threaded=*/true);
}

std::vector<unsigned char> to_rgb8(const Film &film) {
  std::vector<unsigned char> rgb(film.width() * film.height() * 3);
  unsigned char *p = rgb.data();
  for (size_t j = 0; j < film.height(); j++)
    for (size_t i = 0; i < film.width(); i++) {
      const Film::RGBA &c = film.pixel(i, j);
      for (float v : {c.r, c.g, c.b}) *p++ = (unsigned char)std::lround(255.0f * std::clamp(v, 0.0f, 1.0f));
    }
  return rgb;
}

}  // namespace
}  // namespace swarf

extern "C" swarf_status swarf_stock_write_png(const swarf_stock *s, const char *path, int width,
                                              int height, swarf_error *err) {
  return swarf::guard(err, path, [&] {
    if (s == nullptr) throw swarf::Error(SWARF_ERR_ARG, "stock is NULL");
    swarf::check_path(path);
    if (width < 1 || height < 1 || width > swarf::kMaxSide || height > swarf::kMaxSide)
      throw swarf::Error(SWARF_ERR_ARG, "image size must be 1 to 16384 pixels a side");
    if (long(width) * height > swarf::kMaxPixels)
      throw swarf::Error(SWARF_ERR_ARG, "image larger than 2^26 pixels");
    openvdb::tools::Film film{static_cast<size_t>(width), static_cast<size_t>(height)};
    swarf::fill_background(film);
    swarf::trace(*s, film);
    const std::vector<unsigned char> rgb = swarf::to_rgb8(film);
    const std::string png = swarf::png_encode_rgb(rgb.data(), unsigned(width), unsigned(height));
    swarf::write_atomic(path, [&](std::ostream &os) { os.write(png.data(), std::streamsize(png.size())); });
  });
}
