#pragma once
// Axis-aligned boxes in double precision (world space may be far from the origin).
#include <algorithm>
#include <limits>
#include <glm/glm.hpp>

namespace lzb {

struct Bounds {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void extend(const Bounds& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  glm::dvec3 center() const { return 0.5 * (lo + hi); }
  glm::dvec3 extent() const { return hi - lo; }
  double diagonal() const { return empty() ? 0.0 : glm::length(hi - lo); }
  bool contains(const glm::dvec3& p) const {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
  }
  bool overlaps(const Bounds& b) const {
    return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y &&
           lo.z <= b.hi.z && b.lo.z <= hi.z;
  }
  glm::dvec3 corner(int i) const {
    return {i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z};
  }
  // The box around this box transformed by an affine matrix.
  Bounds transformed(const glm::dmat4& m) const {
    Bounds out;
    if (empty()) return out;
    for (int i = 0; i < 8; ++i) out.extend(glm::dvec3(m * glm::dvec4(corner(i), 1.0)));
    return out;
  }
};

}  // namespace lzb
