#pragma once
// What a z-buffer pass draws: lists of triangles per (scene node, placement), each expanded
// triangle once, in ascending expanded-ID order (NativeRasterizer::draw,
// TriangleRasterizer::drawList).
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace lzb {

struct DrawList {
  uint32_t node = 0;
  glm::dmat4 world{1.0};  // node frame -> world
  uint64_t idBase = 0;    // expanded ID of the node's triangle 0 at this placement
  std::vector<uint32_t> triangles;  // ascending
};

struct DrawLists {
  std::vector<DrawList> lists;  // ascending idBase
  uint64_t triangles = 0;       // total (each expanded triangle once)
  uint64_t leaves = 0;          // distinct (placement, octree leaf) pairs they came from
  // Whether expanded triangle `id` is listed.
  bool contains(uint64_t id) const;
};

}  // namespace lzb
