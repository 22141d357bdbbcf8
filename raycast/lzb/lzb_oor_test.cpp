#include "raycast/lzb/lzb_oor.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "raycast/lzb/lzb_cull.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/scenes.hpp"

namespace lzb::localz {
namespace {

// Random points of every culled leaf's content box behind the clip depth project inside the
// leaf's polygon: the OOR test never drops a pixel a far triangle could cover.
void expectConservative(const Scene& scene, const Camera& cam, double clip, int* clippedOut) {
  LzbAccelParams params;
  params.leafEntries = 16;
  const LzbAccel accel(scene, params);
  const CulledScene culled = cullScene(accel, cam);
  ASSERT_GT(culled.leaves.size(), 10u);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int clipped = 0, sides[17] = {};
  for (const CullLeaf& l : culled.leaves) {
    const CullPath& path = culled.paths[l.path];
    const Bounds& box = accel.node(path.node).contentBox(l.leaf);
    const ScreenPolygon poly = projectLeaf(accel, path, l.leaf, cam, clip);
    if (l.depthMin < clip) ++clipped;
    if (l.depthMax < clip) {
      EXPECT_GT(poly.x0, poly.x1) << "in front of the plane: covers nothing";
      continue;
    }
    if (l.depthMin > clip && poly.count) ++sides[poly.count];
    for (int i = 0; i < 200; ++i) {
      const glm::dvec3 local = box.lo + glm::dvec3(u(rng), u(rng), u(rng)) * box.extent();
      const glm::dvec3 world(path.world * glm::dvec4(local, 1.0));
      const glm::dvec3 p = cam.project(world);
      if (p.z < clip) continue;
      EXPECT_TRUE(poly.contains(p.x, p.y)) << "leaf " << l.leaf << " point " << p.x << "," << p.y;
    }
  }
  // Boxes wholly behind the plane project to hexagons, pentagons or quadrilaterals.
  for (int n = 0; n <= 16; ++n) {
    if (n < 4 || n > 6) {
      EXPECT_EQ(sides[n], 0) << n << " sides";
    }
  }
  EXPECT_GT(sides[6], 0);
  *clippedOut = clipped;
}

TEST(OorProjection, PolygonsHoldEveryFarPointOfTheirBoxes) {
  const Scene scene = test::nestedScene(5);  // rotated and scaled instance frames
  const Camera cam = test::closeCamera(scene, 160, 120);
  int clipped = 0;
  expectConservative(scene, cam, cam.viewDepth(scene.bounds().center()), &clipped);
  EXPECT_GT(clipped, 0);  // some boxes straddle the plane and are cut at it
}

TEST(OorProjection, CameraInsideTheBoxesIsClippedNotWholeScreen) {
  Scene scene = test::nestedScene(6);
  CameraSpec spec = test::closeSpec(scene);
  spec.position = scene.bounds().center();  // inside the octree and inside leaves
  spec.lookAt = spec.position + glm::dvec3(1.0, 0.2, 0.1);
  spec.nearPlane = 1e-3;
  const Camera cam(spec, 120, 90);
  int clipped = 0;
  expectConservative(scene, cam, 0.05, &clipped);
  EXPECT_GT(clipped, 0);
}

TEST(OorProjection, ContainsUsesTheHullNotJustTheBox) {
  ScreenPolygon p;
  p.x0 = 0, p.y0 = 0, p.x1 = 10, p.y1 = 10;
  p.count = 3;
  p.v[0] = {0, 0}, p.v[1] = {10, 0}, p.v[2] = {0, 10};  // turning left in (x, y)
  EXPECT_TRUE(p.contains(1, 1));
  EXPECT_TRUE(p.contains(5, 5));   // on the hypotenuse
  EXPECT_FALSE(p.contains(9, 9));  // in the box, outside the triangle
  EXPECT_FALSE(p.contains(-1, 1));
  const ScreenPolygon none{};
  EXPECT_FALSE(none.contains(0.5, 0.5));
}

TEST(OorObjects, BinsCoverEveryPolygonPixel) {
  const Scene scene = test::nestedScene(7);
  const Camera cam = test::closeCamera(scene, 100, 70);  // partial tiles at the edges
  const LzbAccel accel(scene, LzbAccelParams{});
  const CulledScene culled = cullScene(accel, cam);
  const ScreenTiles tiles(cam.width(), cam.height());
  const OorObjects objects(accel, culled, cam, cam.nearPlane(), tiles, 2);
  ASSERT_GT(objects.size(), 0u);
  // A pixel centre inside polygon k lies in a tile whose bin lists k.
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x) {
      const int t =
          (y / ScreenTiles::kDefaultSide) * tiles.columns() + x / ScreenTiles::kDefaultSide;
      const auto bin = objects.tile(t);
      for (uint32_t k = 0; k < objects.size(); ++k) {
        if (objects.polygon(k).contains(x + 0.5, y + 0.5)) {
          EXPECT_TRUE(std::find(bin.begin(), bin.end(), k) != bin.end()) << x << "," << y;
        }
      }
    }
}

}  // namespace
}  // namespace lzb::localz
