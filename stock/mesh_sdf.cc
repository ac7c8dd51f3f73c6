/* SPDX-License-Identifier: MPL-2.0 */
/// @file mesh_sdf.cc
/// @brief mesh_band (mesh_sdf.h): a closed mesh's exact signed distance in a
/// narrow band, block by block.
///
///  1. Signs. Every voxel column (i, j) is a ray along +z; each triangle whose
///     projection covers (i, j) crosses it at one height, with +1 if it faces
///     up, -1 if down (top-left rule on the projected edges, with exact
///     orientation tests: a column through a shared edge or vertex meets it
///     once, a silhouette edge both ways). A voxel is inside iff the
///     crossings above it sum to +1 (the winding number of a closed outward
///     mesh), which holds for any mesh check_solid accepts.
///  2. Distances. Each triangle is paired with the 8^3 blocks within
///     half_width voxels of it (a block's voxels lie within 3.5 sqrt 3 of its
///     centre); per block (in parallel), each of its triangles visits the
///     voxels of its bounding box grown by half_width, skipping those whose
///     distance to its plane already exceeds the best found: every voxel
///     closer than half_width to the surface gets its exact distance (its
///     closest triangle is among its block's).
///  3. The blocks with band become leaves; each tile of the rest of the grid
///     takes the sign of the winding number at one of its voxels (sign_tiles).
/// Cost: about (bounding box + 2 half_width)^3 cheap plane tests a small
/// triangle, no neighbour propagation and no renormalisation.
#include "mesh_sdf.h"

#include <openvdb/tools/SignedFloodFill.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "mesh_tri.h"
#include "stock_private.h"

