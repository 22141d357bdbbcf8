#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <random>
#include <utility>

#include "src/octree/octree.hpp"
#include "tests/support/random_geometry.hpp"

namespace lzb {
namespace {

using test::randomMesh;
using test::vertex;

constexpr double kInf = std::numeric_limits<double>::infinity();

struct LeafVisit {
  uint32_t leaf;
  double t0, t1;
};

std::vector<LeafVisit> walk(const Octree& tree, const glm::dvec3& o, const glm::dvec3& d, double tMin,
                        double tMax) {
  std::vector<LeafVisit> out;
  tree.traverseRay(o, d, tMin, tMax, [&](uint32_t leaf, double t0, double t1) {
    out.push_back({leaf, t0, t1});
    return true;
  });
  return out;
}

// Independent reference: Liang–Barsky on every non-empty leaf, dividing by the direction and
// testing containment for zero components, then sorted by (entry t, leaf).
std::vector<LeafVisit> bruteForce(const Octree& tree, const glm::dvec3& o, const glm::dvec3& d,
                              double tMin, double tMax) {
  std::vector<LeafVisit> out;
  for (uint32_t leaf : test::nonEmptyLeaves(tree)) {
    const Bounds& b = tree.nodeBox(leaf);
    double t0 = tMin, t1 = tMax;
    bool hit = true;
    for (int k = 0; k < 3 && hit; ++k) {
      if (d[k] == 0.0) {
        hit = o[k] >= b.lo[k] && o[k] <= b.hi[k];
      } else {
        const double a = (b.lo[k] - o[k]) / d[k], c = (b.hi[k] - o[k]) / d[k];
        t0 = std::max(t0, std::min(a, c));
        t1 = std::min(t1, std::max(a, c));
        hit = t0 <= t1;
      }
    }
    if (hit) out.push_back({leaf, t0, t1});
  }
  std::sort(out.begin(), out.end(), [](const LeafVisit& x, const LeafVisit& y) {
    return x.t0 < y.t0 || (x.t0 == y.t0 && x.leaf < y.leaf);
  });
  return out;
}

// Same leaves in the same order with the same intervals (to rounding when `exact` is false).
void expectSameWalk(const std::vector<LeafVisit>& got, const std::vector<LeafVisit>& want, bool exact) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].leaf, want[i].leaf) << "position " << i;
    for (const auto& [x, y] :
         {std::pair(got[i].t0, want[i].t0), std::pair(got[i].t1, want[i].t1)}) {
      if (exact || std::isinf(y)) {
        EXPECT_EQ(x, y) << "position " << i;
      } else {
        EXPECT_NEAR(x, y, 1e-12 * (1.0 + std::abs(y))) << "position " << i;
      }
    }
    EXPECT_LE(got[i].t0, got[i].t1);
    if (i > 0) {
      EXPECT_LE(got[i - 1].t0, got[i].t0) << "not front to back";
    }
  }
}

// A tree whose root is exactly [-1, 1]^3 (two corner triangles pin it), so every splitting
// plane is a dyadic number and rays with unit or zero direction components compute exact t.
Octree dyadicTree(uint32_t maxLeaf) {
  Mesh mesh = randomMesh(4000, 31);
  mesh.add({-1.0f, -1.0f, -1.0f}, {-0.99f, -1.0f, -1.0f}, {-1.0f, -0.99f, -1.0f}, 0);
  mesh.add({1.0f, 1.0f, 1.0f}, {0.99f, 1.0f, 1.0f}, {1.0f, 0.99f, 1.0f}, 0);
  OctreeParams p;
  p.maxLeafEntries = maxLeaf;
  Octree tree(mesh, {}, p);
  EXPECT_EQ(tree.bounds().lo, glm::dvec3(-1.0));
  EXPECT_EQ(tree.bounds().hi, glm::dvec3(1.0));
  return tree;
}

TEST(OctreeRay, RandomRaysVisitExactlyTheLeavesTheyCrossFrontToBack) {
  const Mesh mesh = randomMesh(5000, 32);
  OctreeParams p;
  p.maxLeafEntries = 20;
  const Octree tree(mesh, {}, p);
  std::mt19937_64 rng(32);
  std::uniform_real_distribution<double> u(-1.5, 1.5), unit(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  size_t visited = 0;
  for (int i = 0; i < 1500; ++i) {
    const glm::dvec3 o{u(rng), u(rng), u(rng)};
    glm::dvec3 d{g(rng), g(rng), g(rng)};
    if (i % 4 == 1) d[i % 3] = 0.0;                   // parallel to one family of planes
    if (i % 4 == 2) d[i % 3] = d[(i + 1) % 3] = 0.0;  // along an axis
    const double tMin = i % 3 == 0 ? 0.0 : unit(rng),
                 tMax = i % 3 == 0 ? kInf : tMin + 2.0 * unit(rng);
    const auto got = walk(tree, o, d, tMin, tMax);
    expectSameWalk(got, bruteForce(tree, o, d, tMin, tMax), false);
    if (testing::Test::HasFatalFailure()) return;
    visited += got.size();
  }
  EXPECT_GT(visited, 2000u);
}

TEST(OctreeRay, AxisRaysOnSplittingPlanesSeeBothSides) {
  const Octree tree = dyadicTree(25);
  const double offsets[] = {0.0, 0.5, -0.25, 0.125, 0.3, -0.7, 1.0, -1.0};
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {1.0, -1.0})
      for (double a : offsets)
        for (double b : offsets) {
          glm::dvec3 o, d(0.0);
          o[axis] = -2.0 * sign;
          o[(axis + 1) % 3] = a;
          o[(axis + 2) % 3] = b;
          d[axis] = sign;
          const auto got = walk(tree, o, d, 0.0, kInf);
          expectSameWalk(got, bruteForce(tree, o, d, 0.0, kInf), true);
          if (testing::Test::HasFatalFailure()) return;
          // On the plane y = 0 (a == 0) the ray touches the leaves on both sides of it.
          if (a == 0.0 && b == 0.3) {
            glm::dvec3 off = o;
            off[(axis + 1) % 3] = 1e-6;
            EXPECT_GT(got.size(), walk(tree, off, d, 0.0, kInf).size());
          }
        }
}

