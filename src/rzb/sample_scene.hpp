#pragma once
// The randomized z-buffer's scene: one DistributionTree per scene node that the root reaches
// (section 7.3). Every node's triangles stay in the node's own frame and tree (so a triangle's ID
// is its instance path's base + its mesh index, and the z-buffer fallback can draw it from the
// node's uploaded mesh); instances become instance entries holding the child's tree and transform.
//
// Instance flattening: an instance of a node that has no triangles (only instances) is replaced
// by that node's instances, composed, while the tree stays under DistributionParams::flattenBudget
// entries. Nested 2 x 2 instancing (the chessboard) then costs one instance level per 6 levels of
// the scene graph when a sample descends.
//
// Dynamic updates go through here so that a change inside an instanced tree reaches the instance
// entries of every tree that references it.
#include <cstdint>
#include <memory>
#include <vector>

#include "src/core/scene.hpp"
#include "src/rzb/distribution_tree.hpp"

namespace lzb::rzb {

struct SceneTreeStats {
  uint64_t trees = 0, nodes = 0, triangles = 0, instanceEntries = 0, memoryBytes = 0;
  int maxDepth = 0;
  double buildSeconds = 0.0;
};

class SampleScene {
 public:
  // scene: finalized, outlives this. Builds trees in parallel (OpenMP, deterministic result).
  SampleScene(const Scene& scene, const DistributionParams& params);

  const Scene& scene() const { return *scene_; }
  const DistributionTree& root() const { return *trees_[scene_->root]; }
  const DistributionTree* tree(uint32_t node) const { return trees_[node].get(); }
  const SceneTreeStats& stats() const { return stats_; }
  const DistributionParams& params() const { return params_; }

  // Dynamic updates (O(tree height) in the tree of `node`, plus one entry update per referencing
  // instance entry up the graph). The triangle must already be in scene.nodes[node].mesh.
  void insertTriangle(uint32_t node, uint32_t meshTriangle);
  void removeTriangle(uint32_t node, uint32_t meshTriangle);
  // A whole object: an instance entry of `child` (which has a tree) in node's tree; returns the
  // entry index for removeInstance. idOffset: the child's expanded ID 0 relative to node's.
  uint32_t insertInstance(uint32_t node, uint32_t child, const glm::dmat4& transform,
                          uint64_t idOffset);
  void removeInstance(uint32_t node, uint32_t entry);
  // Static layout again for every edited tree.
  void compact();

 private:
  DistributionTree& mutableTree(uint32_t node);
  void propagate(uint32_t node);
  std::vector<InstanceRef> flattenInstances(uint32_t node) const;

  const Scene* scene_;
  DistributionParams params_;
  std::vector<std::unique_ptr<DistributionTree>> trees_;  // per scene node (null: no tree)
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> referencedBy_;  // (tree node, entry)
  SceneTreeStats stats_;
};

// An instance entry for child placed by transform (area and length scales, bounds, flags).
InstanceRef makeInstanceRef(const Scene& scene, uint32_t child, const DistributionTree* childTree,
                            const glm::dmat4& transform, uint64_t idOffset);

}  // namespace lzb::rzb