namespace swarf {
namespace {

using openvdb::Coord;
using openvdb::Vec3d;
using Leaf = openvdb::FloatTree::LeafNodeType;
using mesh::box_dist2;
using mesh::make_tri;
using mesh::Tri;
using mesh::tri_dist2;

constexpr double kBlockRadius = 3.5 * 1.7320508075688772; ///< block centre to its farthest voxel
constexpr double kMaxBlockTests = 2e8;                    ///< blocks in all grown bounding boxes

/// One crossing of a voxel column by the surface.
struct Crossing {
  int32_t i, j;
  float z;
  int32_t s; ///< +1 the triangle faces up, -1 down
};

inline bool column_less(const Crossing &a, const Crossing &b) {
  return a.i != b.i ? a.i < b.i : a.j < b.j;
}

/// Edge function of (u -> v) at the integer point (x, y): > 0 left of it.
/// Differences of floats are exact in double, and so is each product; the
/// sign of their rounded difference is the exact sign.
inline double edge(double ux, double uy, double vx, double vy, double x, double y) {
  return (vx - ux) * (y - uy) - (vy - uy) * (x - ux);
}

/// Top-left rule: of the two directions of an edge exactly one owns the
/// points on it.
inline bool owns(double ux, double uy, double vx, double vy) {
  return vy < uy || (vy == uy && vx < ux);
}

/// The crossings of the columns under triangle t (its corners as floats).
void column_crossings(const openvdb::Vec3s &A, const openvdb::Vec3s &B, const openvdb::Vec3s &C,
                      std::vector<Crossing> &out) {
  double ax = A[0], ay = A[1], bx = B[0], by = B[1], cx = C[0], cy = C[1];
  const double area = edge(ax, ay, bx, by, cx, cy);
  if (area == 0.0) return; // seen edge-on: its neighbours carry the crossings
  double az = A[2], bz = B[2], cz = C[2];
  const int32_t s = area > 0.0 ? 1 : -1;
  if (area < 0.0) std::swap(bx, cx), std::swap(by, cy), std::swap(bz, cz); // counter-clockwise
  const double x0 = std::ceil(std::min(ax, std::min(bx, cx))),
               x1 = std::floor(std::max(ax, std::max(bx, cx)));
  const double y0 = std::ceil(std::min(ay, std::min(by, cy))),
               y1 = std::floor(std::max(ay, std::max(by, cy)));
  const bool oa = owns(bx, by, cx, cy), ob = owns(cx, cy, ax, ay), oc = owns(ax, ay, bx, by);
  for (double x = x0; x <= x1; x++)
    for (double y = y0; y <= y1; y++) {
      const double wa = edge(bx, by, cx, cy, x, y), wb = edge(cx, cy, ax, ay, x, y),
                   wc = edge(ax, ay, bx, by, x, y);
      if (wa < 0.0 || wb < 0.0 || wc < 0.0) continue;
      if ((wa == 0.0 && !oa) || (wb == 0.0 && !ob) || (wc == 0.0 && !oc)) continue;
      const double z = (wa * az + wb * bz + wc * cz) / (wa + wb + wc);
      out.push_back({int32_t(x), int32_t(y), float(z), s});
    }
}

/// floor and ceil of a double within the int range (index coordinates are
/// below 2^29), without the library call (generic x86-64 has no rounding
/// instruction; these are most of the band's inner loop otherwise).
inline int ifloor(double v) {
  const int i = int(v);
  return i - (v < double(i));
}

inline int iceil(double v) {
  const int i = int(v);
  return i + (v > double(i));
}

/// A (block, triangle) pair; blocks by their origin's leaf coordinates.
struct Pair {
  int32_t x, y, z;
  uint32_t tri;
};

inline bool pair_less(const Pair &a, const Pair &b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  if (a.z != b.z) return a.z < b.z;
  return a.tri < b.tri;
}

inline int32_t leaf_of(double v) {
  return ifloor(v / 8.0); // within the int range: check_mesh_size
}

/// Pairs of triangle t (number k) with the blocks within w voxels of it.
void block_pairs(const Tri &t, uint32_t k, double w, std::vector<Pair> &out) {
  int32_t lo[3], hi[3];
  for (int a = 0; a < 3; a++)
    lo[a] = leaf_of(t.lo[a] - w), hi[a] = leaf_of(t.hi[a] + w);
  const bool few = (int64_t(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1)) <= 8;
  const double reach = (kBlockRadius + w) * (kBlockRadius + w);
  for (int32_t x = lo[0]; x <= hi[0]; x++)
    for (int32_t y = lo[1]; y <= hi[1]; y++)
      for (int32_t z = lo[2]; z <= hi[2]; z++)
        if (few || tri_dist2(t, Vec3d(8.0 * x + 3.5, 8.0 * y + 3.5, 8.0 * z + 3.5)) <= reach)
          out.push_back({x, y, z, k});
}

/// The voxel range (block-local, inclusive) of t's bounding box grown by g.
inline bool local_range(const Tri &t, const Coord &o, double g, int lo[3], int hi[3]) {
  for (int a = 0; a < 3; a++) {
    lo[a] = std::max(0, iceil(t.lo[a] - g) - o[a]);
    hi[a] = std::min(7, ifloor(t.hi[a] + g) - o[a]);
    if (lo[a] > hi[a]) return false;
  }
  return true;
}

/// One pass of a triangle over the block's voxels within g of its bounding
/// box (block-local range lo..hi): each voxel whose row bit is set in `rows`
/// and which the pass may improve gets the triangle's squared distance when it
/// is below the best so far. A voxel is passed over when the box, or the
/// triangle's plane, is already farther than its best, and in the second pass
/// when the box is nearer than `near` (the first pass had it). The row's
/// parts of the box and plane distances are taken once a row (x's once for
/// its rows), the box's distances without branches; the sums are those of
/// box_dist2 and (pt - a).n term by term, so every test decides as before.
inline void triangle_pass(const Tri &t, const Coord &o, const int lo[3], const int hi[3], double g2,
                          bool second, double near2, const uint8_t *rows, float *d2) {
  // a coordinate's distance to the box's range: max(lo - p, p - hi, 0) is
  // the same double as the three-way choice (lo <= hi), without branches
  auto out = [](double p, double l, double h) { return std::max(0.0, std::max(l - p, p - h)); };
  const unsigned range = (0xffu << lo[2]) & (0xffu >> (7 - hi[2])); // the box's voxels along z
  for (int x = lo[0]; x <= hi[0]; x++) {
    const double px = o[0] + x;
    const double ex = out(px, t.lo[0], t.hi[0]), ex2 = ex * ex, pxn = (px - t.a[0]) * t.n[0];
    for (int y = lo[1]; y <= hi[1]; y++) {
      const int row = (x << 3) | y;
      unsigned bits = rows != nullptr ? rows[row] & range : range;
      if (bits == 0) continue;
      // the row's voxels within g of the triangle's box
      const double py = o[1] + y;
      const double ey = out(py, t.lo[1], t.hi[1]);
      const double r2 = g2 - ex2 - ey * ey;
      if (!(r2 > 0.0)) continue;
      const double exy = ex2 + ey * ey;                // box_dist2's first two terms
      const double pxy = pxn + (py - t.a[1]) * t.n[1]; // (pt - a).n's
      float *best_of = d2 + (row << 3);
      for (; bits != 0; bits &= bits - 1) {
        const int z = __builtin_ctz(bits);
        const double pz = o[2] + z;
        const double ez = out(pz, t.lo[2], t.hi[2]);
        const double best = double(best_of[z]), bd = exy + ez * ez;
        if (!(bd < g2) || bd >= best || (second && bd < near2))
          continue; // beyond g, farther, or done in the first pass
        const double pd = pxy + (pz - t.a[2]) * t.n[2];
        if (pd * pd >= best) continue; // the plane is already farther
        const double e = tri_dist2(t, Vec3d(px, py, pz));
        if (e < best) best_of[z] = float(e);
      }
    }
  }
}

/// Ask for a triangle's cache lines ahead of its use (a block's triangles lie
/// anywhere in the mesh's order).
inline void prefetch_tri(const Tri &t) {
  const char *c = reinterpret_cast<const char *>(&t);
  __builtin_prefetch(c);
  __builtin_prefetch(c + 64);
  __builtin_prefetch(c + sizeof(Tri) - 1);
}

/// The block's voxels: squared distances (index units) to its triangles,
/// those below w^2 exact. First the voxels next to each triangle (its box
/// grown by one voxel), which leaves most voxels near their final value, then
/// the rest of the band, for the voxels the first pass left a voxel or more
/// away only (the others' nearest triangle is already known: any other box
/// is a voxel away); only voxels within the grown box's rounded corners
/// are visited, and a triangle whose box or plane is farther than the best
/// found so far is passed over without the closest-point computation.
void block_distances(const Coord &o, const Pair *p, size_t n, const std::vector<Tri> &tris,
                     double w, float *d2) {
  for (openvdb::Index v = 0; v < Leaf::SIZE; v++)
    d2[v] = float(w * w);
  const double near = std::min(1.0, w), near2 = near * near;
  for (size_t q = 0; q < n; q++) {
    if (q + 4 < n) prefetch_tri(tris[p[q + 4].tri]);
    const Tri &t = tris[p[q].tri];
    int lo[3], hi[3];
    if (local_range(t, o, near, lo, hi))
      triangle_pass(t, o, lo, hi, near2, false, near2, nullptr, d2);
  }
  if (!(w > near)) return;
  uint8_t rows[64]; // per (x, y): the voxels (bit z) still a voxel or more away
  bool any = false;
  for (int r = 0; r < 64; r++) {
    unsigned bits = 0;
    for (int z = 0; z < 8; z++)
      bits |= unsigned(!(double(d2[(r << 3) | z]) < near2)) << z;
    rows[r] = uint8_t(bits);
    any = any || bits != 0;
  }
  if (!any) return;
  for (size_t q = 0; q < n; q++) {
    if (q + 4 < n) prefetch_tri(tris[p[q + 4].tri]);
    const Tri &t = tris[p[q].tri];
    int lo[3], hi[3];
    if (local_range(t, o, w, lo, hi)) triangle_pass(t, o, lo, hi, w * w, true, near2, rows, d2);
  }
}

/// Winding numbers of the block's voxels from the sorted crossings: one
/// search a row of columns (x fixed, y along the block), whose crossings
/// follow one another in the sorted list.
void block_signs(const Coord &o, const std::vector<Crossing> &cross, int8_t *inside) {
  for (int x = 0; x < 8; x++) {
    const Crossing key{o[0] + x, o[1], 0.0f, 0};
    auto c = std::lower_bound(cross.begin(), cross.end(), key, column_less);
    for (int y = 0; y < 8; y++) {
      while (c != cross.end() && c->i == o[0] + x && c->j < o[1] + y)
        ++c;
      auto e = c;
      while (e != cross.end() && e->i == o[0] + x && e->j == o[1] + y)
        ++e;
      for (int z = 0; z < 8; z++) {
        int wn = 0;
        for (auto k = c; k != e; ++k)
          if (double(k->z) > double(o[2] + z)) wn += k->s;
        inside[(x << 6) | (y << 3) | z] = wn > 0;
      }
      c = e;
    }
  }
}

/// The winding number's sign at voxel c (as block_signs).
bool inside_at(const std::vector<Crossing> &cross, const Coord &c) {
  const Crossing key{c[0], c[1], 0.0f, 0};
  int wn = 0;
  for (auto k = std::lower_bound(cross.begin(), cross.end(), key, column_less);
       k != cross.end() && k->i == c[0] && k->j == c[1]; ++k)
    if (double(k->z) > double(c[2])) wn += k->s;
  return wn > 0;
}

/// The sign of every tile below the root (blocks and 128^3 regions without
/// a leaf) from the winding number at its first voxel, then OpenVDB's fill
/// for the root's gaps. A tile holds no voxel within a voxel of the surface
/// (those are all in leaves), so the surface passes neither through it nor
/// between its voxels and a neighbour's: one voxel gives its sign. OpenVDB's
/// signedFloodFill takes a tile's sign from a neighbouring leaf's corner
/// voxel instead, and a voxel exactly on the surface (a face on a plane of
/// voxel centres) carries the sign of one side only; with a band of one
/// voxel the leaf beyond it may be missing and the tile take the wrong side
/// (half of a design's interior, bear grown at 0.3 mm). Its leaf pass would
/// refill the leaves' inactive voxels by scan lines, which the winding
/// numbers already sign.
void sign_tiles(openvdb::FloatTree &tree, const std::vector<Crossing> &cross, float bg) {
  auto it = tree.beginValueAll();
  it.setMaxDepth(openvdb::FloatTree::ValueAllIter::LEAF_DEPTH - 1);
  for (; it; ++it)
    if (it.getLevel() < openvdb::FloatTree::RootNodeType::LEVEL)
      it.setValue(inside_at(cross, it.getCoord()) ? -bg : bg);
  openvdb::tools::signedFloodFill(tree, true, 1, openvdb::FloatTree::RootNodeType::LEVEL);
}

void make_tri(const std::vector<openvdb::Vec3s> &pts, const openvdb::Vec3I &tri, Tri &t) {
  make_tri(pts[tri[0]], pts[tri[1]], pts[tri[2]], t);
}

std::vector<Tri> index_triangles(const std::vector<openvdb::Vec3s> &pts,
                                 const std::vector<openvdb::Vec3I> &tris) {
  std::vector<Tri> out(tris.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tris.size(), 4096),
                    [&](const tbb::blocked_range<size_t> &r) {
                      for (size_t k = r.begin(); k != r.end(); ++k)
                        make_tri(pts, tris[k], out[k]);
                    });
  return out;
}

/// Refuse meshes whose grown bounding boxes would cost too many block tests.
void check_block_tests(const std::vector<Tri> &tris, double w) {
  double sum = 0.0;
  for (const Tri &t : tris) {
    double n = 1.0;
    for (int a = 0; a < 3; a++)
      n *= double(leaf_of(t.hi[a] + w)) - double(leaf_of(t.lo[a] - w)) + 1.0;
    sum += n;
  }
  if (sum > kMaxBlockTests)
    throw Error(SWARF_ERR_LIMIT, "the mesh's triangles span too many blocks at this voxel size");
}

template <typename T, typename Fn> std::vector<T> gather(size_t n, Fn fn) {
  tbb::enumerable_thread_specific<std::vector<T>> local;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024),
                    [&](const tbb::blocked_range<size_t> &r) {
                      std::vector<T> &out = local.local();
                      for (size_t k = r.begin(); k != r.end(); ++k)
                        fn(k, out);
                    });
  std::vector<T> all;
  size_t total = 0;
  for (const auto &v : local)
    total += v.size();
  all.reserve(total);
  for (const auto &v : local)
    all.insert(all.end(), v.begin(), v.end());
  return all;
}

