#pragma once
// The draw lists (src/zbuffer/draw_lists.hpp) of LZB's z-buffer passes, deduplicated per
// expanded triangle with the rendering bit (TriangleSet):
//  - near scene (step 3): triangles of the culled leaves in front of the partition plane;
//  - PVL (steps 5, lazy and later): triangles of the leaves the rays traversed.
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "raycast/lzb/lzb_accel.hpp"
#include "raycast/lzb/lzb_cull.hpp"
#include "raycast/lzb/lzb_ray_walk.hpp"
#include "src/zbuffer/draw_lists.hpp"

namespace lzb::localz {

// Near scene: triangles of culled leaves with depthMin < zClip. With farTriangles given, also
// counts the triangle entries of culled leaves with depthMax > zClip (the far scene in the
// frustum; a triangle listed by k such leaves counts k times: the distinct count would cost
// ~4 ms per frame on the 1.8 M-triangle city, for a report figure).
DrawLists nearScene(const LzbAccel& accel, const CulledScene& culled, double zClip, int threads,
                    uint64_t* farTriangles = nullptr);
// The PVL: the union of the parts' leaves, their triangles once each.
DrawLists mergePvl(const LzbAccel& accel, std::span<const PvlPart> parts, int threads);

}  // namespace lzb::localz
