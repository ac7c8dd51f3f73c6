/* SPDX-License-Identifier: MPL-2.0 */
/// @file mesh_surface.cc
/// @brief MeshSurface (mesh_sdf.h): a mesh's triangles kept for exact
/// distance queries beyond its band. The triangles in Morton order of their
/// centroids, in chunks of kChunk under an implicit binary tree of bounds; a
/// query descends nearer child first and passes over every node no nearer
/// than the best distance found.
#include <sys/mman.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

#include "mesh_sdf.h"
#include "mesh_tri.h"
#include "stock_private.h"

namespace swarf {
namespace {

using mesh::box_dist2;
using mesh::make_tri;
using mesh::Tri;
using mesh::tri_dist2;
using openvdb::Vec3d;

/// A triangle's corners, as the queries keep them (36 bytes, not Tri's 120:
/// the ordering writes less, and a query makes the few Tri it measures).
struct Corners {
  openvdb::Vec3s p[3];
};

/// The bounds of c, as make_tri's.
inline void corners_box(const Corners &c, double lo[3], double hi[3]) {
  for (int a = 0; a < 3; a++) {
    const double x = c.p[0][a], y = c.p[1][a], z = c.p[2][a];
    lo[a] = std::min(x, std::min(y, z)), hi[a] = std::max(x, std::max(y, z));
  }
}

/// Spread the low 21 bits of v three apart (Morton codes).
uint64_t spread3(uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

constexpr size_t kChunk = 32;

/// Anonymous memory on transparent huge pages where the kernel gives them,
/// faulted in by one call: a large buffer without a page fault per page,
/// which on a paravirtualized machine cost 0.2 s for the 49 MB of a
/// 1.36 M-triangle design's triangles (0.08 s with MAP_POPULATE alone). The
/// mapping is 2 MB larger than asked, so that a 2 MB-aligned start exists.
struct Region {
  void *p = nullptr;    ///< the buffer (2 MB-aligned)
  void *base = nullptr; ///< the mapping
  size_t bytes = 0;     ///< the mapping's length
  Region() = default;
  Region(const Region &) = delete;
  Region &operator=(const Region &) = delete;
  void swap(Region &o) { std::swap(p, o.p), std::swap(base, o.base), std::swap(bytes, o.bytes); }
  ~Region() {
    if (base != nullptr) ::munmap(base, bytes);
  }
  void map(size_t n) {
    constexpr size_t kHuge = size_t(2) << 20;
    constexpr int kPopulateWrite = 23; // MADV_POPULATE_WRITE (Linux 5.14)
    if (n == 0) return;
    const size_t len = n + kHuge;
    base = ::mmap(nullptr, len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (base == MAP_FAILED) {
      base = nullptr;
      throw std::bad_alloc();
    }
    bytes = len;
    p = reinterpret_cast<void *>((reinterpret_cast<uintptr_t>(base) + kHuge - 1) & ~(kHuge - 1));
    (void)::madvise(p, n, MADV_HUGEPAGE); // best effort, as is the population
    (void)::madvise(p, n, kPopulateWrite);
  }
};

} // namespace

struct MeshSurface {
  std::vector<openvdb::Vec3s> pts; ///< the mesh, until ordered
  std::vector<openvdb::Vec3I> tris;
  /// mesh_surface_lazy: the surface to take over at the first query
  std::function<std::shared_ptr<MeshSurface>()> load;
  std::once_flag once;
  std::exception_ptr failed; ///< what the first query's read threw, if it did
  /// The triangles in Morton order of their centroids (tri, ntri): in owned
  /// (order()) or in region (mesh_surface_ordered).
  std::vector<Corners> owned;
  Region region;
  const Corners *tri = nullptr;
  size_t ntri = 0;
  struct Box {
    double lo[3], hi[3];
  };
  /// An implicit binary tree of bounds over the chunks tri[kChunk c,
  /// kChunk (c + 1)): node 1 the root, node i's children 2i and 2i + 1, chunk
  /// c's leaf node `leaves + c` (empty leaves hold an empty box, at infinite
  /// distance). Morton order keeps a node's chunks together, so its box is
  /// tight and a query visits few nodes.
  std::vector<Box> nodes;
  size_t leaves = 0; ///< a power of two, at least the chunks' count
  void order();
  void build_tree();
};

/// The triangles in Morton order, in chunks with their bounds; the mesh
/// itself is let go.
void MeshSurface::order() {
  if (tris.empty()) return;
  // the triangles' bounds (their corners'), then each one's Morton code, in
  // parallel; the triangles made once, in their sorted places (a design's
  // first query beyond its band pays for this: 1.36 M triangles)
  Vec3d lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (const openvdb::Vec3I &t : tris)
    for (int c = 0; c < 3; c++)
      lo = openvdb::math::minComponent(lo, Vec3d(pts[t[c]])),
      hi = openvdb::math::maxComponent(hi, Vec3d(pts[t[c]]));
  std::vector<std::pair<uint64_t, uint32_t>> key(tris.size());
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, tris.size(), 4096), [&](const tbb::blocked_range<size_t> &r) {
        for (size_t k = r.begin(); k != r.end(); ++k) {
          uint64_t code = 0;
          for (int a = 0; a < 3; a++) {
            const double p0 = pts[tris[k][0]][a], p1 = pts[tris[k][1]][a], p2 = pts[tris[k][2]][a];
            const double c = (std::min(p0, std::min(p1, p2)) + std::max(p0, std::max(p1, p2))) *
                             0.5,
                         span = hi[a] - lo[a];
            code |= spread3(uint64_t(span > 0.0 ? (c - lo[a]) / span * 2097151.0 : 0.0)) << a;
          }
          key[k] = {code, uint32_t(k)};
        }
      });
  tbb::parallel_sort(key.begin(), key.end());
  owned.resize(tris.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, key.size(), 4096),
                    [&](const tbb::blocked_range<size_t> &r) {
                      for (size_t k = r.begin(); k != r.end(); ++k) {
                        const openvdb::Vec3I &t = tris[key[k].second];
                        owned[k] = Corners{{pts[t[0]], pts[t[1]], pts[t[2]]}};
                      }
                    });
  tri = owned.data();
  ntri = owned.size();
  std::vector<openvdb::Vec3s>().swap(pts);
  std::vector<openvdb::Vec3I>().swap(tris);
  build_tree();
}