/// The (block, triangle) pairs sorted by block, then triangle: made in
/// chunks of triangles (in parallel), then a counting sort by block over the
/// blocks' bounding box, chunk by chunk in triangle order (a comparison sort
/// when that box is too large).
std::vector<Pair> sorted_pairs(const std::vector<Tri> &t, double w) {
  constexpr size_t kTris = 8192;
  struct Part {
    std::vector<Pair> pairs;
    int32_t lo[3] = {INT32_MAX, INT32_MAX, INT32_MAX}, hi[3] = {INT32_MIN, INT32_MIN, INT32_MIN};
  };
  std::vector<Part> parts((t.size() + kTris - 1) / kTris);
  tbb::parallel_for(size_t(0), parts.size(), [&](size_t c) {
    Part &part = parts[c];
    for (size_t k = c * kTris; k < std::min(t.size(), (c + 1) * kTris); k++)
      block_pairs(t[k], uint32_t(k), w, part.pairs);
    for (const Pair &q : part.pairs) {
      const int32_t b[3] = {q.x, q.y, q.z};
      for (int a = 0; a < 3; a++)
        part.lo[a] = std::min(part.lo[a], b[a]), part.hi[a] = std::max(part.hi[a], b[a]);
    }
  });
  int32_t lo[3] = {INT32_MAX, INT32_MAX, INT32_MAX}, hi[3] = {INT32_MIN, INT32_MIN, INT32_MIN};
  size_t total = 0;
  for (const Part &part : parts) {
    total += part.pairs.size();
    for (int a = 0; a < 3; a++)
      lo[a] = std::min(lo[a], part.lo[a]), hi[a] = std::max(hi[a], part.hi[a]);
  }
  std::vector<Pair> out;
  out.reserve(total);
  if (total == 0) return out;
  uint64_t n[3], bins = 1;
  for (int a = 0; a < 3; a++)
    n[a] = uint64_t(int64_t(hi[a]) - lo[a] + 1),
    bins *= std::min<uint64_t>(n[a], uint64_t(1) << 30);
  if (bins > (uint64_t(1) << 26)) { // sparse: sort
    for (const Part &part : parts)
      out.insert(out.end(), part.pairs.begin(), part.pairs.end());
    tbb::parallel_sort(out.begin(), out.end(), pair_less);
    return out;
  }
  auto bin = [&](const Pair &q) {
    return (uint64_t(q.x - lo[0]) * n[1] + uint64_t(q.y - lo[1])) * n[2] + uint64_t(q.z - lo[2]);
  };
  std::vector<uint32_t> at(bins + 1, 0);
  for (const Part &part : parts)
    for (const Pair &q : part.pairs)
      at[bin(q) + 1]++;
  for (size_t b = 0; b < bins; b++)
    at[b + 1] += at[b];
  out.resize(total);
  for (Part &part : parts) {
    for (const Pair &q : part.pairs)
      out[at[bin(q)]++] = q;
    std::vector<Pair>().swap(part.pairs);
  }
  return out;
}

} // namespace

