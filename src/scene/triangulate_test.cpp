#include "src/scene/triangulate.hpp"

#include <gtest/gtest.h>

namespace lzb {
namespace {

double signedAreaZ(const std::vector<glm::dvec3>& p, const std::array<uint32_t, 3>& t) {
  return 0.5 * glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]).z;
}

TEST(Triangulate, TriangleIsKept) {
  std::vector<glm::dvec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  std::vector<std::array<uint32_t, 3>> out;
  triangulatePolygon(p, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], (std::array<uint32_t, 3>{0, 1, 2}));
}

TEST(Triangulate, ConcaveLShapeCoversItsAreaWithItsWinding) {
  // An L of area 3, counter-clockwise in the x-y plane, reflex corner at (1, 1).
  std::vector<glm::dvec3> p = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  std::vector<std::array<uint32_t, 3>> out;
  triangulatePolygon(p, out);
  ASSERT_EQ(out.size(), 4u);
  double area = 0.0;
  for (const auto& t : out) {
    EXPECT_GT(signedAreaZ(p, t), 0.0);  // same winding as the polygon, no flipped ear
    area += signedAreaZ(p, t);
  }
  EXPECT_NEAR(area, 3.0, 1e-12);
}

TEST(Triangulate, ClockwisePolygonKeepsClockwiseWinding) {
  std::vector<glm::dvec3> p = {{0, 2, 0}, {1, 2, 0}, {1, 1, 0}, {2, 1, 0}, {2, 0, 0}, {0, 0, 0}};
  std::vector<std::array<uint32_t, 3>> out;
  triangulatePolygon(p, out);
  ASSERT_EQ(out.size(), 4u);
  double area = 0.0;
  for (const auto& t : out) {
    EXPECT_LT(signedAreaZ(p, t), 0.0);
    area += signedAreaZ(p, t);
  }
  EXPECT_NEAR(area, -3.0, 1e-12);
}

TEST(Triangulate, PolygonInAVerticalPlane) {
  // Concave, in the x-z plane (the projection must drop y, not z).
  std::vector<glm::dvec3> p = {{0, 5, 0}, {4, 5, 0}, {4, 5, 4}, {2, 5, 1}, {0, 5, 4}};
  std::vector<std::array<uint32_t, 3>> out;
  triangulatePolygon(p, out);
  ASSERT_EQ(out.size(), 3u);
  const glm::dvec3 n0 = glm::cross(p[1] - p[0], p[2] - p[0]);
  double area = 0.0;
  for (const auto& t : out) {
    const glm::dvec3 n = glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
    EXPECT_GT(glm::dot(n, n0), 0.0);
    area += 0.5 * glm::length(n);
  }
  EXPECT_NEAR(area, 16.0 - 0.5 * 4 * 3, 1e-12);  // square minus the notch triangle
}

TEST(Triangulate, DegeneratePolygonStillGivesNMinus2Pieces) {
  std::vector<glm::dvec3> p = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {4, 0, 0}};
  std::vector<std::array<uint32_t, 3>> out;
  triangulatePolygon(p, out);
  EXPECT_EQ(out.size(), 3u);  // all collinear: the loader drops and counts them
}

}  // namespace
}  // namespace lzb