/// The chunks' bounds as the tree's leaves, then each node's as the union of
/// its children's (in floating point too a parent is never farther from a
/// point than its children: the pruning only ever skips what the chunks'
/// own boxes would).
void MeshSurface::build_tree() {
  const size_t chunks = (ntri + kChunk - 1) / kChunk;
  leaves = 1;
  while (leaves < chunks)
    leaves *= 2;
  const double inf = std::numeric_limits<double>::infinity();
  nodes.assign(2 * leaves, Box{{inf, inf, inf}, {-inf, -inf, -inf}});
  for (size_t c = 0; c < chunks; c++) {
    Box &b = nodes[leaves + c];
    for (size_t k = c * kChunk; k < std::min((c + 1) * kChunk, ntri); k++) {
      double lo[3], hi[3];
      corners_box(tri[k], lo, hi);
      for (int a = 0; a < 3; a++)
        b.lo[a] = std::min(b.lo[a], lo[a]), b.hi[a] = std::max(b.hi[a], hi[a]);
    }
  }
  for (size_t i = leaves - 1; i >= 1; i--)
    for (int a = 0; a < 3; a++) {
      nodes[i].lo[a] = std::min(nodes[2 * i].lo[a], nodes[2 * i + 1].lo[a]);
      nodes[i].hi[a] = std::max(nodes[2 * i].hi[a], nodes[2 * i + 1].hi[a]);
    }
}

std::shared_ptr<MeshSurface> mesh_surface(std::vector<openvdb::Vec3s> pts,
                                          std::vector<openvdb::Vec3I> tris) {
  auto m = std::make_shared<MeshSurface>();
  m->pts = std::move(pts);
  m->tris = std::move(tris);
  return m;
}

std::shared_ptr<MeshSurface> mesh_surface_lazy(std::function<std::shared_ptr<MeshSurface>()> load) {
  auto m = std::make_shared<MeshSurface>();
  m->load = std::move(load);
  return m;
}

std::shared_ptr<MeshSurface> mesh_surface_ordered(size_t count,
                                                  const std::function<void(float *)> &fill) {
  static_assert(sizeof(Corners) == 9 * sizeof(float), "packed corners");
  auto m = std::make_shared<MeshSurface>();
  m->region.map(count * sizeof(Corners));
  if (count > 0) fill(static_cast<float *>(m->region.p));
  m->tri = static_cast<const Corners *>(m->region.p);
  m->ntri = count;
  m->build_tree();
  return m;
}

