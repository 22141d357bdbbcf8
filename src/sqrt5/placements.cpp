#include "src/sqrt5/placements.hpp"

#include <cmath>

#include "src/core/error.hpp"

namespace lzb::sqrt5 {

namespace {

struct Walk {
  const Scene& scene;
  const std::vector<Bounds>& meshBounds;
  const Frustum frustum;
  std::vector<Placement> out;

  void visit(uint32_t node, const glm::dmat4& world, uint64_t idBase) {
    if (frustum.classify(scene.nodeBounds[node].transformed(world)) == Cull::kOutside) return;
    const Node& n = scene.nodes[node];
    if (!n.mesh.empty()) {
      const Bounds b = meshBounds[node].transformed(world);
      if (frustum.classify(b) != Cull::kOutside) {
        require(out.size() < kMaxPlacements, scene.source,
                "more than 2^22 visible placements: too instanced for sqrt5's per-placement "
                "sampling");
        out.push_back({node, world, idBase, b});
      }
    }
    for (size_t i = 0; i < n.instances.size(); ++i)
      visit(n.instances[i].node, world * n.instances[i].transform,
            idBase + scene.childOffset(node, i));
  }
};

}  // namespace

std::vector<Placement> visiblePlacements(const Scene& scene, const std::vector<Bounds>& meshBounds,
                                         const Camera& camera) {
  Walk w{scene, meshBounds, camera.frustum(), {}};
  w.visit(scene.root, glm::dmat4(1.0), 0);
  return std::move(w.out);
}

double nearestDistance(const Bounds& b, const glm::dvec3& eye) {
  return glm::length(glm::max(glm::max(b.lo - eye, eye - b.hi), glm::dvec3(0.0)));
}

double farthestDistance(const Bounds& b, const glm::dvec3& eye) {
  return glm::length(glm::max(glm::abs(b.lo - eye), glm::abs(b.hi - eye)));
}

}  // namespace lzb::sqrt5
