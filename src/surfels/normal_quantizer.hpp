#pragma once
// Hierarchical octahedral normal quantization (Tobor et al., section 4.2).
//
// The unit sphere is the octahedron through (+-1, 0, 0), (0, +-1, 0), (0, 0, +-1), its faces
// subdivided `levels` times into 4 (edge midpoints pushed back onto the sphere). A normal's code
// is its 3 sign bits (the octant: bit 0 x < 0, bit 1 y < 0, bit 2 z < 0) followed by 2 bits per
// level naming the child triangle whose cone holds it: code = signs << 2 levels | path. Encoding
// descends the subdivision from the octant's triangle, one point-in-pyramid test per child (three
// determinants), so it costs O(levels) = O(log n) for n samples and no trigonometry. A code's
// normal is the normal of its flat triangle (the paper's sample), kept in a table ordered by code
// and also computable by the same descent (decodeByDescent).
//
// Bound: every direction lies in the cone of the triangle it is encoded to, and the largest angle
// between a triangle's normal and the points of its cone is the angle to one of its corners (a
// spherical cap is convex), so maxErrorBound() = the maximum of those corner angles over all
// triangles of the level; the tests check measured errors against it, level by level.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace lzb::surfels {

class OctahedralNormals {
 public:
  static constexpr int kMaxLevels = 10;  // 23-bit codes

  explicit OctahedralNormals(int levels);

  int levels() const { return levels_; }
  int bits() const { return 3 + 2 * levels_; }
  uint32_t codes() const { return uint32_t(1) << bits(); }

  // The code of direction n (any length > 0; the zero vector gets the code of (1, 1, 1)).
  uint32_t encode(const glm::dvec3& n) const;
  // The quantized unit normal of a code (table look-up).
  const glm::vec3& decode(uint32_t code) const { return table_[code]; }
  // The same normal recomputed by descending the subdivision (no table).
  glm::dvec3 decodeByDescent(uint32_t code) const;
  // The largest angle, in radians, between any unit vector and the normal of its code.
  double maxErrorBound() const { return bound_; }
  // The octant of a code (its sign bits).
  uint32_t octant(uint32_t code) const { return code >> (2 * levels_); }
  // The code without its sign bits (2 bits per level).
  uint32_t path(uint32_t code) const { return code & ((uint32_t(1) << 2 * levels_) - 1); }

 private:
  int levels_;
  std::vector<glm::vec3> table_;
  double bound_ = 0.0;
};

}  // namespace lzb::surfels
