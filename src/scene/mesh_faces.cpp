#include "src/scene/mesh_faces.hpp"

#include <algorithm>

namespace lzb {

namespace {

// Geometry whose centre lies farther from the origin than this many times its size is recentred.
constexpr double kFarFactor = 1e3;

}  // namespace

glm::dvec3 storageOrigin(const Bounds& b) {
  if (b.empty()) return glm::dvec3(0.0);
  const glm::dvec3 e = b.extent();
  return glm::length(b.center()) > kFarFactor * std::max({e.x, e.y, e.z}) ? b.center()
                                                                          : glm::dvec3(0.0);
}

glm::dvec3 storedVertex(const glm::dmat4& transform, float x, float y, float z,
                        const glm::dvec3& origin) {
  return glm::dvec3(transform * glm::dvec4(x, y, z, 1.0)) - origin;
}

Rgba8 meanColour(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  glm::vec3 sum(0.0f);
  sum += a;
  sum += b;
  sum += c;
  return packRgb(sum / 3.0f);
}

}  // namespace lzb
