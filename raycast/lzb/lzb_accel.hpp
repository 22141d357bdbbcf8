#pragma once
// The LZB preprocessing (paper, section II.A and III.B.1): per scene node an octree over its
// triangles and instances, an Octree-o (the K largest triangles of every leaf as its static
// local occluders), the per-leaf base visibility of the dynamic occluder selection, and the
// neighbour links of the coherent walk. Instanced nodes are built once, whatever their use count.
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "raycast/lzb/lzb_octree_ropes.hpp"
#include "src/core/affine.hpp"
#include "src/core/scene.hpp"
#include "src/octree/octree.hpp"

namespace lzb::localz {

// normal x area of triangle t, node frame, in double: its length is the triangle's area.
inline glm::dvec3 areaVector(const Mesh& mesh, uint32_t t) {
  const glm::dvec3 a(mesh.vertex(t, 0)), b(mesh.vertex(t, 1)), c(mesh.vertex(t, 2));
  return 0.5 * glm::cross(b - a, c - a);
}
// The same in float: visibility = -dot(v, areaNormal) (paper, equation 1). Derived from the
// vertices where the walk tests it (12 bytes a triangle less than storing it).
inline glm::vec3 areaNormal(const Mesh& mesh, uint32_t t) {
  return glm::vec3(areaVector(mesh, t));
}

struct LzbAccelParams {
  uint32_t leafEntries = 150;        // nodes with triangles (the paper: <= 150 per leaf)
  uint32_t instanceLeafEntries = 8;  // nodes with at least as many instances as triangles
  int maxDepth = 16;
  int occluders = 5;        // K: static local occluders kept per leaf
  double baseFacing = 0.5;  // the paper's preset -v.n of the base visibility
};

class NodeAccel {
 public:
  NodeAccel() = default;
  NodeAccel(const Scene& scene, uint32_t node, const LzbAccelParams& params);

  const Octree& octree() const { return octree_; }
  const OctreeRopes& ropes() const { return ropes_; }
  bool empty() const { return octree_.empty(); }

  // A leaf's entries split by kind (triangle indices; instance indices without kInstanceBit).
  std::span<const uint32_t> leafTriangles(uint32_t leaf) const {
    return span(triBegin_, tris_, leaf);
  }
  std::span<const uint32_t> leafInstances(uint32_t leaf) const {
    return span(instBegin_, insts_, leaf);
  }
  // The leaf's static local occluders: its min(K, count) largest triangles, largest first.
  std::span<const uint32_t> leafOccluders(uint32_t leaf) const {
    return span(occBegin_, occluders_, leaf);
  }
  // The leaf box cut down to the bounds of the leaf's triangles (their boxes intersected with
  // the leaf box, widened by 1e-7 of its diagonal): every triangle point inside the leaf lies in
  // it. Empty for leaves without triangles; an inner node's is the union of its children's.
  // Used for depth ranges, OOR objects and to skip leaves a ray cannot hit anything in.
  const Bounds& contentBox(uint32_t leaf) const { return content_[leaf]; }
  // The box of instance i in this node's frame (its child's bounds, transformed, widened by
  // 1e-7 of its diagonal).
  const Bounds& instanceBox(uint32_t i) const { return instanceBoxes_[i]; }
  // The leaf's triangles that can pass the dynamic selection (area above the base visibility),
  // largest first.
  std::span<const uint32_t> leafDynamicCandidates(uint32_t leaf) const {
    return span(dynBegin_, dynamic_, leaf);
  }
  // Base visibility of the dynamic selection: baseFacing x the mean triangle area of the leaf.
  float baseVisibility(uint32_t leaf) const { return baseVisibility_[leaf]; }
  // Parent frame -> child frame of instance i (the inverse of its transform).
  const Affine& instanceInverse(uint32_t i) const { return inverse_[i]; }
  bool instanceUsable(uint32_t i) const { return usable_[i] != 0; }
  uint64_t memoryBytes() const;

 private:
  static std::span<const uint32_t> span(const std::vector<uint32_t>& begin,
                                        const std::vector<uint32_t>& items, uint32_t leaf) {
    return {items.data() + begin[leaf], begin[leaf + 1] - begin[leaf]};
  }

  Octree octree_;
  OctreeRopes ropes_;
  std::vector<uint32_t> triBegin_, tris_;       // per octree node (+1): triangle entries
  std::vector<uint32_t> instBegin_, insts_;     // per octree node (+1): instance entries
  std::vector<uint32_t> occBegin_, occluders_;  // per octree node (+1): static occluders
  std::vector<uint32_t> dynBegin_, dynamic_;    // per octree node (+1): dynamic candidates
  std::vector<float> baseVisibility_;           // per octree node
  std::vector<Bounds> content_;                 // per octree node
  std::vector<Bounds> instanceBoxes_;           // per instance
  std::vector<Affine> inverse_;                 // per instance
  std::vector<uint8_t> usable_;                 // per instance: finite, invertible transform
};

struct LzbAccelStats {
  double seconds = 0.0;
  uint64_t octrees = 0, octreeNodes = 0, leaves = 0, occluders = 0, memoryBytes = 0;
};

class LzbAccel {
 public:
  // scene: finalized, outlives this. Builds every node's structures (octree builds run their
  // own OpenMP tasks; nodes go one after the other).
  LzbAccel(const Scene& scene, const LzbAccelParams& params);
  const NodeAccel& node(uint32_t n) const { return nodes_[n]; }
  const Scene& scene() const { return scene_; }
  const LzbAccelParams& params() const { return params_; }
  const LzbAccelStats& stats() const { return stats_; }
  // Total instances over all nodes, and the first index of node n's instances in that numbering.
  uint64_t instanceSlots() const { return instanceSlotBegin_.back(); }
  uint64_t instanceSlot(uint32_t node, uint32_t instance) const {
    return instanceSlotBegin_[node] + instance;
  }

 private:
  const Scene& scene_;
  LzbAccelParams params_;
  std::vector<NodeAccel> nodes_;
  std::vector<uint64_t> instanceSlotBegin_;
  LzbAccelStats stats_;
};

}  // namespace lzb::localz
