#pragma once
// The frame's objects for --method sqrt5: every (node with triangles, world matrix, ID base) whose
// bounds meet the frustum, in expanded-ID order (the same list on every rank; the walk is
// src/core/visible_placements.hpp's).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "src/core/camera.hpp"
#include "src/core/scene.hpp"

namespace lzb::sqrt5 {

// More visible placements than this are refused (InputError): the list is per frame.
constexpr uint64_t kMaxPlacements = uint64_t(1) << 22;

struct SampledPlacement {
  uint32_t node = 0;
  glm::dmat4 world{1.0};
  uint64_t idBase = 0;
  Bounds bounds;  // world bounds of the node's own surface
};

// meshBounds: per node, the bounds of its own surface (node frame; empty when it has none).
std::vector<SampledPlacement> visiblePlacements(const Scene& scene, const std::vector<Bounds>& meshBounds,
                                         const Camera& camera);

// The nearest and farthest distance from the eye to a box (0 inside it).
double nearestDistance(const Bounds& b, const glm::dvec3& eye);
double farthestDistance(const Bounds& b, const glm::dvec3& eye);

}  // namespace lzb::sqrt5
