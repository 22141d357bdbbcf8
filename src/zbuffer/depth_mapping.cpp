#include "src/zbuffer/depth_mapping.hpp"

#include <cmath>
#include <numbers>

namespace lzb {

glm::dmat4 reversedZProjection(const Camera& camera) {
  const double n = camera.nearPlane(), f = camera.farPlane();
  const double sy = 1.0 / std::tan(camera.fovyDegrees() * std::numbers::pi / 360.0);
  const double sx = sy * double(camera.height()) / double(camera.width());
  glm::dmat4 p(0.0);  // column-major: p[column][row]
  p[0][0] = sx;
  p[1][1] = sy;
  // z_clip = a * z_eye + b with z_eye = -d; w_clip = -z_eye = d.
  p[2][2] = n / (f - n);
  p[3][2] = n * f / (f - n);
  p[2][3] = -1.0;
  return p;
}

float depthStorageScale(double farPlane) {
  int e = 0;
  std::frexp(farPlane, &e);  // farPlane < 2^e
  return std::ldexp(1.0f, -(e + 1));
}

}  // namespace lzb
