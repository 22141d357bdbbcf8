#pragma once
// Neighbour links ("ropes") of an octree, for the coherent ray walk of the final LZB stage: a ray
// goes from leaf to leaf across faces instead of descending from the root for every leaf, and
// starts at the previous ray's start leaf (climbing only as far as needed) instead of the root.
//
// rope(n, face) is the smallest node of size >= n's that touches n's face from outside (Samet's
// equal-or-larger neighbour), kNone at the octree's border. Faces: 2 * axis + (1 for the upper
// side). Memory: 7 uint32 per node.
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "src/octree/octree.hpp"

namespace lzb::localz {

class OctreeRopes {
 public:
  static constexpr uint32_t kNone = ~uint32_t(0);

  OctreeRopes() = default;
  explicit OctreeRopes(const Octree& tree);

  uint32_t parent(uint32_t node) const { return parent_[node]; }
  uint32_t rope(uint32_t node, int face) const { return ropes_[node][size_t(face)]; }

  // The leaf under `from` whose closed box holds p; on a splitting plane the side dir points to
  // (the upper side for a zero component). p is taken as inside `from`.
  static uint32_t descend(const Octree& tree, uint32_t from, const glm::dvec3& p,
                          const glm::dvec3& dir);
  // descend(root) computed from a leaf `hint` (e.g. the previous ray's): climbs to the first
  // ancestor that claims p as descend would, then descends, so the leaf does not depend on the
  // hint. Returns the levels climbed in *climbed.
  uint32_t locate(const Octree& tree, uint32_t hint, const glm::dvec3& p, const glm::dvec3& dir,
                  int* climbed) const;

 private:
  std::vector<uint32_t> parent_;
  std::vector<std::array<uint32_t, 6>> ropes_;
};

}  // namespace lzb::localz
