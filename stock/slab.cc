/* SPDX-License-Identifier: MPL-2.0 */
/// @file slab.cc
/// @brief Slabs of a stock's index space (stock.h, "Slabs of the stock"): a
/// region that removal and the queries keep to, a tally of the blocks removal
/// visits, and a slab's blocks saved to a memory buffer and put into another
/// stock of the same frame. Several processes each removing in their own
/// region of copies of one stock, then loading the others' slabs into one,
/// get the grid one process would: removal is pointwise and per block.
///
/// A slab is every leaf-aligned 8^3 block whose origin lies in the region
/// and which sits below a level-1 node of the tree: a leaf, or a tile of one
/// block (the only nodes removal creates or changes; blocks under larger
/// tiles are as the stock was built). Loading a block makes the same
/// topology change removal made (touchLeaf, addTile at level 1), so the
/// merged tree has the same nodes, values and active states.
///
/// Buffer (native byte order, the same machine type on every rank): "SWPT",
/// voxel (double), background (float), then records: kind (1 byte: 0 leaf,
/// 1 tile), origin (3 int32); a leaf: value mask (8 uint64), 512 floats; a
/// tile: value (float), active (1 byte).
#include <cstdlib>
#include <cstring>

#include "stock_private.h"

namespace {

using openvdb::Coord;
using Tree = openvdb::FloatTree;
using Leaf = Tree::LeafNodeType;
using Internal1 = Tree::RootNodeType::ChildNodeType::ChildNodeType;

constexpr char kMagic[4] = {'S', 'W', 'P', 'T'};
constexpr size_t kHeader = 4 + sizeof(double) + sizeof(float);
constexpr size_t kOrigin = 1 + 3 * sizeof(int32_t);
constexpr size_t kLeaf = kOrigin + 8 * sizeof(uint64_t) + Leaf::SIZE * sizeof(float);
constexpr size_t kTile = kOrigin + sizeof(float) + 1;

bool in_region(const swarf_stock &s, const Coord &o) {
  if (!s.has_region) return true;
  for (int k = 0; k < 3; k++)
    if (o[k] < s.region_lo[k] || o[k] > s.region_hi[k]) return false;
  return true;
}

/// Bytes written to a buffer, or only counted (p NULL): save() runs twice, so
/// that the slab is written once into a buffer of its exact size.
struct Out {
  char *p = nullptr;
  size_t n = 0;
  void put(const void *src, size_t k) {
    if (p != nullptr) std::memcpy(p + n, src, k);
    n += k;
  }
  void put_origin(char kind, const Coord &o) {
    put(&kind, 1);
    for (int k = 0; k < 3; k++) {
      const int32_t v = o[k];
      put(&v, sizeof v);
    }
  }
};

void save(const swarf_stock &s, Out &b) {
  b.put(kMagic, 4);
  b.put(&s.voxel, sizeof s.voxel);
  b.put(&s.background, sizeof s.background);
  std::vector<const Internal1 *> nodes;
  s.grid->constTree().getNodes(nodes);
  for (const Internal1 *n : nodes) {
    for (auto it = n->cbeginChildOn(); it; ++it) {
      const Leaf &leaf = *it;
      if (!in_region(s, leaf.origin())) continue;
      b.put_origin(0, leaf.origin());
      for (int w = 0; w < 8; w++) {
        const uint64_t word = leaf.getValueMask().template getWord<uint64_t>(w);
        b.put(&word, sizeof word);
      }
      b.put(leaf.buffer().data(), Leaf::SIZE * sizeof(float));
    }
    for (auto it = n->cbeginValueAll(); it; ++it) {
      const Coord o = it.getCoord();
      if (!in_region(s, o)) continue;
      b.put_origin(1, o);
      const float v = it.getValue();
      const char on = it.isValueOn() ? 1 : 0;
      b.put(&v, sizeof v);
      b.put(&on, 1);
    }
  }
}

template <class T> T get(const char *&p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  p += sizeof v;
  return v;
}

void load(swarf_stock &s, const char *buf, size_t len) {
  using swarf::Error;
  if (len < kHeader || std::memcmp(buf, kMagic, 4) != 0)
    throw Error(SWARF_ERR_FORMAT, "not a stock slab");
  const char *p = buf + 4, *end = buf + len;
  const double voxel = get<double>(p);
  const float bg = get<float>(p);
  if (voxel != s.voxel || bg != s.background)
    throw Error(SWARF_ERR_ARG, "the slab's voxel or band differs from the stock's");
  Tree &tree = s.grid->tree();
  while (p < end) {
    if (size_t(end - p) < kOrigin) throw Error(SWARF_ERR_FORMAT, "a stock slab is truncated");
    const char kind = *p++;
    int32_t c[3];
    for (int k = 0; k < 3; k++)
      c[k] = get<int32_t>(p);
    const Coord o(c[0], c[1], c[2]);
    for (int k = 0; k < 3; k++)
      if ((c[k] & 7) != 0 || c[k] < -(1 << 30) || c[k] > (1 << 30))
        throw Error(SWARF_ERR_FORMAT, "a stock slab's block is not leaf-aligned");
    if (kind == 0 && size_t(end - p) >= kLeaf - kOrigin) {
      Leaf *leaf = tree.touchLeaf(o);
      openvdb::util::NodeMask<3> mask;
      for (int w = 0; w < 8; w++)
        mask.template getWord<uint64_t>(w) = get<uint64_t>(p);
      std::memcpy(leaf->buffer().data(), p, Leaf::SIZE * sizeof(float));
      p += Leaf::SIZE * sizeof(float);
      leaf->setValueMask(mask);
    } else if (kind == 1 && size_t(end - p) >= kTile - kOrigin) {
      const float v = get<float>(p);
      const bool on = *p++ != 0;
      tree.addTile(1, o, v, on);
    } else {
      throw Error(SWARF_ERR_FORMAT, "a stock slab holds a bad or truncated record");
    }
  }
}

} // namespace

