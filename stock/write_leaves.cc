/* SPDX-License-Identifier: MPL-2.0 */
/// @file write_leaves.cc
/// @brief The .vdb writer's leaf buffers on the stock's threads:
/// a shallow copy of the stock's grid whose writeBuffers, the part of
/// io::Archive::write that compresses every leaf (mask compression, then
/// Blosc), runs OpenVDB's own LeafNode::writeBuffers on many leaves at once,
/// each batch of leaves into a memory buffer of its own, and appends the
/// buffers to the file in the tree's order. The bytes are the ones the serial
/// loop (Tree::writeBuffers: root table, then child order, down to the
/// leaves, as a leaf iterator visits them) writes: the leaves' stream state
/// (the grid's data compression and background) is copied to each buffer's
/// stream. At 0.1 mm on bear.nc that loop was the largest serial part of a
/// run (about 0.25 s of 3.5, two-thread goal).
/// SWARF_VDB_SERIAL_WRITE=1 in the environment (swarf_reference.h) writes with OpenVDB's loop
/// (tests compare the two files byte for byte).
/// Owns nothing beyond the copy: the tree is shared with the stock.
#include <openvdb/io/io.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>

#include "stock_private.h"
#include "swarf_reference.h"

namespace swarf {
namespace {

using Leaf = openvdb::FloatTree::LeafNodeType;

constexpr size_t kChunk = 64;    ///< leaves per buffer (about 64 x 2 KB at bear's 0.1 mm)
constexpr size_t kRound = 16384; ///< leaves compressed before their buffers are written

/// An output buffer that appends to a string (no copy when it is written out).
class StringBuf : public std::streambuf {
public:
  std::string bytes;

protected:
  std::streamsize xsputn(const char *p, std::streamsize n) override {
    bytes.append(p, static_cast<size_t>(n));
    return n;
  }
  int_type overflow(int_type c) override {
    if (!traits_type::eq_int_type(c, traits_type::eof()))
      bytes.push_back(traits_type::to_char_type(c));
    return traits_type::not_eof(c);
  }
};

class LeafParallelGrid final : public openvdb::FloatGrid {
public:
  LeafParallelGrid(openvdb::FloatGrid &g, std::shared_ptr<tbb::task_arena> arena)
      : openvdb::FloatGrid(g, openvdb::ShallowCopy{}), arena_(std::move(arena)) {}

  void writeBuffers(std::ostream &os) const override {
    if (hasMultiPassIO() || swarf_reference_on(SWARF_REFERENCE_VDB_SERIAL_WRITE)) {
      openvdb::FloatGrid::writeBuffers(os);
      return;
    }
    std::vector<const Leaf *> leaves;
    leaves.reserve(tree().leafCount());
    for (auto it = tree().cbeginLeaf(); it; ++it)
      leaves.push_back(it.getLeaf());
    for (size_t first = 0; first < leaves.size() && os; first += kRound)
      write_round(os, leaves.data() + first, std::min(kRound, leaves.size() - first));
  }

private:
  /// Leaves[0..n) compressed in parallel, then written in order.
  void write_round(std::ostream &os, const Leaf *const *leaves, size_t n) const {
    const uint32_t compression = openvdb::io::getDataCompression(os);
    const void *background = openvdb::io::getGridBackgroundValuePtr(os);
    const bool half = saveFloatAsHalf();
    std::vector<StringBuf> bufs((n + kChunk - 1) / kChunk);
    auto work = [&] {
      tbb::parallel_for(size_t(0), bufs.size(), [&](size_t c) {
        std::ostream out(&bufs[c]);
        openvdb::io::setDataCompression(out, compression);
        openvdb::io::setGridBackgroundValuePtr(out, background);
        for (size_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); i++)
          leaves[i]->writeBuffers(out, half);
      });
    };
    if (arena_)
      arena_->execute(work);
    else
      work();
    for (const StringBuf &b : bufs)
      os.write(b.bytes.data(), static_cast<std::streamsize>(b.bytes.size()));
  }

  std::shared_ptr<tbb::task_arena> arena_;
};

} // namespace

openvdb::FloatGrid::Ptr leaf_parallel_copy(const swarf_stock &s) {
  return std::make_shared<LeafParallelGrid>(*s.grid, s.arena);
}

} // namespace swarf
