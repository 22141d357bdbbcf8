#pragma once
// Triangle–box overlap by the separating axis theorem (Akenine-Möller, "Fast 3D triangle-box
// overlap testing", 2001): the box is separated from the triangle iff one of 13 axes separates
// their projections: the 3 box normals, the triangle normal and the 9 cross products of a
// triangle edge with a box axis.
//
// Semantics: both shapes are closed, so a triangle that only touches the box (a face, an edge, a
// corner) overlaps it. The box-normal tests compare coordinates directly and are exact; the other
// axes widen the box by a relative band of kTriBoxTolerance times the coordinate magnitudes, so
// rounding can only turn "separated by less than the band" into "overlapping", never the reverse.
// Degenerate triangles (zero-length edges, collinear vertices) need no special case: their zero
// axes project everything to 0 and never separate, and the remaining axes still form a complete
// set for a segment or a point.
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "src/core/bounds.hpp"

namespace lzb {

constexpr double kTriBoxTolerance = 1e-12;

namespace detail {

inline double min3(double a, double b, double c) {
  return std::min(a, std::min(b, c));
}
inline double max3(double a, double b, double c) {
  return std::max(a, std::max(b, c));
}

// True when `axis` separates the triangle (vertices relative to the box centre) from the box of
// half size h; `mag` bounds the coordinate magnitudes, which bound the rounding error.
inline bool separatedOn(const glm::dvec3& axis, const glm::dvec3& v0, const glm::dvec3& v1,
                        const glm::dvec3& v2, const glm::dvec3& h, const glm::dvec3& mag) {
  const double p0 = glm::dot(axis, v0), p1 = glm::dot(axis, v1), p2 = glm::dot(axis, v2);
  const glm::dvec3 a = glm::abs(axis);
  const double r = glm::dot(a, h) + kTriBoxTolerance * glm::dot(a, mag);
  return min3(p0, p1, p2) > r || max3(p0, p1, p2) < -r;
}

}  // namespace detail

// True when the closed triangle (a, b, c) and the closed box share a point (see above).
inline bool triBoxOverlap(const Bounds& box, const glm::dvec3& a, const glm::dvec3& b,
                          const glm::dvec3& c) {
  // Box normals: the triangle's bounding box against the box, exact (and false for empty boxes).
  for (int k = 0; k < 3; ++k) {
    if (!(detail::min3(a[k], b[k], c[k]) <= box.hi[k])) return false;
    if (!(detail::max3(a[k], b[k], c[k]) >= box.lo[k])) return false;
  }
  const glm::dvec3 centre = 0.5 * (box.lo + box.hi), h = 0.5 * (box.hi - box.lo);
  const glm::dvec3 v0 = a - centre, v1 = b - centre, v2 = c - centre;
  const glm::dvec3 mag =
      glm::max(glm::max(glm::abs(centre) + h, glm::abs(a)), glm::max(glm::abs(b), glm::abs(c)));
  const glm::dvec3 e0 = v1 - v0, e1 = v2 - v1, e2 = v0 - v2;
  // Triangle normal: any direction is a valid candidate axis, so rounding in it is harmless.
  if (detail::separatedOn(glm::cross(e0, e1), v0, v1, v2, h, mag)) return false;
  // Edge x box axis: cross(e, x) = (0, e.z, -e.y), cross(e, y) = (-e.z, 0, e.x),
  // cross(e, z) = (e.y, -e.x, 0), formed exactly from the edge components.
  for (const glm::dvec3& e : {e0, e1, e2}) {
    if (detail::separatedOn({0.0, e.z, -e.y}, v0, v1, v2, h, mag)) return false;
    if (detail::separatedOn({-e.z, 0.0, e.x}, v0, v1, v2, h, mag)) return false;
    if (detail::separatedOn({e.y, -e.x, 0.0}, v0, v1, v2, h, mag)) return false;
  }
  return true;
}

// Akenine-Möller's original signature: box by centre and half size, triangle as 3 vertices.
inline bool triBoxOverlap(const glm::dvec3& boxCentre, const glm::dvec3& boxHalfSize,
                          const glm::dvec3 tri[3]) {
  return triBoxOverlap(Bounds{boxCentre - boxHalfSize, boxCentre + boxHalfSize}, tri[0], tri[1],
                       tri[2]);
}

}  // namespace lzb
