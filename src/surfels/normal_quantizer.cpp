#include "src/surfels/normal_quantizer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace lzb::surfels {

namespace {

using Tri = std::array<glm::dvec3, 3>;  // counter-clockwise seen from outside the sphere

double det(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return glm::dot(glm::cross(a, b), c);
}

// The four children of a spherical triangle: corners 0, 1, 2 and the centre (child 3), each
// counter-clockwise like its parent.
std::array<Tri, 4> children(const Tri& t) {
  const glm::dvec3 m01 = glm::normalize(t[0] + t[1]), m12 = glm::normalize(t[1] + t[2]),
                   m20 = glm::normalize(t[2] + t[0]);
  return {Tri{t[0], m01, m20}, Tri{m01, t[1], m12}, Tri{m20, m12, t[2]}, Tri{m01, m12, m20}};
}

// Which child's cone holds a (a inside t's cone): a corner child when a lies on its side of the
// plane through the origin and the child's inner edge, else the centre.
int childHolding(const Tri& t, const glm::dvec3& a) {
  const glm::dvec3 m01 = t[0] + t[1], m12 = t[1] + t[2], m20 = t[2] + t[0];  // length is irrelevant
  if (det(m01, m20, a) >= 0.0) return 0;
  if (det(m12, m01, a) >= 0.0) return 1;
  if (det(m20, m12, a) >= 0.0) return 2;
  return 3;
}

const Tri kFirstOctant = {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)};

glm::dvec3 faceNormal(const Tri& t) {
  return glm::normalize(glm::cross(t[1] - t[0], t[2] - t[0]));
}

glm::dvec3 applySigns(glm::dvec3 v, uint32_t signs) {
  for (int k = 0; k < 3; ++k)
    if (signs >> k & 1) v[k] = -v[k];
  return v;
}

// Visits every triangle of the first octant at `levels` with its path.
template <class F>
void forEachTriangle(const Tri& t, int levels, uint32_t path, F&& f) {
  if (levels == 0) {
    f(t, path);
    return;
  }
  const std::array<Tri, 4> c = children(t);
  for (uint32_t k = 0; k < 4; ++k) forEachTriangle(c[k], levels - 1, path << 2 | k, f);
}

double angle(const glm::dvec3& a, const glm::dvec3& b) {
  // atan2 of |a x b| and a . b: accurate for tiny angles, where acos is not.
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

}  // namespace

OctahedralNormals::OctahedralNormals(int levels) : levels_(levels) {
  if (levels < 0 || levels > kMaxLevels)
    throw std::invalid_argument("OctahedralNormals: levels must be in [0, 10]");
  table_.resize(codes());
  forEachTriangle(kFirstOctant, levels, 0, [&](const Tri& t, uint32_t path) {
    const glm::dvec3 n = faceNormal(t);
    for (const glm::dvec3& corner : t) bound_ = std::max(bound_, angle(n, corner));
    for (uint32_t signs = 0; signs < 8; ++signs)
      table_[signs << 2 * levels | path] = glm::vec3(applySigns(n, signs));
  });
}

uint32_t OctahedralNormals::encode(const glm::dvec3& n) const {
  const uint32_t signs = uint32_t(n.x < 0.0) | uint32_t(n.y < 0.0) << 1 | uint32_t(n.z < 0.0) << 2;
  glm::dvec3 a = glm::abs(n);
  if (!(a.x + a.y + a.z > 0.0)) a = glm::dvec3(1.0);
  Tri t = kFirstOctant;
  uint32_t path = 0;
  for (int l = 0; l < levels_; ++l) {
    const int k = childHolding(t, a);
    path = path << 2 | uint32_t(k);
    t = children(t)[size_t(k)];
  }
  return signs << 2 * levels_ | path;
}

glm::dvec3 OctahedralNormals::decodeByDescent(uint32_t code) const {
  Tri t = kFirstOctant;
  for (int l = levels_ - 1; l >= 0; --l) t = children(t)[code >> (2 * l) & 3];
  return applySigns(faceNormal(t), octant(code));
}

}  // namespace lzb::surfels
