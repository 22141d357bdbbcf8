#include "src/sampletree/cube_projection.hpp"

#include <algorithm>

namespace lzb::sampletree {

CubeProjector::CubeProjector(const Camera& camera)
    : eye_(camera.position()),
      right_(camera.right()),
      up_(camera.up()),
      forward_(camera.forward()),
      near_(camera.nearPlane()),
      cx_(0.5 * camera.width()),
      cy_(0.5 * camera.height()),
      ax_(0.5 * camera.width() / camera.tanHalfX()),
      ay_(0.5 * camera.height() / camera.tanHalfY()) {
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 c(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    dr_[size_t(k)] = glm::dot(c, right_);
    du_[size_t(k)] = glm::dot(c, up_);
    df_[size_t(k)] = glm::dot(c, forward_);
  }
}

ScreenRect CubeProjector::rect(const glm::dvec3& lo, double side) const {
  const glm::dvec3 d = lo - eye_;
  const double r = glm::dot(d, right_), u = glm::dot(d, up_), f = glm::dot(d, forward_);
  ScreenRect out{1e300, 1e300, -1e300, -1e300, false};
  for (size_t k = 0; k < 8; ++k) {
    const double depth = f + side * df_[k];
    out.behind |= !(depth >= near_);
    const double inv = 1.0 / depth;
    const double x = cx_ + ax_ * (r + side * dr_[k]) * inv;
    const double y = cy_ - ay_ * (u + side * du_[k]) * inv;
    out.x0 = std::min(out.x0, x), out.x1 = std::max(out.x1, x);
    out.y0 = std::min(out.y0, y), out.y1 = std::max(out.y1, y);
  }
  return out;
}

}  // namespace lzb::sampletree
