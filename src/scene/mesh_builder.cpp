#include "src/scene/mesh_builder.hpp"

#include <cmath>
#include <numbers>

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

void MeshBuilder::sphere(int slices, int stacks, Rgba8 color) {
  const double pi = std::numbers::pi;
  const auto point = [&](int stack, int slice) {
    const double theta = pi * stack / stacks, phi = 2.0 * pi * slice / slices;
    return glm::dvec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                      std::cos(theta));
  };
  // Wound so the normal points away from the centre.
  const auto outward = [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    if (glm::dot(glm::cross(b - a, c - a), a + b + c) >= 0.0)
      triangle(a, b, c, color);
    else
      triangle(a, c, b, color);
  };
  for (int st = 0; st < stacks; ++st)
    for (int sl = 0; sl < slices; ++sl) {
      const glm::dvec3 a = point(st, sl), b = point(st + 1, sl), c = point(st + 1, sl + 1),
                       d = point(st, sl + 1);
      if (st > 0) outward(a, b, d);           // the top pole row is one triangle per slice
      if (st < stacks - 1) outward(b, c, d);  // and so is the bottom one
    }
}

}  // namespace lzb
