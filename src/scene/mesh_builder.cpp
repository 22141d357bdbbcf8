#include "src/scene/mesh_builder.hpp"

#include <cmath>

namespace lzb {

namespace {

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

bool MeshBuilder::triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                           Rgba8 color) {
  const glm::vec3 fa(a), fb(b), fc(c);
  // Checked after rounding: a finite double beyond float range becomes Inf.
  if (!finite(glm::dvec3(fa)) || !finite(glm::dvec3(fb)) || !finite(glm::dvec3(fc))) {
    ++stats_.nonFinite;
    return false;
  }
  if (!mesh_.add(fa, fb, fc, color)) {
    ++stats_.degenerate;
    return false;
  }
  ++stats_.loaded;
  return true;
}

void MeshBuilder::quad(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                       const glm::dvec3& d, const glm::dvec3& outward, Rgba8 color) {
  if (glm::dot(glm::cross(b - a, c - a), outward) >= 0.0) {
    triangle(a, b, c, color);
    triangle(a, c, d, color);
  } else {
    triangle(a, c, b, color);
    triangle(a, d, c, color);
  }
}

void MeshBuilder::box(const Bounds& b, Rgba8 color, bool bottom) {
  const glm::dvec3 &l = b.lo, &h = b.hi;
  quad({l.x, l.y, l.z}, {l.x, h.y, l.z}, {l.x, h.y, h.z}, {l.x, l.y, h.z}, {-1, 0, 0}, color);
  quad({h.x, l.y, l.z}, {h.x, h.y, l.z}, {h.x, h.y, h.z}, {h.x, l.y, h.z}, {1, 0, 0}, color);
  quad({l.x, l.y, l.z}, {h.x, l.y, l.z}, {h.x, h.y, l.z}, {l.x, h.y, l.z}, {0, 0, -1}, color);
  quad({l.x, l.y, h.z}, {h.x, l.y, h.z}, {h.x, h.y, h.z}, {l.x, h.y, h.z}, {0, 0, 1}, color);
  quad({l.x, h.y, l.z}, {h.x, h.y, l.z}, {h.x, h.y, h.z}, {l.x, h.y, h.z}, {0, 1, 0}, color);
  if (bottom)
    quad({l.x, l.y, l.z}, {h.x, l.y, l.z}, {h.x, l.y, h.z}, {l.x, l.y, h.z}, {0, -1, 0}, color);
}

}  // namespace lzb
