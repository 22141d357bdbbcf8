#include "src/sqrt5/placements.hpp"

#include <cmath>

#include "src/core/error.hpp"
#include "src/core/visible_placements.hpp"

namespace lzb::sqrt5 {

std::vector<SampledPlacement> visiblePlacements(const Scene& scene, const std::vector<Bounds>& meshBounds,
                                         const Camera& camera) {
  std::vector<SampledPlacement> out;
  const auto add = [&](uint32_t node, const glm::dmat4& world, uint64_t idBase, const Bounds& b) {
    require(out.size() < kMaxPlacements, scene.source,
            "more than 2^22 visible placements: too instanced for sqrt5's per-placement sampling");
    out.push_back({node, world, idBase, b});
  };
  forEachVisiblePlacement(scene, meshBounds, camera.frustum(), add);
  return out;
}

double nearestDistance(const Bounds& b, const glm::dvec3& eye) {
  return glm::length(glm::max(glm::max(b.lo - eye, eye - b.hi), glm::dvec3(0.0)));
}

double farthestDistance(const Bounds& b, const glm::dvec3& eye) {
  return glm::length(glm::max(glm::abs(b.lo - eye), glm::abs(b.hi - eye)));
}

}  // namespace lzb::sqrt5
