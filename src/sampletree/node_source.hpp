#pragma once
// Where the node cache gets node payloads from: the store on this rank's disk (StoreReader) or a
// node server on another rank (NodeClient). Both give the node table (resident) and read nodes'
// triangles on request, from the cache's one loader thread.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "src/sampletree/sample_tree.hpp"
#include "src/sampletree/store_format.hpp"

namespace lzb::sampletree {

// What rendering needs of a node's triangles: where they are, their IDs (the key buffer's) and
// colours (the tree shades its own pixels, tree_shading.hpp).
struct NodePayload {
  std::vector<glm::vec3> positions;  // 3 per triangle
  std::vector<uint64_t> ids;
  std::vector<Rgba8> colours;
};

// Bytes of a node's payload as loaded: positions, IDs and colours.
inline uint64_t payloadBytes(const TreeNode& n) {
  return uint64_t(n.triangleCount) * (format::kPositionBytes + format::kIdBytes + format::kColourBytes);
}

// What a resident node costs the cache besides its payload: its entry in the cache's map, the
// payload's own object and the heap blocks of its three arrays (allocator headers and rounding).
constexpr uint64_t kNodeBookkeepingBytes = 256;

// What a node costs the node cache while resident (--cache-mb counts this, not the payload alone:
// a frame at 10^8 triangles holds ~10^6 nodes, whose bookkeeping alone would be ~256 MB).
inline uint64_t cachedBytes(const TreeNode& n) {
  return payloadBytes(n) + kNodeBookkeepingBytes;
}

class NodeSource {
 public:
  virtual ~NodeSource() = default;
  // The tree without triangles: parameters, root cube and every node.
  virtual const SampleTree& table() const = 0;
  // The payloads of `nodes`, in their order. Not thread-safe: one loader calls it.
  virtual std::vector<NodePayload> readNodes(std::span<const uint32_t> nodes) = 0;
  // Bytes this rank read from a store file so far (0 when another rank reads them).
  virtual uint64_t fileBytesRead() const = 0;
};

}  // namespace lzb::sampletree
