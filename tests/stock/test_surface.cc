/* SPDX-License-Identifier: MPL-2.0 */
/* test_surface.cc -- a mesh's exact surface distance (mesh_sdf.h's
 * mesh_surface_distance, the designs' depths beyond their band) against
 * brute force over all its triangles.
 *
 * An internal of stock/ (not the C API): the tree over the triangles prunes
 * by bounding boxes, and a box wrongly passed over gives a distance that is
 * too large by up to the mesh's size, anywhere. Meshes: a bumpy sphere (a
 * closed surface of 20 k triangles, as a design's) and a soup of random
 * triangles, large and small, some degenerate; points near the surface,
 * inside, far outside and on it. Each query must match the closest point on
 * every triangle (openvdb::math::closestPointOnTriangleToPoint) to 1e-9.
 *
 *   test_stock_surface                       the checks
 *   test_stock_surface FILE.stl VOXEL [N]    queries/s on a mesh (index
 *                                            space at VOXEL mm): N points
 *                                            near its surface, N anywhere
 */
#include <openvdb/math/Math.h>
#include <openvdb/math/Proximity.h>
#include <openvdb/openvdb.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <vector>

#include "check.h"
#include "mesh_file.h"
#include "mesh_sdf.h"

using openvdb::Vec3d;
using openvdb::Vec3I;
using openvdb::Vec3s;

