#include "raycast/lzb/lzb_plane.hpp"

#include <gtest/gtest.h>

#include "raycast/lzb/lzb_triangle_set.hpp"
#include "tests/support/scenes.hpp"

namespace lzb::localz {
namespace {

// Looking straight at the quad [-1, 1]^2 (z = 0) from z = d: every hit has view depth d.
Camera headOn(double d, double x = 0.0, double turn = 0.0, bool away = false) {
  CameraSpec spec;
  spec.position = {x, 0.0, d};
  spec.lookAt = {x + turn, 0.0, away ? 2.0 * d : 0.0};
  spec.fovyDegrees = 40.0;
  spec.nearPlane = 0.1;
  spec.farPlane = 100.0;
  return Camera(spec, 64, 48);
}

TEST(PartitionPlane, DynamicIsTheMeanDepthOfTheCoarseHits) {
  const Scene scene = test::quadScene();
  const EmbreeScene embree(scene, {});
  const PlaneDecision d = PartitionPlane::coarseRayCast(embree, headOn(4.0), 8);
  EXPECT_EQ(d.coarseRays, 64u);
  EXPECT_GT(d.coarseHits, 0u);
  EXPECT_LT(d.coarseHits, 64u);  // the quad does not fill the view
  EXPECT_NEAR(d.depth, 4.0, 1e-6);
  // Nothing hit: the whole frustum is near.
  const PlaneDecision none = PartitionPlane::coarseRayCast(embree, headOn(4.0, 0.0, 0.0, true), 8);
  EXPECT_EQ(none.coarseHits, 0u);
  EXPECT_EQ(none.depth, 100.0);
}

TEST(PartitionPlane, CoarseRaysGiveTheSameHitsOnAnyThreadCount) {
  const Scene scene = test::quadScene();
  const EmbreeScene embree(scene, {});
  // 40 x 40 rays: several blocks of the parallel loop, the last one partial.
  std::vector<double> one, two;
  const PlaneDecision a = PartitionPlane::coarseRayCast(embree, headOn(3.0, 0.3), 40, &one, 1);
  const PlaneDecision b = PartitionPlane::coarseRayCast(embree, headOn(3.0, 0.3), 40, &two, 2);
  EXPECT_EQ(a.coarseRays, 1600u);
  EXPECT_GT(a.coarseHits, 100u);
  EXPECT_EQ(a.coarseHits, b.coarseHits);
  EXPECT_EQ(a.depth, b.depth);
  EXPECT_EQ(one, two);
}

TEST(PartitionPlane, StaticIsAFractionOfTheFrustumDepth) {
  const Scene scene = test::quadScene();
  const EmbreeScene embree(scene, {});
  LzbOptions o;
  o.planeFraction = 0.25;
  PartitionPlane plane(o);
  const PlaneDecision d = plane.place(embree, headOn(2.0));
  EXPECT_DOUBLE_EQ(d.depth, 0.1 + 0.25 * (100.0 - 0.1));
  EXPECT_FALSE(d.reused);
  EXPECT_EQ(d.coarseRays, 0u);
}

TEST(PartitionPlane, ReusedWhileTheViewStaysCloseThenRecomputed) {
  const Scene scene = test::quadScene();
  const EmbreeScene embree(scene, {});
  LzbOptions o;
  o.planeReuse = 3;
  PartitionPlane plane(o);
  const PlaneDecision first = plane.place(embree, headOn(2.0));
  EXPECT_FALSE(first.reused);
  plane.observe(1000);
  // Moved 2 % of the plane depth: still valid.
  const PlaneDecision near = plane.place(embree, headOn(2.0, 0.04));
  EXPECT_TRUE(near.reused);
  EXPECT_EQ(near.depth, first.depth);
  EXPECT_EQ(near.coarseRays, 0u);
  plane.observe(1000);
  // Moved 10 %: recomputed.
  EXPECT_FALSE(plane.place(embree, headOn(2.0, 0.2)).reused);
  plane.observe(1000);
  // Turned by more than fovy / 16 (2.5 degrees): recomputed.
  EXPECT_FALSE(plane.place(embree, headOn(2.0, 0.2, 0.1)).reused);
  plane.observe(1000);
  // At most planeReuse reuses in a row.
  int reused = 0;
  for (int i = 0; i < 6; ++i) {
    reused += plane.place(embree, headOn(2.0, 0.2, 0.1)).reused;
    plane.observe(1000);
  }
  EXPECT_EQ(reused, 3 + 2);  // 3 reuses, a recompute, 2 more reuses
}

TEST(PartitionPlane, MoreUnfinishedPixelsInvalidateThePlane) {
  const Scene scene = test::quadScene();
  const EmbreeScene embree(scene, {});
  PartitionPlane plane(LzbOptions{});
  plane.place(embree, headOn(2.0));
  plane.observe(100);
  EXPECT_TRUE(plane.place(embree, headOn(2.0)).reused);
  plane.observe(100 + 30);  // within 1.5 x + 1 % of the image: still fine
  EXPECT_TRUE(plane.place(embree, headOn(2.0)).reused);
  plane.observe(1000);  // the near pass got much worse
  EXPECT_FALSE(plane.place(embree, headOn(2.0)).reused);
}

TEST(PartitionPlane, NeverReusedWithReuseZero) {
  const Scene scene = test::quadScene();
  const EmbreeScene embree(scene, {});
  LzbOptions o;
  o.planeReuse = 0;
  PartitionPlane plane(o);
  for (int i = 0; i < 3; ++i) {
    EXPECT_FALSE(plane.place(embree, headOn(2.0)).reused);
    plane.observe(10);
  }
}

TEST(PartitionPlane, CostPlaneWeighsNearTrianglesAgainstRays) {
  const Camera cam = headOn(4.0);  // 64 x 48 pixels, near 0.1, far 100
  // 16 coarse rays: 8 hit at depth 10, 8 at depth 50. Each ray stands for 3072 / 16 = 192 px.
  std::vector<double> hits(8, 10.0);
  hits.insert(hits.end(), 8, 50.0);
  // Few triangles before 10, a million between 10 and 50: stop the near scene at 10.
  std::vector<LeafLoad> loads = {{5.0, 100}, {20.0, 1000000}};
  EXPECT_EQ(PartitionPlane::costPlane(hits, 16, cam, loads, 12.0), 10.0);
  // Cheap near scene throughout: everything near (plane at the farthest hit).
  loads = {{5.0, 100}, {20.0, 100}};
  EXPECT_EQ(PartitionPlane::costPlane(hits, 16, cam, loads, 12.0), 50.0);
  // Expensive from the start and rays cheap: the plane at the near plane, all rays.
  loads = {{0.5, 1000000}};
  EXPECT_EQ(PartitionPlane::costPlane(hits, 16, cam, loads, 1.0), 0.1);
  // No hit (geometry between the coarse rays): the whole frustum is near when its triangles cost
  // less than a ray per pixel (3072 x 12), else all of it is far.
  const std::vector<LeafLoad> few = {{0.5, 30000}};
  EXPECT_EQ(PartitionPlane::costPlane({}, 16, cam, few, 12.0), 100.0);
  EXPECT_EQ(PartitionPlane::costPlane({}, 16, cam, loads, 12.0), 0.1);
}

// The loads are binned on threads (past 65536 leaves): the same plane for any thread count, and
// the one a single leaf of their summed triangles at the same start gives.
TEST(PartitionPlane, CostPlaneIsTheSameOnAnyThreadCount) {
  const Camera cam = headOn(4.0);
  std::vector<double> hits;
  for (int i = 0; i < 16; ++i) hits.push_back(1.0 + 6.0 * i);
  std::vector<LeafLoad> many;
  for (int i = 0; i < 200000; ++i) many.push_back({i % 2 ? 40.0 : 3.0, i % 2 ? 1u : 0u});
  const double one = PartitionPlane::costPlane(hits, 16, cam, many, 12.0, 1);
  EXPECT_EQ(PartitionPlane::costPlane(hits, 16, cam, many, 12.0, 2), one);
  EXPECT_EQ(PartitionPlane::costPlane(hits, 16, cam, many, 12.0, 3), one);
  const std::vector<LeafLoad> summed = {{40.0, 100000u}};
  EXPECT_EQ(PartitionPlane::costPlane(hits, 16, cam, summed, 12.0, 1), one);
  EXPECT_EQ(one, 37.0) << "100000 triangles from 40 on against 192-pixel rays: stop before them";
}

TEST(PartitionPlane, CostModeIsDynamicAndReusable) {
  const Scene scene = test::quadScene();
  const EmbreeScene embree(scene, {});
  LzbOptions o;
  o.costPlane = true;
  PartitionPlane plane(o);
  const std::vector<LeafLoad> loads = {{3.9, 2}};  // the quad's leaf, starting before 4
  const PlaneDecision d = plane.place(embree, headOn(4.0), loads);
  EXPECT_GT(d.coarseRays, 0u);
  EXPECT_NEAR(d.depth, 4.0, 1e-5);  // 2 triangles are cheaper than any ray
  plane.observe(0);
  EXPECT_TRUE(plane.place(embree, headOn(4.0), loads).reused);
}

TEST(PartitionPlane, TakesCoarseRaysAlreadyCastForTheSameCamera) {
  const Scene scene = test::quadScene();
  const EmbreeScene embree(scene, {});
  for (const bool cost : {false, true}) {
    LzbOptions o;
    o.costPlane = cost;
    o.planeReuse = 0;
    const std::vector<LeafLoad> loads = {{3.9, 2}};
    CoarseHits cast;
    cast.mean = PartitionPlane::coarseRayCast(embree, headOn(4.0), o.planeGrid, &cast.depths);
    PartitionPlane own(o), given(o);
    const PlaneDecision a = own.place(embree, headOn(4.0), loads);
    const PlaneDecision b = given.place(embree, headOn(4.0), loads, 1, false, &cast);
    EXPECT_EQ(a.depth, b.depth);
    EXPECT_EQ(a.coarseRays, b.coarseRays);
    EXPECT_EQ(a.coarseHits, b.coarseHits);
    // The given rays are the ones used: hits moved to depth 7 move the plane there.
    for (double& d : cast.depths) d = 7.0;
    cast.mean.depth = 7.0;
    EXPECT_NEAR(given.place(embree, headOn(4.0), loads, 1, false, &cast).depth, 7.0, 1e-5)
        << (cost ? "cost" : "mean") << " plane";
  }
}

TEST(TriangleSet, ListsEachTriangleOnceInAscendingOrder) {
  TriangleSet set;
  set.reset(1000);
  for (uint32_t t : {700u, 3u, 64u, 3u, 999u, 63u, 700u}) set.add(t);
  EXPECT_EQ(set.count(), 5u);
  std::vector<uint32_t> out;
  set.take(out);
  EXPECT_EQ(out, (std::vector<uint32_t>{3, 63, 64, 700, 999}));
  // Taken sets are clear: reusable for the next placement.
  set.reset(10);
  EXPECT_TRUE(set.add(3));
  EXPECT_EQ(set.count(), 1u);
  out.clear();
  set.take(out);
  EXPECT_EQ(out, (std::vector<uint32_t>{3}));
}

}  // namespace
}  // namespace lzb::localz
