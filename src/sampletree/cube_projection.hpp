#pragma once
// The screen rectangle of an axis-aligned cube, for the traversal's stop rule and the
// approximated-pixel bound, which project ~10^6 cells a frame: a cube's 8 corners differ from
// its lowest by the side along the axes, so their view coordinates are the lowest corner's plus
// per-frame offsets, and only the perspective divide is left per corner (Camera::project
// recomputes all three dot products for each).
#include <array>

#include <glm/glm.hpp>

#include "src/core/camera.hpp"

namespace lzb::sampletree {

struct ScreenRect {
  double x0, y0, x1, y1;  // pixel coordinates, y down (as Camera::project)
  bool behind;            // a corner not in front of the near plane: the rectangle is unbounded
  double area() const { return (x1 - x0) * (y1 - y0); }
};

class CubeProjector {
 public:
  explicit CubeProjector(const Camera& camera);
  // The cube [lo, lo + side]^3.
  ScreenRect rect(const glm::dvec3& lo, double side) const;

 private:
  glm::dvec3 eye_, right_, up_, forward_;
  double near_, cx_, cy_, ax_, ay_;            // x = cx + ax * right / depth, y = cy - ay * up / depth
  std::array<double, 8> dr_, du_, df_;         // corner k's offsets along each axis, unit side
};

}  // namespace lzb::sampletree
