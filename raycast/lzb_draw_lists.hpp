#pragma once
// What the z-buffer passes of LZB draw: lists of triangles per (node, placement), deduplicated
// per expanded triangle with the rendering bit (TriangleSet) and in ascending expanded-ID order,
// ready for TriangleRasterizer::drawList.
//  - near scene (step 3): triangles of the culled leaves in front of the partition plane;
//  - PVL (steps 5, lazy and later): triangles of the leaves the rays traversed.
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "raycast/lzb_accel.hpp"
#include "raycast/lzb_cull.hpp"
#include "raycast/lzb_ray_walk.hpp"

namespace lzb {

struct DrawList {
  uint32_t node = 0;
  glm::dmat4 world{1.0};
  uint64_t idBase = 0;
  std::vector<uint32_t> triangles;  // ascending
};

struct DrawLists {
  std::vector<DrawList> lists;  // ascending idBase
  uint64_t triangles = 0;       // total (each expanded triangle once)
  uint64_t leaves = 0;          // distinct (placement, leaf) pairs they came from
  // Whether expanded triangle `id` is listed.
  bool contains(uint64_t id) const;
};

// Near scene: triangles of culled leaves with depthMin < zClip. With farTriangles given, also
// counts the triangle entries of culled leaves with depthMax > zClip (the far scene in the
// frustum; a triangle listed by k such leaves counts k times: the distinct count would cost
// ~4 ms per frame on the 1.8 M-triangle city, for a report figure).
DrawLists nearScene(const LzbAccel& accel, const CulledScene& culled, double zClip, int threads,
                    uint64_t* farTriangles = nullptr);
// The PVL: the union of the parts' leaves, their triangles once each.
DrawLists mergePvl(const LzbAccel& accel, std::span<const PvlPart> parts, int threads);

}  // namespace lzb
