#include "src/octree/octree.hpp"

#include <stdexcept>

namespace lzb {

nlohmann::json OctreeStats::toJson() const {
  return {{"nodes", nodes},
          {"leaves", leaves},
          {"non_empty_leaves", nonEmptyLeaves},
          {"max_depth", maxDepth},
          {"entries", entries},
          {"mean_leaf_entries", meanLeafEntries},
          {"max_leaf_entries", maxLeafEntries},
          {"growth_stopped_leaves", growthStoppedLeaves},
          {"skipped_triangles", skippedTriangles},
          {"memory_bytes", memoryBytes},
          {"build_seconds", buildSeconds}};
}

Frustum frustumToNodeSpace(const Frustum& world, const glm::dmat4& nodeToWorld) {
  // (n, d) . (M p) = (M^T (n, d)) . p for a node-space point p.
  const glm::dmat4 t = glm::transpose(nodeToWorld);
  Frustum f;
  for (size_t i = 0; i < world.planes.size(); ++i) {
    const glm::dvec4 q = t * glm::dvec4(world.planes[i].n, world.planes[i].d);
    const double len = glm::length(glm::dvec3(q));
    const double s = len > 0.0 && std::isfinite(len) ? 1.0 / len : 1.0;
    f.planes[i] = Plane{glm::dvec3(q) * s, q.w * s};
  }
  return f;
}

std::vector<Bounds> Octree::instanceBoxes(const Scene& scene, uint32_t node) {
  if (node >= scene.nodes.size() || scene.nodeBounds.size() != scene.nodes.size())
    throw std::invalid_argument("Octree: node out of range or Scene::finalize() not run");
  std::vector<Bounds> boxes;
  boxes.reserve(scene.nodes[node].instances.size());
  for (const Instance& inst : scene.nodes[node].instances)
    boxes.push_back(scene.nodeBounds.at(inst.node).transformed(inst.transform));
  return boxes;
}

Octree::Octree(const Scene& scene, uint32_t node, const OctreeParams& params)
    : Octree(scene.nodes.at(node).mesh, instanceBoxes(scene, node), params) {}

void Octree::computeStats() {
  OctreeStats s;
  s.nodes = nodes_.size();
  for (uint32_t i = 0; i < nodes_.size(); ++i) {
    const Node& n = nodes_[i];
    if (!n.leaf()) continue;
    ++s.leaves;
    s.maxDepth = std::max(s.maxDepth, int(depths_[i]));
    if (n.count == 0) continue;
    ++s.nonEmptyLeaves;
    s.entries += n.count;
    s.maxLeafEntries = std::max<uint64_t>(s.maxLeafEntries, n.count);
  }
  s.meanLeafEntries = s.nonEmptyLeaves ? double(s.entries) / double(s.nonEmptyLeaves) : 0.0;
  s.memoryBytes = nodes_.capacity() * sizeof(Node) + boxes_.capacity() * sizeof(Bounds) +
                  depths_.capacity() * sizeof(uint8_t) + entries_.capacity() * sizeof(uint32_t);
  s.growthStoppedLeaves = stats_.growthStoppedLeaves;
  s.skippedTriangles = stats_.skippedTriangles;
  s.buildSeconds = stats_.buildSeconds;
  stats_ = s;
}

}  // namespace lzb