TEST(OctreeRay, DiagonalRayThroughNodeCorners) {
  const Octree tree = dyadicTree(25);
  for (const glm::dvec3& d : {glm::dvec3(1, 1, 1), glm::dvec3(-1, 1, -1), glm::dvec3(1, 0, -1)}) {
    const glm::dvec3 o = -2.0 * d;
    const auto got = walk(tree, o, d, 0.0, kInf);
    EXPECT_FALSE(got.empty());
    expectSameWalk(got, bruteForce(tree, o, d, 0.0, kInf), true);
  }
}

TEST(OctreeRay, SubnormalDirectionComponentsAndNonFiniteRays) {
  const Octree tree = dyadicTree(25);
  const glm::dvec3 o{-2.0, 0.1, 0.2};
  for (const glm::dvec3& d : {glm::dvec3(1.0, 1e-310, -3e-320), glm::dvec3(1.0, -4.9e-324, 0.0)}) {
    const auto got = walk(tree, o, d, 0.0, kInf);
    EXPECT_FALSE(got.empty());
    for (const LeafVisit& v : got) EXPECT_FALSE(std::isnan(v.t0) || std::isnan(v.t1));
    expectSameWalk(got, bruteForce(tree, o, d, 0.0, kInf), true);
  }
  EXPECT_TRUE(walk(tree, {NAN, 0.0, 0.0}, {1.0, 0.0, 0.0}, 0.0, kInf).empty());
  EXPECT_TRUE(walk(tree, o, {kInf, 0.0, 0.0}, 0.0, kInf).empty());
  EXPECT_TRUE(walk(tree, o, {1.0, 0.0, 0.0}, 1.0, 0.5).empty());
  EXPECT_TRUE(walk(tree, o, {0.0, 0.0, 0.0}, 0.0, kInf).empty()) << "origin outside the root";
  // A zero direction from inside: the ray is a point, in the leaves containing it.
  const glm::dvec3 at{0.5, 0.1, 0.2}, none(0.0);
  expectSameWalk(walk(tree, at, none, 0.0, kInf), bruteForce(tree, at, none, 0.0, kInf), true);
}

TEST(OctreeRay, VisitorStopsTheWalk) {
  const Octree tree = dyadicTree(25);
  int visits = 0;
  const bool finished = tree.traverseRay({-2.0, 0.1, 0.2}, {1.0, 0.05, 0.0}, 0.0, kInf,
                                         [&](uint32_t, double, double) { return ++visits < 3; });
  EXPECT_FALSE(finished);
  EXPECT_EQ(visits, 3);
  EXPECT_TRUE(tree.traverseRay({-2.0, 0.1, 0.2}, {1.0, 0.05, 0.0}, 0.0, kInf,
                               [](uint32_t, double, double) { return true; }));
}

// Möller–Trumbore in double: the hit distance, if the ray hits the triangle.
std::optional<double> hitTriangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a,
                                  const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (det == 0.0) return std::nullopt;
  const glm::dvec3 s = o - a;
  const double u = glm::dot(s, p) / det;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) / det;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  const double t = glm::dot(e2, q) / det;
  return t >= 0.0 ? std::optional<double>(t) : std::nullopt;
}

TEST(OctreeRay, LazyRayCastingFindsTheNearestHit) {
  // The use in LZB: walk leaves front to back, test their triangles, stop at the first leaf
  // with a hit inside its interval; that must be the nearest hit of all triangles.
  const Mesh mesh = randomMesh(20000, 33);
  const Octree tree(mesh, {}, {});
  std::mt19937_64 rng(33);
  std::uniform_real_distribution<double> u(-0.8, 0.8);
  int hits = 0, leavesVisited = 0;
  for (int i = 0; i < 400; ++i) {
    const glm::dvec3 o = 3.0 * glm::normalize(glm::dvec3{u(rng), u(rng), u(rng)});
    const glm::dvec3 d = glm::dvec3{u(rng), u(rng), u(rng)} * 0.5 - o;
    double nearest = kInf;
    for (uint32_t t = 0; t < mesh.size(); ++t)
      if (auto h = hitTriangle(o, d, vertex(mesh, t, 0), vertex(mesh, t, 1), vertex(mesh, t, 2)))
        nearest = std::min(nearest, *h);
    double found = kInf;
    tree.traverseRay(o, d, 0.0, kInf, [&](uint32_t leaf, double t0, double t1) {
      ++leavesVisited;
      const double eps = 1e-9 * (1.0 + t1);
      for (uint32_t t : tree.leafEntries(leaf))
        if (auto h = hitTriangle(o, d, vertex(mesh, t, 0), vertex(mesh, t, 1), vertex(mesh, t, 2)))
          if (*h >= t0 - eps && *h <= t1 + eps) found = std::min(found, *h);
      return found == kInf;
    });
    if (nearest == kInf) {
      EXPECT_EQ(found, kInf) << "ray " << i;
    } else {
      EXPECT_NEAR(found, nearest, 1e-9) << "ray " << i;
    }
    hits += nearest < kInf;
  }
  EXPECT_GT(hits, 100);
  EXPECT_LT(leavesVisited, 400 * 200);
}

}  // namespace
}  // namespace lzb
