#pragma once
// The element buffer for drawing a list of triangles out of a node's unindexed vertex buffer:
// triangle t becomes the indices 3t, 3t + 1, 3t + 2, so gl_VertexID / 3 is t again (the ID the
// shader writes) and every vertex is the very one a range draw uses. Needs a current context.
#include <cstdint>
#include <span>
#include <vector>

namespace lzb::gl {

class ListIndices {
 public:
  // Triangles per upload (12 MiB of indices): bounds the scratch memory and GL's 32-bit counts.
  static constexpr uint64_t kBatchTriangles = uint64_t(1) << 20;

  ListIndices() = default;
  ~ListIndices();
  ListIndices(const ListIndices&) = delete;
  ListIndices& operator=(const ListIndices&) = delete;

  // Fills the element buffer, bound to the current vertex array, with the indices of at most
  // kBatchTriangles triangles (indices into the bound vertex buffer, each < 2^32 / 3).
  void upload(std::span<const uint32_t> triangles);

 private:
  unsigned buffer_ = 0;
  std::vector<uint32_t> scratch_;
};

}  // namespace lzb::gl
