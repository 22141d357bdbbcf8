#include "raycast/lzb/lzb_octree_ropes.hpp"

namespace lzb::localz {

OctreeRopes::OctreeRopes(const Octree& tree) {
  const uint32_t n = tree.nodeCount();
  parent_.assign(n, kNone);
  ropes_.assign(n, {kNone, kNone, kNone, kNone, kNone, kNone});
  if (n == 0) return;
  // Parents first (explicit stack: no recursion depth limits), so a child's ropes can use its
  // parent's.
  std::vector<uint32_t> stack{0};
  while (!stack.empty()) {
    const uint32_t node = stack.back();
    stack.pop_back();
    const Octree::Node& nd = tree.node(node);
    if (nd.leaf()) continue;
    for (uint32_t o = 0; o < 8; ++o) {
      const uint32_t child = nd.firstChild + o;
      parent_[child] = node;
      for (int k = 0; k < 3; ++k)
        for (int side = 0; side < 2; ++side) {
          const int face = 2 * k + side;
          uint32_t r;
          if (int((o >> k) & 1) != side) {
            r = nd.firstChild + (o ^ (1u << k));  // the sibling across an inner face
          } else {
            const uint32_t up = ropes_[node][size_t(face)];
            // Across the parent's face: the parent's neighbour, or its child facing this one.
            r = (up == kNone || tree.node(up).leaf()) ? up
                                                      : tree.node(up).firstChild + (o ^ (1u << k));
          }
          ropes_[child][size_t(face)] = r;
        }
      stack.push_back(child);
    }
  }
}

uint32_t OctreeRopes::descend(const Octree& tree, uint32_t node, const glm::dvec3& p,
                              const glm::dvec3& dir) {
  for (;;) {
    const Octree::Node& nd = tree.node(node);
    if (nd.leaf()) return node;
    const glm::dvec3 mid = tree.nodeBox(nd.firstChild).hi;  // octant 0 ends at the split
    uint32_t o = 0;
    for (int k = 0; k < 3; ++k)
      if (p[k] > mid[k] || (p[k] == mid[k] && dir[k] >= 0.0)) o |= 1u << k;
    node = nd.firstChild + o;
  }
}

uint32_t OctreeRopes::locate(const Octree& tree, uint32_t hint, const glm::dvec3& p,
                             const glm::dvec3& dir, int* climbed) const {
  // A box claims p as descend() would: half-open on each axis, the closed side facing against
  // dir. So the leaf found does not depend on the hint (the previous ray).
  const auto claims = [&](const Bounds& b) {
    for (int k = 0; k < 3; ++k) {
      const bool afterLo = p[k] > b.lo[k] || (p[k] == b.lo[k] && dir[k] >= 0.0);
      const bool beforeHi = p[k] < b.hi[k] || (p[k] == b.hi[k] && dir[k] < 0.0);
      if (!afterLo || !beforeHi) return false;
    }
    return true;
  };
  uint32_t node = hint;
  int up = 0;
  while (parent_[node] != kNone && !claims(tree.nodeBox(node))) {
    node = parent_[node];
    ++up;
  }
  if (climbed) *climbed = up;
  return descend(tree, node, p, dir);
}

}  // namespace lzb::localz
