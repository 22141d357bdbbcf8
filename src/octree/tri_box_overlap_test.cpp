#include "src/octree/tri_box_overlap.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace lzb {
namespace {

using Polygon = std::vector<glm::dvec3>;

// Sutherland–Hodgman against one axis plane, keeping the closed side (points on the plane stay).
Polygon clipAxis(const Polygon& in, int axis, double value, bool keepAbove) {
  Polygon out;
  const auto dist = [&](const glm::dvec3& p) {
    return keepAbove ? p[axis] - value : value - p[axis];
  };
  for (size_t i = 0; i < in.size(); ++i) {
    const glm::dvec3 &a = in[i], &b = in[(i + 1) % in.size()];
    const double da = dist(a), db = dist(b);
    if (da >= 0.0) out.push_back(a);
    if ((da >= 0.0) != (db >= 0.0)) {
      glm::dvec3 p = a + (da / (da - db)) * (b - a);
      p[axis] = value;  // exactly on the plane, so the opposite clip of this axis keeps it
      out.push_back(p);
    }
  }
  return out;
}

// Exact-up-to-rounding reference: overlap iff the triangle clipped to the box is non-empty.
bool clipOverlap(const Bounds& box, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  Polygon poly{a, b, c};
  for (int k = 0; k < 3 && !poly.empty(); ++k) {
    poly = clipAxis(poly, k, box.lo[k], true);
    poly = clipAxis(poly, k, box.hi[k], false);
  }
  return !poly.empty();
}

// True when a dense barycentric sample of the triangle has a point in the closed box.
bool sampleInBox(const Bounds& box, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  constexpr int kSteps = 24;
  for (int i = 0; i <= kSteps; ++i)
    for (int j = 0; i + j <= kSteps; ++j) {
      const double u = double(i) / kSteps, v = double(j) / kSteps;
      if (box.contains(a + u * (b - a) + v * (c - a))) return true;
    }
  return false;
}

Bounds grown(const Bounds& b, double d) {
  return {b.lo - d, b.hi + d};
}

struct OverlapCase {
  Bounds box;
  glm::dvec3 a, b, c;
};

// Checks one case against sampling and clipping; `exact` asks agreement with clipping whenever
// clipping reports overlap (inputs on a coarse dyadic grid make the SAT arithmetic exact).
void check(const OverlapCase& k, bool exact, int& disagreements) {
  const bool got = triBoxOverlap(k.box, k.a, k.b, k.c);
  if (sampleInBox(k.box, k.a, k.b, k.c)) {
    ASSERT_TRUE(got) << "a sample point lies in the box";
  }
  const bool ref = clipOverlap(k.box, k.a, k.b, k.c);
  if (got == ref) return;
  ++disagreements;
  const double scale = 1.0 + glm::length(k.a) + glm::length(k.b) + glm::length(k.c) +
                       glm::length(k.box.lo) + glm::length(k.box.hi);
  const double band = 1e-9 * scale;
  if (got) {
    // A conservative answer only within the band around the box.
    ASSERT_TRUE(clipOverlap(grown(k.box, band), k.a, k.b, k.c)) << "false positive";
  } else {
    ASSERT_FALSE(exact) << "false negative on exact input";
    ASSERT_FALSE(clipOverlap(grown(k.box, -band), k.a, k.b, k.c)) << "false negative";
  }
}

TEST(TriBoxOverlap, AgreesWithClippingOnRandomTriangles) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  int disagreements = 0, overlaps = 0;
  constexpr int kCases = 60000;
  for (int i = 0; i < kCases; ++i) {
    OverlapCase k;
    const glm::dvec3 centre{2 * u(rng), 2 * u(rng), 2 * u(rng)};
    const glm::dvec3 half{0.05 + pos(rng), 0.05 + pos(rng), 0.05 + pos(rng)};
    k.box = {centre - half, centre + half};
    // Triangle sizes from 1e-3 to 10, placed around the box so about half overlap.
    const double size = std::pow(10.0, -3.0 + 4.0 * pos(rng));
    const glm::dvec3 at = centre + 1.5 * glm::dvec3{u(rng), u(rng), u(rng)} * (half + 0.2 * size);
    k.a = at + size * glm::dvec3{u(rng), u(rng), u(rng)};
    k.b = at + size * glm::dvec3{u(rng), u(rng), u(rng)};
    k.c = at + size * glm::dvec3{u(rng), u(rng), u(rng)};
    switch (i % 6) {
      case 1:
        k.b = k.a;
        break;  // zero-length edge
      case 2:
        k.c = k.a + 0.37 * (k.b - k.a);
        break;  // collinear
      case 3:
        k.a.z = k.b.z = k.c.z = at.z;
        break;  // axis-aligned plane
      case 4:
        k.a.y = k.b.y = k.c.y = k.box.hi.y;
        break;  // in a box face plane
      default:
        break;
    }
    check(k, false, disagreements);
    if (testing::Test::HasFatalFailure()) return;
    overlaps += triBoxOverlap(k.box, k.a, k.b, k.c);
  }
  EXPECT_GT(overlaps, kCases / 5);
  EXPECT_LT(overlaps, kCases * 4 / 5);
  EXPECT_LT(disagreements, kCases / 1000);
}

