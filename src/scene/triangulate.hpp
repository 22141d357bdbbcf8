#pragma once
// Splits polygons from mesh files into triangles. Our own, because assimp's Triangulate step
// aborts the process (ai_assert) on some malformed files instead of reporting them.
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace lzb {

// Appends n - 2 triangles (index triples into `polygon`, keeping its winding) for a polygon of
// n >= 3 vertices given in order. Simple polygons, convex or not, are split by ear clipping in
// the plane of their Newell normal; what cannot be clipped cleanly (self-intersecting, collinear)
// is split anyway so nothing is lost silently: degenerate pieces are dropped and counted later.
void triangulatePolygon(std::span<const glm::dvec3> polygon,
                        std::vector<std::array<uint32_t, 3>>& triangles);

}  // namespace lzb