/// m read (a lazy surface) and ordered, once: at its first query (most
/// designs are never asked beyond their band). Isolated, so that the sort's
/// thread does not take up another query of the caller's parallel loop while
/// it holds the flag. A failed read is kept and thrown to every query (an
/// exception thrown through call_once is not safe everywhere).
static void ready(MeshSurface &m) {
  std::call_once(m.once, [&] {
    tbb::this_task_arena::isolate([&] {
      try {
        if (m.load) {
          std::shared_ptr<MeshSurface> got = m.load();
          m.pts.swap(got->pts);
          m.tris.swap(got->tris);
          m.owned.swap(got->owned);
          m.region.swap(got->region);
          m.nodes.swap(got->nodes);
          m.tri = got->tri, m.ntri = got->ntri, m.leaves = got->leaves;
          m.load = nullptr;
        }
        if (m.tri == nullptr) m.order();
      } catch (...) {
        m.failed = std::current_exception();
      }
    });
  });
  if (m.failed) std::rethrow_exception(m.failed);
}

const float *mesh_surface_corners(MeshSurface &m, size_t *count) {
  ready(m);
  *count = m.ntri;
  return reinterpret_cast<const float *>(m.tri);
}

/// The squared distance (index units) of mesh_surface_distance.
double mesh_surface_distance2(MeshSurface &m, const openvdb::Vec3d &p) {
  ready(m);
  double best = std::numeric_limits<double>::infinity();
  if (m.ntri == 0) return best;
  // Depth first, the nearer child first (its triangles lower the best soon),
  // a node passed over when its box is no nearer than the best found.
  struct Entry {
    size_t node;
    double d2;
  };
  Entry stack[64]; // the tree's depth is below 40 (2^32 triangles at most)
  size_t top = 0;
  stack[top++] = {1, box_dist2(m.nodes[1].lo, m.nodes[1].hi, p)};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.d2 >= best) continue;
    if (e.node >= m.leaves) {
      const size_t c = e.node - m.leaves;
      for (size_t k = c * kChunk; k < std::min((c + 1) * kChunk, m.ntri); k++) {
        double lo[3], hi[3];
        corners_box(m.tri[k], lo, hi);
        if (!(box_dist2(lo, hi, p) < best)) continue;
        Tri t;
        make_tri(m.tri[k].p[0], m.tri[k].p[1], m.tri[k].p[2], t);
        best = std::min(best, tri_dist2(t, p));
      }
      continue;
    }
    const size_t a = 2 * e.node, b = a + 1;
    const double da = box_dist2(m.nodes[a].lo, m.nodes[a].hi, p),
                 db = box_dist2(m.nodes[b].lo, m.nodes[b].hi, p);
    if (da <= db) {
      stack[top++] = {b, db};
      stack[top++] = {a, da};
    } else {
      stack[top++] = {a, da};
      stack[top++] = {b, db};
    }
  }
  return best;
}

double mesh_surface_distance(MeshSurface &m, const openvdb::Vec3d &p) {
  return std::sqrt(mesh_surface_distance2(m, p));
}

double surface_distance_exact(const swarf_stock &d, const openvdb::Vec3d &w) {
  return mesh_surface_distance(*d.surface, (w - d.origin) / d.voxel) * d.voxel;
}

double surface_distance(const swarf_stock &d, const openvdb::Vec3d &w) {
  // within SWARF_STOCK_DESIGN_BAND voxels, what mesh_band stores there: the
  // squared distance as a float, its root in mm as a float
  Vec3d p = (w - d.origin) / d.voxel; // the voxel's index, as mesh_band's
  for (int a = 0; a < 3; a++)
    if (std::fabs(p[a] - std::round(p[a])) < 1e-6) p[a] = std::round(p[a]);
  const double e2 = mesh_surface_distance2(*d.surface, p);
  const float f2 = float(e2);
  constexpr double kBand2 = double(SWARF_STOCK_DESIGN_BAND) * SWARF_STOCK_DESIGN_BAND;
  if (double(f2) < kBand2) return double(float(std::sqrt(double(f2)) * d.voxel));
  return std::sqrt(e2) * d.voxel;
}

} // namespace swarf
