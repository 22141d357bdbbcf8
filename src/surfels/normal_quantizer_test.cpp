// Hierarchical octahedral normal quantization: codes of the paper's sizes, look-up by descent
// equal to the table, and every level's error within its bound (tight: reached at the corners).
#include "src/surfels/normal_quantizer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace lzb::surfels {
namespace {

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// Random unit vectors and the 26 directions of the cube's faces, edges and corners.
std::vector<glm::dvec3> directions() {
  std::vector<glm::dvec3> out;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int i = 0; i < 200000; ++i)
    out.push_back(glm::normalize(glm::dvec3(g(rng), g(rng), g(rng))));
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) out.push_back(glm::normalize(glm::dvec3(x, y, z)));
  return out;
}

// Points just inside each corner of every triangle of the subdivided first octant (built the way
// the quantizer builds it): they encode to that triangle, at almost its corner's angle.
void nearCorners(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int levels,
                 std::vector<glm::dvec3>& out) {
  if (levels == 0) {
    const glm::dvec3 centre = (a + b + c) / 3.0;
    for (const glm::dvec3& v : {a, b, c}) out.push_back(glm::normalize(v + 1e-9 * (centre - v)));
    return;
  }
  const glm::dvec3 ab = glm::normalize(a + b), bc = glm::normalize(b + c),
                   ca = glm::normalize(c + a);
  nearCorners(a, ab, ca, levels - 1, out);
  nearCorners(ab, b, bc, levels - 1, out);
  nearCorners(ca, bc, c, levels - 1, out);
  nearCorners(ab, bc, ca, levels - 1, out);
}

TEST(OctahedralNormals, CodesHaveThePapersSizes) {
  EXPECT_EQ(OctahedralNormals(4).bits(), 11);  // low-quality collector
  EXPECT_EQ(OctahedralNormals(6).bits(), 15);  // high-quality collector
  EXPECT_EQ(OctahedralNormals(6).codes(), 32768u);
}

TEST(OctahedralNormals, EveryLevelStaysWithinItsBoundAndTheBoundIsReached) {
  double previous = 0.0;
  for (int levels = 0; levels <= 7; ++levels) {
    const OctahedralNormals q(levels);
    std::vector<glm::dvec3> dirs = directions();
    if (levels <= 5) nearCorners({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, levels, dirs);
    double worst = 0.0;
    for (const glm::dvec3& d : dirs) {
      const uint32_t code = q.encode(d);
      ASSERT_LT(code, q.codes());
      worst = std::max(worst, angleBetween(d, glm::dvec3(q.decode(code))));
    }
    const double bound = q.maxErrorBound();
    EXPECT_LE(worst, bound + 1e-6) << "level " << levels;  // float table: 1e-6 rad
    std::printf("level %d (%d-bit codes): bound %.4f degrees, measured %.4f\n", levels, q.bits(),
                bound * 180.0 / M_PI, worst * 180.0 / M_PI);
    if (levels <= 5) {
      EXPECT_GE(worst, (1.0 - 1e-6) * bound) << "level " << levels << ": bound not tight";
    }
    // The bound of the octant's face (level 0) is the angle between (1,1,1) and an axis.
    if (levels == 0) {
      EXPECT_NEAR(bound, std::acos(1.0 / std::sqrt(3.0)), 1e-12);
    }
    // Subdividing halves the triangles' size, and so the error, level by level.
    if (levels >= 2) {
      EXPECT_LT(bound, 0.6 * previous) << "level " << levels;
      EXPECT_GT(bound, 0.4 * previous) << "level " << levels;
    }
    previous = bound;
  }
}

TEST(OctahedralNormals, TableEqualsDescentAndCodesRoundTrip) {
  for (int levels : {0, 1, 4, 6}) {
    const OctahedralNormals q(levels);
    for (uint32_t code = 0; code < q.codes(); ++code) {
      const glm::dvec3 n = q.decodeByDescent(code);
      const glm::vec3& t = q.decode(code);
      EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
      EXPECT_NEAR(glm::length(glm::dvec3(t) - n), 0.0, 1e-6);
      // A sample lies strictly inside its own octant, so it encodes to its own code and the
      // octant's signs are the sample's.
      EXPECT_EQ(q.encode(n), code) << "level " << levels;
      for (int k = 0; k < 3; ++k) EXPECT_EQ(t[k] < 0.0f, bool(q.octant(code) >> k & 1)) << code;
      for (int k = 0; k < 3; ++k) EXPECT_NE(t[k], 0.0f) << code;
    }
  }
}

TEST(OctahedralNormals, EncodingIgnoresLengthAndMapsZeroSafely) {
  const OctahedralNormals q(6);
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.3, -0.8, 0.2));
  EXPECT_EQ(q.encode(d), q.encode(17.0 * d));
  EXPECT_EQ(q.encode(glm::dvec3(0.0)), q.encode(glm::dvec3(1.0)));
}

}  // namespace
}  // namespace lzb::surfels
