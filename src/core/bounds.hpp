#pragma once
// Axis-aligned boxes in double precision (world space may be far from the origin), and the
// slab test of a ray against them (the octree walk's, the pixel cast's box bound).
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <limits>

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

// A ray set up for slab tests. Zero direction components test containment instead of dividing
// (no 0 * inf NaN); subnormal ones, whose reciprocal overflows, divide instead of multiplying.
// t is monotonic in the plane coordinate, so a child's interval always lies inside its parent's.
struct RaySlabs {
  glm::dvec3 o, d, inv{0.0};
  bool zero[3], divide[3];
  RaySlabs(const glm::dvec3& origin, const glm::dvec3& dir) : o(origin), d(dir) {
    for (int k = 0; k < 3; ++k) {
      zero[k] = d[k] == 0.0;
      inv[k] = zero[k] ? 0.0 : 1.0 / d[k];
      divide[k] = !zero[k] && !std::isfinite(inv[k]);
    }
  }
  double at(double x, int k) const { return divide[k] ? (x - o[k]) / d[k] : (x - o[k]) * inv[k]; }
  // Narrows [t0, t1] to the part inside the closed box; false when nothing is left.
  bool clip(const Bounds& b, double& t0, double& t1) const {
    for (int k = 0; k < 3; ++k) {
      if (zero[k]) {
        if (!(o[k] >= b.lo[k] && o[k] <= b.hi[k])) return false;
        continue;
      }
      double enter = at(b.lo[k], k), exit = at(b.hi[k], k);
      if (d[k] < 0.0) std::swap(enter, exit);
      if (enter > t0) t0 = enter;
      if (exit < t1) t1 = exit;
      if (!(t0 <= t1)) return false;
    }
    return true;
  }
};

}  // namespace lzb
