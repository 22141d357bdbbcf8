#pragma once
// What a z-buffer pass draws: lists of triangles per (scene node, placement), each expanded
// triangle once, in ascending expanded-ID order (NativeRasterizer::draw,
// TriangleRasterizer::drawList).
#include <cstddef>
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

// Whole placed nodes as draw lists, every triangle 0..m-1 (the placements sqrt5 and surfels draw
// as polygons); each node's list is made on first use and kept.
class WholeNodeLists {
 public:
  // Appends `node`, of `triangles` triangles, placed at (world, idBase).
  void add(DrawLists& lists, uint32_t node, const glm::dmat4& world, uint64_t idBase,
           size_t triangles);

 private:
  std::vector<std::vector<uint32_t>> all_;  // per node, grown on demand
};

}  // namespace lzb