openvdb::FloatGrid::Ptr mesh_band(const std::vector<openvdb::Vec3s> &pts,
                                  const std::vector<openvdb::Vec3I> &tris, double voxel,
                                  int half_width, float bg) {
  const double w = double(half_width);
  const std::vector<Tri> t = index_triangles(pts, tris);
  check_block_tests(t, w);
  std::vector<Crossing> cross =
      gather<Crossing>(tris.size(), [&](size_t k, std::vector<Crossing> &out) {
        column_crossings(pts[tris[k][0]], pts[tris[k][1]], pts[tris[k][2]], out);
      });
  tbb::parallel_sort(cross.begin(), cross.end(), column_less);
  std::vector<Pair> pairs = sorted_pairs(t, w);
  std::vector<size_t> starts;
  for (size_t i = 0; i < pairs.size(); i++)
    if (i == 0 || pairs[i].x != pairs[i - 1].x || pairs[i].y != pairs[i - 1].y ||
        pairs[i].z != pairs[i - 1].z)
      starts.push_back(i);
  starts.push_back(pairs.size());
  std::vector<std::unique_ptr<Leaf>> leaves(starts.size() - 1);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, leaves.size(), 8),
                    [&](const tbb::blocked_range<size_t> &r) {
                      float d2[Leaf::SIZE];
                      int8_t inside[Leaf::SIZE];
                      for (size_t b = r.begin(); b != r.end(); ++b) {
                        const Pair &p = pairs[starts[b]];
                        const Coord o(8 * p.x, 8 * p.y, 8 * p.z);
                        block_distances(o, &pairs[starts[b]], starts[b + 1] - starts[b], t, w, d2);
                        bool band = false;
                        for (openvdb::Index v = 0; v < Leaf::SIZE && !band; v++)
                          band = double(d2[v]) < w * w;
                        if (!band) continue;
                        block_signs(o, cross, inside);
                        auto leaf = std::make_unique<Leaf>(o, bg, false);
                        for (openvdb::Index v = 0; v < Leaf::SIZE; v++) {
                          if (double(d2[v]) < w * w) {
                            const float d = float(std::sqrt(double(d2[v])) * voxel);
                            leaf->setValueOn(v, inside[v] ? -d : d);
                          } else {
                            leaf->setValueOff(v, inside[v] ? -bg : bg);
                          }
                        }
                        leaves[b] = std::move(leaf);
                      }
                    });
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(bg);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
  openvdb::FloatTree &tree = grid->tree();
  for (auto &leaf : leaves)
    if (leaf) tree.addLeaf(leaf.release());
  sign_tiles(tree, cross, bg);
  return grid;
}

} // namespace swarf
