#pragma once
// Laying a sampled octree out as the store keeps it: nodes in preorder (children in octant order),
// each node's triangles sorted by ID, a representative per node, and subtrees left without
// triangles after sampling dropped. The external construction lays each bucket out on its own
// and hangs it below the top levels' leaves as a hidden subtree, counted but not held.
#include <cstdint>
#include <utility>
#include <vector>

#include "src/sampletree/cell_octree.hpp"
#include "src/sampletree/sample_tree.hpp"

namespace lzb::sampletree {

// A subtree laid out elsewhere that follows a node: its node and triangle counts.
struct HiddenSubtree {
  uint64_t nodes = 0, triangles = 0;
};

class TreeLayout {
 public:
  // hidden: one per octree node, or empty (none).
  TreeLayout(const CellOctree& oct, const TriangleInput& in, const std::vector<double>& areas,
             std::vector<HiddenSubtree> hidden = {});
  // Appends u's subtree to `out` (u itself included); indices count the hidden subtrees before.
  void emit(size_t u, SampleTree& out);
  // Appends the subtrees of u's children only (a bucket's nodes below its root).
  void emitChildren(size_t u, SampleTree& out);
  // Triangles in u's subtree after sampling (hidden ones included).
  uint64_t remaining(size_t u) const { return remaining_[u]; }
  // (index in out.nodes, octree node) of each node that a hidden subtree follows, in order.
  const std::vector<std::pair<size_t, size_t>>& splices() const { return splices_; }

 private:
  const CellOctree& oct_;
  const TriangleInput& in_;
  const std::vector<double>& areas_;
  std::vector<HiddenSubtree> hidden_;
  std::vector<uint64_t> remaining_;
  std::vector<std::pair<size_t, size_t>> splices_;
  uint64_t hiddenNodes_ = 0, hiddenTriangles_ = 0;
};

}  // namespace lzb::sampletree
