#include "src/sampletree/sample_tree.hpp"

namespace lzb::sampletree {

Bounds SampleTree::cellBounds(const TreeNode& n) const {
  const double s = cellSize(n);
  Bounds b;
  b.lo = origin + s * glm::dvec3(n.cell[0], n.cell[1], n.cell[2]);
  b.hi = b.lo + glm::dvec3(s);
  return b;
}

uint64_t SampleTree::dataBytes() const {
  return nodes.size() * sizeof(TreeNode) + positions.size() * sizeof(glm::vec3) +
         ids.size() * sizeof(uint64_t) + colours.size() * sizeof(Rgba8);
}

}  // namespace lzb::sampletree