namespace {

struct Mesh {
  std::vector<Vec3s> pts;
  std::vector<Vec3I> tris;
};

/// A sphere of radius r (a latitude-longitude grid) with bumps of height h.
Mesh bumpy_sphere(double r, double h, int n) {
  Mesh m;
  for (int i = 0; i <= n; i++)
    for (int j = 0; j < 2 * n; j++) {
      const double th = M_PI * i / n, ph = M_PI * j / n;
      const double rr = r + h * std::sin(5 * th) * std::cos(7 * ph);
      m.pts.emplace_back(float(rr * std::sin(th) * std::cos(ph)),
                         float(rr * std::sin(th) * std::sin(ph)), float(rr * std::cos(th)));
    }
  auto at = [n](int i, int j) { return uint32_t(i * 2 * n + (j % (2 * n))); };
  for (int i = 0; i < n; i++)
    for (int j = 0; j < 2 * n; j++) {
      m.tris.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.tris.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return m;
}

/// Random triangles in a cube of side 100: most small, some large, some
/// with two equal corners or three in a line.
Mesh soup(std::mt19937_64 &rng, int count) {
  std::uniform_real_distribution<double> u(-50.0, 50.0), s(-1.0, 1.0);
  Mesh m;
  for (int k = 0; k < count; k++) {
    const Vec3d a(u(rng), u(rng), u(rng));
    const double size = k % 50 == 0 ? 40.0 : 2.0;
    Vec3d b = a + size * Vec3d(s(rng), s(rng), s(rng)),
          c = a + size * Vec3d(s(rng), s(rng), s(rng));
    if (k % 97 == 0) c = b;                 // two corners the same
    if (k % 89 == 0) c = a + 2.0 * (b - a); // a line
    const uint32_t o = uint32_t(m.pts.size());
    for (const Vec3d &p : {a, b, c})
      m.pts.emplace_back(float(p[0]), float(p[1]), float(p[2]));
    m.tris.emplace_back(o, o + 1, o + 2);
  }
  return m;
}

/// The distance by brute force: every triangle's closest point.
double brute(const Mesh &m, const Vec3d &p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3I &t : m.tris) {
    const Vec3d a(m.pts[t[0]]), b(m.pts[t[1]]), c(m.pts[t[2]]);
    Vec3d uvw;
    const Vec3d q = openvdb::math::closestPointOnTriangleToPoint(a, b, c, p, uvw);
    best = std::min(best, (q - p).length());
  }
  return best;
}

/// Points near the mesh's corners (within `spread`) and anywhere in its box
/// grown by `far`.
std::vector<Vec3d> points(const Mesh &m, std::mt19937_64 &rng, size_t n, double spread,
                          double far) {
  Vec3d lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (const Vec3s &p : m.pts)
    lo = openvdb::math::minComponent(lo, Vec3d(p)), hi = openvdb::math::maxComponent(hi, Vec3d(p));
  std::uniform_real_distribution<double> s(-1.0, 1.0), u(0.0, 1.0);
  std::uniform_int_distribution<size_t> pick(0, m.pts.size() - 1);
  std::vector<Vec3d> out;
  for (size_t k = 0; k < n; k++) {
    if (k % 2 == 0) {
      out.push_back(Vec3d(m.pts[pick(rng)]) + spread * Vec3d(s(rng), s(rng), s(rng)));
    } else {
      Vec3d p;
      for (int a = 0; a < 3; a++)
        p[a] = lo[a] - far + (hi[a] - lo[a] + 2.0 * far) * u(rng);
      out.push_back(p);
    }
  }
  for (size_t k = 0; k < 20; k++) // on the surface: a corner itself
    out.push_back(Vec3d(m.pts[pick(rng)]));
  return out;
}

void check_mesh(const char *what, const Mesh &m, std::mt19937_64 &rng, double spread) {
  std::shared_ptr<swarf::MeshSurface> s = swarf::mesh_surface(m.pts, m.tris);
  int bad = 0;
  for (const Vec3d &p : points(m, rng, 2000, spread, 30.0)) {
    const double want = brute(m, p), got = swarf::mesh_surface_distance(*s, p);
    if (!(std::fabs(got - want) <= 1e-9 * std::max(1.0, want)) && bad++ < 5)
      std::fprintf(stderr, "%s: at (%g, %g, %g): %.12g, brute force %.12g\n", what, p[0], p[1],
                   p[2], got, want);
  }
  CHECK(bad == 0, "%s: %d of 2020 distances differ from brute force", what, bad);
}

/// Queries per second on an STL at `voxel` mm: n near its surface (within
/// 3 voxels of a corner), n anywhere in its box.
int bench(const char *path, double voxel, size_t n) {
  swarf::TriMesh t;
  swarf::read_stl_file(path, t);
  Mesh m;
  for (size_t i = 0; i < t.vertices(); i++)
    m.pts.emplace_back(float(t.xyz[3 * i] / voxel), float(t.xyz[3 * i + 1] / voxel),
                       float(t.xyz[3 * i + 2] / voxel));
  for (size_t k = 0; k < t.triangles(); k++)
    m.tris.emplace_back(t.tri[3 * k], t.tri[3 * k + 1], t.tri[3 * k + 2]);
  std::shared_ptr<swarf::MeshSurface> s = swarf::mesh_surface(m.pts, m.tris);
  std::mt19937_64 rng(7);
  const std::vector<Vec3d> p = points(m, rng, 2 * n, 3.0, 0.0);
  swarf::mesh_surface_distance(*s, p[0]); // the ordering, not timed
  double near_s = 0.0, any_s = 0.0, sum = 0.0;
  for (int pass = 0; pass < 2; pass++) {
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t k = size_t(pass); k < 2 * n; k += 2)
      sum += swarf::mesh_surface_distance(*s, p[k]);
    (pass == 0 ? near_s : any_s) =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  std::printf("%s: %zu triangles, %zu queries each: near the surface %.0f/s, anywhere %.0f/s "
              "(sum %.6g)\n",
              path, m.tris.size(), n, double(n) / near_s, double(n) / any_s, sum);
  return 0;
}

} // namespace

int main(int argc, char **argv) {
  if (argc >= 3)
    return bench(argv[1], std::atof(argv[2]), argc > 3 ? size_t(std::atol(argv[3])) : 20000);
  std::mt19937_64 rng(11);
  check_mesh("bumpy sphere", bumpy_sphere(20.0, 1.5, 100), rng, 3.0);
  check_mesh("soup", soup(rng, 3000), rng, 2.0);
  check_mesh("one triangle", soup(rng, 1), rng, 2.0);
  return check_done();
}