TEST(TriBoxOverlap, ExactOnDyadicGrid) {
  // Coordinates on a grid of 1/2: many triangles touch a face, an edge or a corner exactly.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> g(-4, 4), side(1, 4);
  int disagreements = 0, touching = 0;
  constexpr int kCases = 60000;
  for (int i = 0; i < kCases; ++i) {
    OverlapCase k;
    const glm::dvec3 lo{0.5 * g(rng), 0.5 * g(rng), 0.5 * g(rng)};
    k.box = {lo, lo + 0.5 * glm::dvec3{side(rng), side(rng), side(rng)}};
    const auto p = [&] { return 0.5 * glm::dvec3{g(rng), g(rng), g(rng)}; };
    k.a = p(), k.b = p(), k.c = p();
    if (i % 5 == 1) k.b = k.a;
    if (i % 5 == 2) k.a.x = k.b.x = k.c.x = k.box.lo.x;
    check(k, true, disagreements);
    if (testing::Test::HasFatalFailure()) return;
    touching +=
        triBoxOverlap(k.box, k.a, k.b, k.c) && !clipOverlap(grown(k.box, -1e-6), k.a, k.b, k.c);
  }
  EXPECT_GT(touching, 100) << "the grid should produce many touching cases";
  EXPECT_LT(disagreements, kCases / 100);
}

const Bounds kUnit{glm::dvec3(0.0), glm::dvec3(1.0)};

TEST(TriBoxOverlap, TouchingFaceCountsAndAHairAwayDoesNot) {
  const glm::dvec3 a{0.2, 0.2, 1.0}, b{0.8, 0.2, 1.0}, c{0.5, 0.8, 1.0};
  EXPECT_TRUE(triBoxOverlap(kUnit, a, b, c));
  const glm::dvec3 up{0.0, 0.0, 1e-9};
  EXPECT_FALSE(triBoxOverlap(kUnit, a + up, b + up, c + up));
  // A face-plane triangle that only shares the box's corner region from outside the face.
  EXPECT_FALSE(triBoxOverlap(kUnit, {1.1, 0.2, 1.0}, {1.8, 0.2, 1.0}, {1.5, 0.8, 1.0}));
}

TEST(TriBoxOverlap, TouchingAlongABoxEdgeThroughTheTriangleNormal) {
  // The plane x + y = 2 touches the unit box only along its edge x = y = 1.
  const glm::dvec3 a{2.0, 0.0, -1.0}, b{0.0, 2.0, -1.0}, c{1.0, 1.0, 3.0};
  EXPECT_TRUE(triBoxOverlap(kUnit, a, b, c));
  const glm::dvec3 dx{1e-9, 0.0, 0.0};
  EXPECT_FALSE(triBoxOverlap(kUnit, a + dx, b + dx, c + dx));
}

TEST(TriBoxOverlap, EdgeTouchingBoxEdgeOnlySeparableByACrossAxis) {
  // The triangle's edge crosses the box edge x = y = 1 at z = 0.5; the triangle tilts away.
  const glm::dvec3 a{0.0, 2.0, 0.5}, b{2.0, 0.0, 0.5}, c{2.0, 2.0, 1.5};
  EXPECT_TRUE(triBoxOverlap(kUnit, a, b, c));
  const glm::dvec3 d{1e-9, 1e-9, 0.0};
  EXPECT_FALSE(triBoxOverlap(kUnit, a + d, b + d, c + d));
  // Box normals and the triangle normal alone would call this an overlap.
  EXPECT_TRUE(clipOverlap(kUnit, a, b, c));
  EXPECT_FALSE(clipOverlap(kUnit, a + d, b + d, c + d));
}

