#pragma once
// Tests' shorthand for a camera at `position` looking at `lookAt`.
#include "src/core/camera.hpp"

namespace lzb::testing_util {

inline Camera lookAtCamera(const glm::dvec3& position, const glm::dvec3& lookAt, double nearPlane,
                           double farPlane, int width, int height, double fovyDegrees = 45.0) {
  CameraSpec spec;
  spec.position = position;
  spec.lookAt = lookAt;
  spec.nearPlane = nearPlane;
  spec.farPlane = farPlane;
  spec.fovyDegrees = fovyDegrees;
  return Camera(spec, width, height);
}

}  // namespace lzb::testing_util
