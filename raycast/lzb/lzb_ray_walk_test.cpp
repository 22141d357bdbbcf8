#include "raycast/lzb/lzb_ray_walk.hpp"

#include <gtest/gtest.h>

#include <random>

#include "raycast/lzb/lzb_accel.hpp"
#include "raycast/lzb/lzb_draw_lists.hpp"
#include "raycast/lzb/lzb_octree_ropes.hpp"
#include "tests/support/brute_force.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/scenes.hpp"

namespace lzb::localz {
namespace {

constexpr LeafTest kTests[] = {LeafTest::kAll, LeafTest::kStatic, LeafTest::kDynamic,
                               LeafTest::kHybrid};
constexpr OctreeWalk kWalks[] = {OctreeWalk::kTopDown, OctreeWalk::kCoherent};

LzbAccelParams smallLeaves() {
  LzbAccelParams p;
  p.leafEntries = 12;  // deep trees: many ropes, many leaves per ray
  p.instanceLeafEntries = 2;
  p.occluders = 2;
  return p;
}

TEST(OctreeRopes, RopesAreEqualOrLargerFaceNeighbours) {
  const Scene scene = test::soupScene(3000, 0.25, 3);
  const LzbAccel accel(scene, smallLeaves());
  const Octree& tree = accel.node(0).octree();
  const OctreeRopes& ropes = accel.node(0).ropes();
  ASSERT_GT(tree.nodeCount(), 200u);
  const Bounds root = tree.bounds();
  size_t checked = 0;
  for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
    const Bounds& b = tree.nodeBox(n);
    for (int k = 0; k < 3; ++k)
      for (int side = 0; side < 2; ++side) {
        const uint32_t r = ropes.rope(n, 2 * k + side);
        const double plane = side ? b.hi[k] : b.lo[k];
        if (r == OctreeRopes::kNone) {
          EXPECT_EQ(plane, side ? root.hi[k] : root.lo[k]) << "node " << n;
          continue;
        }
        const Bounds& rb = tree.nodeBox(r);
        EXPECT_EQ(side ? rb.lo[k] : rb.hi[k], plane) << "node " << n << " face " << 2 * k + side;
        for (int j = 0; j < 3; ++j)
          if (j != k) {
            EXPECT_LE(rb.lo[j], b.lo[j]);
            EXPECT_GE(rb.hi[j], b.hi[j]);
          }
        EXPECT_LE(tree.nodeDepth(r), tree.nodeDepth(n));
        ++checked;
      }
  }
  EXPECT_GT(checked, 1000u);
}

TEST(OctreeRopes, LocateFromAnyHintEqualsDescentFromTheRoot) {
  const Scene scene = test::soupScene(3000, 0.25, 4);
  const LzbAccel accel(scene, smallLeaves());
  const Octree& tree = accel.node(0).octree();
  const OctreeRopes& ropes = accel.node(0).ropes();
  std::vector<uint32_t> leaves;
  for (uint32_t n = 0; n < tree.nodeCount(); ++n)
    if (tree.node(n).leaf()) leaves.push_back(n);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Bounds& root = tree.bounds();
  for (int i = 0; i < 2000; ++i) {
    glm::dvec3 p = root.lo + glm::dvec3(u(rng), u(rng), u(rng)) * root.extent();
    // Every fourth point on a splitting plane of some leaf: the tie rule must agree.
    if (i % 4 == 0) p.x = tree.nodeBox(leaves[size_t(i) % leaves.size()]).lo.x;
    const glm::dvec3 dir(u(rng) - 0.5, i % 3 == 0 ? 0.0 : u(rng) - 0.5, u(rng) - 0.5);
    const uint32_t expected = OctreeRopes::descend(tree, 0, p, dir);
    const uint32_t hint = leaves[size_t(rng() % leaves.size())];
    EXPECT_EQ(ropes.locate(tree, hint, p, dir, nullptr), expected) << i;
  }
}

// Every ray whose exact nearest hit is well inside its triangle gets that triangle into the PVL.
void expectPvlHoldsHits(const Scene& scene, const std::vector<glm::dvec3>& origins,
                        const std::vector<glm::dvec3>& dirs, double tMin) {
  const LzbAccel accel(scene, smallLeaves());
  const auto tris = test::worldTriangles(scene);
  for (LeafTest test : kTests)
    for (OctreeWalk walk : kWalks) {
      RayWalker walker(accel, test, walk);
      size_t checked = 0;
      for (size_t i = 0; i < dirs.size(); ++i) {
        PvlPart part;
        const double t = walker.cast(origins[i], dirs[i], tMin, 1e9, part);
        part.finish();
        const test::BruteHit exact = test::bruteForce(tris, origins[i], dirs[i], tMin, 1e9);
        if (exact.id == kNoId) continue;
        if (exact.margin < 1e-9) continue;  // on an edge: either triangle is right
        // The walk's hit is a real one, so never nearer than the nearest.
        EXPECT_GE(t, exact.t * (1 - 1e-9));
        const DrawLists pvl = mergePvl(accel, std::span<const PvlPart>(&part, 1), 1);
        EXPECT_TRUE(pvl.contains(exact.id))
            << "ray " << i << " test " << int(test) << " walk " << int(walk);
        ++checked;
      }
      EXPECT_GE(checked, 50u);
    }
}

TEST(RayWalker, PvlHoldsTheExactHitOnATriangleSoup) {
  const Scene scene = test::soupScene(4000, 0.25, 6);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<glm::dvec3> origins, dirs;
  for (int i = 0; i < 400; ++i) {
    origins.push_back({3.0 * u(rng), 3.0 * u(rng), 3.0});
    dirs.push_back(glm::dvec3(0.3 * u(rng), 0.3 * u(rng), -1.0));
  }
  expectPvlHoldsHits(scene, origins, dirs, 0.0);
}

TEST(RayWalker, PvlHoldsTheExactHitThroughNestedInstances) {
  const Scene scene = test::nestedScene(11);  // rotated, non-uniformly scaled, 3 levels
  const Camera cam = test::closeCamera(scene, 40, 30);
  std::vector<glm::dvec3> origins, dirs;
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x) {
      origins.push_back(cam.position());
      dirs.push_back(cam.pixelDirection(x + 0.5, y + 0.5));
    }
  expectPvlHoldsHits(scene, origins, dirs, cam.nearPlane());
}