TEST(TriBoxOverlap, CornerTouch) {
  EXPECT_TRUE(triBoxOverlap(kUnit, {1.0, 1.0, 1.0}, {2.0, 1.5, 1.0}, {1.5, 2.0, 3.0}));
  EXPECT_FALSE(triBoxOverlap(kUnit, {1.0, 1.0, 1.0 + 1e-9}, {2.0, 1.5, 1.0}, {1.5, 2.0, 3.0}));
}

TEST(TriBoxOverlap, DegenerateTriangles) {
  // Zero-length edge: a segment through the box, and one passing beside a corner.
  EXPECT_TRUE(triBoxOverlap(kUnit, {-1.0, 0.5, 0.5}, {-1.0, 0.5, 0.5}, {2.0, 0.5, 0.5}));
  EXPECT_FALSE(triBoxOverlap(kUnit, {0.0, 2.1, 0.5}, {0.0, 2.1, 0.5}, {2.1, 0.0, 0.5}));
  EXPECT_TRUE(triBoxOverlap(kUnit, {0.0, 2.0, 0.5}, {0.0, 2.0, 0.5}, {2.0, 0.0, 0.5}));
  // Collinear, distinct vertices.
  EXPECT_TRUE(triBoxOverlap(kUnit, {-1.0, -1.0, -1.0}, {0.5, 0.5, 0.5}, {2.0, 2.0, 2.0}));
  EXPECT_FALSE(triBoxOverlap(kUnit, {-1.0, 0.0, 1.1}, {0.5, 0.5, 1.1}, {2.0, 1.0, 1.1}));
  // A single point, inside, on a face, and outside.
  const glm::dvec3 in{0.5, 0.5, 0.5}, face{0.5, 1.0, 0.5}, out{0.5, 1.0 + 1e-12, 0.5};
  EXPECT_TRUE(triBoxOverlap(kUnit, in, in, in));
  EXPECT_TRUE(triBoxOverlap(kUnit, face, face, face));
  EXPECT_FALSE(triBoxOverlap(kUnit, out, out, out));
}

TEST(TriBoxOverlap, LargeTriangleSlicingTheBoxAndBoxInsideTriangleBounds) {
  EXPECT_TRUE(triBoxOverlap(kUnit, {-100.0, -100.0, 0.5}, {100.0, -100.0, 0.5}, {0.0, 100.0, 0.5}));
  // Bounding boxes overlap, the tilted plane passes beside the box.
  EXPECT_FALSE(triBoxOverlap(kUnit, {-10.0, 0.0, 3.5}, {10.0, 0.0, 3.5}, {0.0, 10.0, -6.5}));
}

TEST(TriBoxOverlap, EmptyBoxAndCentreHalfSignature) {
  EXPECT_FALSE(triBoxOverlap(Bounds{}, {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}));
  const glm::dvec3 tri[3] = {{0.2, 0.2, 1.0}, {0.8, 0.2, 1.0}, {0.5, 0.8, 1.0}};
  EXPECT_TRUE(triBoxOverlap(glm::dvec3(0.5), glm::dvec3(0.5), tri));
  EXPECT_FALSE(triBoxOverlap(glm::dvec3(0.5), glm::dvec3(0.49), tri));
}

TEST(TriBoxOverlap, FarFromOriginKeepsTouching) {
  // Box and triangle near 1e7 (world positions far out); the face touch must survive rounding.
  const glm::dvec3 o{1.0e7, -3.0e7, 2.5e7};
  const Bounds box{o, o + glm::dvec3(0.75)};
  const glm::dvec3 a = o + glm::dvec3{0.75, 0.1, 0.1}, b = o + glm::dvec3{2.0, 0.3, 0.2},
                   c = o + glm::dvec3{1.5, 0.6, 0.7};
  EXPECT_TRUE(triBoxOverlap(box, a, b, c));
  EXPECT_FALSE(triBoxOverlap(box, a + glm::dvec3{0.01, 0, 0}, b, c));
}

}  // namespace
}  // namespace lzb