using swarf::Error;

extern "C" void swarf_stock_index_box(const swarf_stock *s, int lo[3], int hi[3]) {
  for (int k = 0; k < 3; k++) {
    lo[k] = s != nullptr && !s->content.empty() ? s->content.min()[k] : 1;
    hi[k] = s != nullptr && !s->content.empty() ? s->content.max()[k] : 0;
  }
}

extern "C" void swarf_stock_index_of(const swarf_stock *s, const double p[3], int ijk[3]) {
  for (int k = 0; k < 3; k++) {
    const double i = s != nullptr ? std::round((p[k] - s->origin[k]) / s->voxel) : 0.0;
    ijk[k] = std::isfinite(i) && std::fabs(i) < 2e9 ? int(i) : 0;
  }
}

extern "C" swarf_status swarf_stock_set_region(swarf_stock *s, const int lo[3], const int hi[3],
                                               swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr) throw Error(SWARF_ERR_ARG, "stock is NULL");
    if (lo == nullptr || hi == nullptr) {
      s->has_region = false;
      return;
    }
    for (int k = 0; k < 3; k++) {
      if (lo[k] > hi[k]) throw Error(SWARF_ERR_ARG, "region: lo > hi");
      // block origins within [lo, hi]: lo rounded up, hi down to multiples of 8
      s->region_lo[k] = int((long(lo[k]) + 7) & ~7L);
      s->region_hi[k] = hi[k] & ~7;
    }
    s->has_region = true;
  });
}

extern "C" void swarf_stock_set_tally(swarf_stock *s, const int lo[3], const int n[3],
                                      unsigned long long *counts) {
  if (s == nullptr) return;
  s->tally = lo != nullptr && n != nullptr ? counts : nullptr;
  for (int k = 0; s->tally && k < 3; k++) {
    s->tally_lo[k] = lo[k] & ~7;
    s->tally_n[k] = n[k] > 0 ? n[k] : 0;
  }
}

extern "C" swarf_status swarf_stock_slab_crop(swarf_stock *s, swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr) throw Error(SWARF_ERR_ARG, "stock is NULL");
    if (!s->has_region) return;
    std::vector<Coord> out;
    for (auto it = s->grid->constTree().cbeginLeaf(); it; ++it)
      if (!in_region(*s, it->origin())) out.push_back(it->origin());
    Tree &tree = s->grid->tree();
    for (const Coord &o : out)
      tree.addTile(1, o, s->background, false);
  });
}

extern "C" swarf_status swarf_stock_slab_save(const swarf_stock *s, void **buf, size_t *len,
                                              swarf_error *err) {
  if (buf != nullptr) *buf = nullptr;
  if (len != nullptr) *len = 0;
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || buf == nullptr || len == nullptr)
      throw Error(SWARF_ERR_ARG, "stock, buf or len is NULL");
    Out count;
    save(*s, count);
    Out b;
    if ((b.p = static_cast<char *>(std::malloc(count.n))) == nullptr) throw std::bad_alloc();
    save(*s, b);
    *buf = b.p;
    *len = b.n;
  });
}

extern "C" swarf_status swarf_stock_slab_load(swarf_stock *s, const void *buf, size_t len,
                                              swarf_error *err) {
  return swarf::guard(err, nullptr, [&] {
    if (s == nullptr || buf == nullptr) throw Error(SWARF_ERR_ARG, "stock or buf is NULL");
    load(*s, static_cast<const char *>(buf), len);
  });
}