TEST(RayWalker, RaysAlongOctreePlanes) {
  // Axis-parallel rays starting on the root's splitting planes (zero direction components,
  // rays lying in the planes between leaves).
  const Scene scene = test::soupScene(4000, 0.25, 8);
  const LzbAccel probe(scene, smallLeaves());
  const glm::dvec3 mid = probe.node(0).octree().bounds().center();
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<glm::dvec3> origins, dirs;
  for (int i = 0; i < 300; ++i) {
    const int axis = i % 3;
    glm::dvec3 o = mid + glm::dvec3(u(rng), u(rng), u(rng));
    o[(axis + 1) % 3] = mid[(axis + 1) % 3];  // in a splitting plane
    o[axis] = -4.0;
    glm::dvec3 d(0.0);
    d[axis] = 1.0;
    origins.push_back(o);
    dirs.push_back(d);
  }
  expectPvlHoldsHits(scene, origins, dirs, 0.0);
}

TEST(RayWalker, CoherentAndTopDownRecordTheSameLeaves) {
  const Scene scene = test::nestedScene(12);
  const LzbAccel accel(scene, smallLeaves());
  const Camera cam = test::closeCamera(scene, 48, 36);
  for (LeafTest test : kTests) {
    RayWalker top(accel, test, OctreeWalk::kTopDown), coherent(accel, test, OctreeWalk::kCoherent);
    PvlPart a, b;
    for (int y = 0; y < cam.height(); ++y)
      for (int x = 0; x < cam.width(); ++x) {
        const glm::dvec3 d = cam.pixelDirection(x + 0.5, y + 0.5);
        const double ta = top.cast(cam.position(), d, cam.nearPlane(), cam.farPlane(), a);
        const double tb = coherent.cast(cam.position(), d, cam.nearPlane(), cam.farPlane(), b);
        EXPECT_EQ(ta, tb);
      }
    a.finish();
    b.finish();
    EXPECT_EQ(a.leaves, b.leaves) << "test " << int(test);
    EXPECT_GT(a.leaves.size(), 20u);
    EXPECT_EQ(top.counts.triangleTests, coherent.counts.triangleTests);
    EXPECT_GT(coherent.counts.climbs, 0u);
  }
}

TEST(RayWalker, OccludersCutTestsAndLazyTestsMost) {
  const Scene scene = test::soupScene(6000, 0.25, 10);
  LzbAccelParams params;  // the paper's leaves: up to 150 triangles
  const LzbAccel accel(scene, params);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  uint64_t tests[4] = {}, leaves[4] = {};
  for (int m = 0; m < 4; ++m) {
    RayWalker w(accel, kTests[m], OctreeWalk::kTopDown);
    std::mt19937_64 r2(12);
    std::uniform_real_distribution<double> v(-1.0, 1.0);
    PvlPart part;
    for (int i = 0; i < 500; ++i)
      w.cast({v(r2), v(r2), 3.0}, {0.2 * v(r2), 0.2 * v(r2), -1.0}, 0.0, 1e9, part);
    part.finish();
    tests[m] = w.counts.triangleTests;
    leaves[m] = part.leaves.size();
  }
  // Lazy tests every triangle up to the first hit; occluder selection tests far fewer and,
  // resolving rays later, records at least as many leaves.
  EXPECT_LT(tests[1], tests[0] / 3);
  EXPECT_LT(tests[2], tests[0] / 2);
  EXPECT_LT(tests[3], tests[0] / 3);
  EXPECT_GE(leaves[1], leaves[0]);
  EXPECT_GE(leaves[3], leaves[0]);
}

}  // namespace
}  // namespace lzb::localz
