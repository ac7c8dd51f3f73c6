/* SPDX-License-Identifier: MPL-2.0 */
/// @file mesh_tri.h
/// @brief A triangle's exact squared distance, shared by the band of a mesh
/// (mesh_sdf.cc) and the queries on its triangles beyond the band
/// (mesh_surface.cc). Index space; internal to stock/.
#ifndef SWARF_STOCK_MESH_TRI_H
#define SWARF_STOCK_MESH_TRI_H

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>

namespace swarf {
namespace mesh {

using openvdb::Vec3d;

/// A triangle in index space with what the distance needs.
struct Tri {
  Vec3d a, b, c;
  Vec3d n; ///< unit normal (zero when degenerate)
  double lo[3], hi[3];
};

/// Squared distance from p to the segment [a, b].
inline double seg_dist2(const Vec3d &p, const Vec3d &a, const Vec3d &b) {
  const Vec3d ab = b - a;
  const double l2 = ab.lengthSqr();
  double t = l2 > 0.0 ? (p - a).dot(ab) / l2 : 0.0;
  t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
  return (p - (a + ab * t)).lengthSqr();
}

/// Squared distance from p to the triangle (closest point by Voronoi regions,
/// Ericson, Real-Time Collision Detection 5.1.5; segments when degenerate).
inline double tri_dist2(const Tri &t, const Vec3d &p) {
  if (t.n.lengthSqr() == 0.0)
    return std::min(seg_dist2(p, t.a, t.b),
                    std::min(seg_dist2(p, t.b, t.c), seg_dist2(p, t.c, t.a)));
  const Vec3d ab = t.b - t.a, ac = t.c - t.a, ap = p - t.a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return ap.lengthSqr();
  const Vec3d bp = p - t.b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return bp.lengthSqr();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return (ap - ab * (d1 / (d1 - d3))).lengthSqr();
  const Vec3d cp = p - t.c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return cp.lengthSqr();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return (ap - ac * (d2 / (d2 - d6))).lengthSqr();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return (bp - (t.c - t.b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))).lengthSqr();
  const double pd = ap.dot(t.n); // inside the face: the plane's distance
  return pd * pd;
}

/// Squared distance from p to the box [lo, hi].
inline double box_dist2(const double lo[3], const double hi[3], const Vec3d &p) {
  double d2 = 0.0;
  for (int a = 0; a < 3; a++) {
    const double e = p[a] < lo[a] ? lo[a] - p[a] : p[a] > hi[a] ? p[a] - hi[a] : 0.0;
    d2 += e * e;
  }
  return d2;
}

/// The triangle (A, B, C) with what the distance needs.
inline void make_tri(const openvdb::Vec3s &A, const openvdb::Vec3s &B, const openvdb::Vec3s &C,
                     Tri &t) {
  t.a = Vec3d(A), t.b = Vec3d(B), t.c = Vec3d(C);
  const Vec3d n = (t.b - t.a).cross(t.c - t.a);
  const double len = n.length();
  t.n = len > 0.0 && std::isfinite(len) ? n / len : Vec3d(0.0);
  for (int a = 0; a < 3; a++) {
    t.lo[a] = std::min(t.a[a], std::min(t.b[a], t.c[a]));
    t.hi[a] = std::max(t.a[a], std::max(t.b[a], t.c[a]));
  }
}

} // namespace mesh
} // namespace swarf

#endif
