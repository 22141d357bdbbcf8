#pragma once
// The frame's placements: each instance, in the fully instanced scene, of a node with triangles
// (node, world matrix, expanded ID of its triangle 0) whose own bounds meet the frustum. A walk
// of the scene graph in expanded-ID order that drops subtrees outside the frustum, so every rank
// lists the same placements in the same order (sqrt5 and surfels plan their frames on it).
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "src/core/bounds.hpp"
#include "src/core/camera.hpp"
#include "src/core/scene.hpp"

namespace lzb {

// worldBounds: the node's own bounds (meshBounds[node]) in the world.
using PlacementVisitor = std::function<void(uint32_t node, const glm::dmat4& world, uint64_t idBase,
                                            const Bounds& worldBounds)>;

// meshBounds: per node, the bounds of its own triangles in its frame (empty when it has none).
void forEachVisiblePlacement(const Scene& scene, const std::vector<Bounds>& meshBounds,
                             const Frustum& frustum, const PlacementVisitor& visit);

}  // namespace lzb
