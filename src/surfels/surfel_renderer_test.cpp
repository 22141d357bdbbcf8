// The surfel renderer: no holes on a closed mesh at the level it chooses (and holes when told to
// use coarser cells), accuracy on a scanned mesh at the default settings, the switch between
// polygons and surfels, instancing, and the time budget's shuffled prefix, the same on any
// threads and ranks.
#include "src/surfels/surfel_renderer.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "raycast/exact/raycast_renderer.hpp"
#include "src/core/error.hpp"
#include "src/image/metrics.hpp"
#include "src/scene/load.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/frames.hpp"
#include "tests/support/meshes.hpp"
#include "tests/support/options.hpp"
#include "tests/support/reference.hpp"
#include "tests/support/render.hpp"
#include "tests/support/scenes.hpp"

namespace lzb::surfels {
namespace {

SurfelParams defaults() {
  return parseSurfelOptions({});
}

TEST(SurfelRenderer, NoHolesOnAClosedMeshAtTheChosenLevel) {
  const Scene scene = test::spheres({{0.0, 0.0, 0.0}});
  // 80x60: the sphere spans ~30 px, and the levels chosen for it (128^3 to 512^3 by sprite and
  // shape) cost a quarter of what twice the pixels would pick; the rule is the same at any size.
  const Camera cam = test::lookAtCamera({0.4, 0.7, 4.5}, {0, 0, 0}, 0.05, 1000.0, 80, 60);
  const Framebuffer truth = test::exactFrame(scene, cam, test::renderOptions("surfels", 2));
  for (int sprite : {1, 2, 4})
    for (bool disc : {false, true})
      for (bool drop : {true, false})
        for (Surfelizer how : {Surfelizer::kRaster, Surfelizer::kShots}) {
          SurfelParams p = defaults();
          p.sprite = sprite;
          p.disc = disc;
          p.dropBackfaces = drop;
          p.surfelize = how;
          SurfelRenderer r(scene, test::renderOptions("surfels", 2), p);
          FrameStats stats;
          const Framebuffer image = test::renderFrame(r, cam, &stats);
          const std::string what = "sprite " + std::to_string(sprite) +
                                   (disc ? " disc" : " square") + (drop ? " drop" : " keep") +
                                   (how == Surfelizer::kRaster ? " raster" : " shots");
          ASSERT_EQ(stats.shared["placements_surfels"], 1.0) << what;  // drawn as surfels
          std::printf("%s: %s\n", what.c_str(), stats.shared["grid_placements"].dump().c_str());
          EXPECT_EQ(test::holes(image, truth), 0u) << what << ", " << stats.shared.dump();
        }
}

TEST(SurfelRenderer, CoarserCellsThanTheSpriteCoversOpenHoles) {
  // The control of the test above: cells four times the hole-free size must leave holes.
  const Scene scene = test::spheres({{0.0, 0.0, 0.0}});
  const Camera cam = test::lookAtCamera({0.4, 0.7, 4.5}, {0, 0, 0}, 0.05, 1000.0, 160, 120);
  // The rule is a worst case (the box's nearest corner, the cube's whole extent, grids in powers
  // of two): at 2.0 it picks 128^3, whose cells project to 0.63 px at the sphere's front (no
  // holes); 4.0 picks 64^3, 1.27 px cells against 1-pixel sprites.
  SurfelParams p = defaults();
  p.cellFraction = 4.0;
  SurfelRenderer r(scene, test::renderOptions("surfels", 2), p);
  FrameStats stats;
  const Framebuffer image = test::renderFrame(r, cam, &stats);
  ASSERT_EQ(stats.shared["placements_surfels"], 1.0);
  ASSERT_EQ(stats.shared["grid_placements"].value("64", 0.0), 1.0) << stats.shared.dump();
  EXPECT_GT(test::holes(image, test::exactFrame(scene, cam, test::renderOptions("surfels", 2))),
            50u);
}

TEST(SurfelRenderer, ShowsVisibleTrianglesOnAScannedMeshAtTheDefaults) {
  const std::string mesh = test::scannedMesh("armadillo.off");
  if (mesh.empty()) GTEST_SKIP() << "armadillo.off missing: run scripts/fetch-test-meshes.sh";
  const Scene scene = loadScene(mesh, true);
  // At 320 px the mesh's cube projects over 256 px, so even 512^3 cells exceed half a 1-pixel
  // sprite: the defaults draw it as polygons (below); 80 and 160 px draw surfels of two levels.
  for (int width : {80, 160}) {
    const Camera cam = test::pathFrame(scene, 1, 4, width, width * 3 / 4);
    SurfelRenderer r(scene, test::renderOptions("surfels", 2), defaults());
    FrameStats stats;
    const Framebuffer image = test::renderFrame(r, cam, &stats);
    ASSERT_EQ(stats.shared["placements_surfels"], 1.0) << "width " << width;
    std::printf("width %d: %s\n", width, stats.shared["grid_placements"].dump().c_str());
    const Accuracy a = test::accuracy(scene, cam, image, test::renderOptions("surfels", 2));
    EXPECT_GE(a.correctRateCovered, 0.90) << "width " << width << ": " << toJson(a).dump();
    EXPECT_EQ(a.missingPixels, 0u) << "width " << width;
  }
  const Camera near = test::pathFrame(scene, 1, 4, 320, 240);
  SurfelRenderer r(scene, test::renderOptions("surfels", 2), defaults());
  FrameStats stats;
  const Framebuffer image = test::renderFrame(r, near, &stats);
  EXPECT_EQ(stats.shared["placements_polygons"], 1.0);
  EXPECT_GE(
      test::accuracy(scene, near, image, test::renderOptions("surfels", 2)).correctRateCovered,
      0.999);  // the native z-buffer
}

TEST(SurfelRenderer, NearObjectsStayPolygonsAndAreExact) {
  // One sphere just in front of the camera, one far away.
  const Scene scene = test::spheres({{0.0, 0.0, 0.0}, {6.0, 0.0, -60.0}});
  const Camera cam = test::lookAtCamera({0.0, 0.0, 2.2}, {0.3, 0.0, -1.0}, 0.05, 1000.0, 160, 120);
  SurfelRenderer r(scene, test::renderOptions("surfels", 2), defaults());
  FrameStats stats;
  const Framebuffer image = test::renderFrame(r, cam, &stats);
  EXPECT_EQ(stats.shared["placements_polygons"], 1.0);
  EXPECT_EQ(stats.shared["placements_surfels"], 1.0);
  EXPECT_EQ(stats.counts["polygon_triangles"], double(scene.nodes[1].mesh.size()));
  // The near sphere (IDs below its triangle count) is the exact image wherever it is visible.
  const Framebuffer truth = test::exactFrame(scene, cam, test::renderOptions("surfels", 2));
  const uint64_t n = scene.nodes[1].mesh.size();
  size_t near = 0, same = 0;
  for (size_t i = 0; i < truth.size(); ++i)
    if (truth.covered(i) && truth.id[i] < n) {
      ++near;
      same += image.id[i] == truth.id[i];
    }
  ASSERT_GT(near, 3000u);
  EXPECT_GE(double(same), 0.999 * double(near));
}

TEST(SurfelRenderer, ChoosesTheCoarsestHoleFreeLevelAndTheSmallestSprite) {
  SurfelParams p = defaults();  // grids 1..512, sprite 1, cells at most half the sprite
  EXPECT_EQ(chooseLevel(100.0, p).level, 8);  // 100 / 256 <= 0.5 < 100 / 128
  EXPECT_EQ(chooseLevel(100.0, p).sprite, 1);
  EXPECT_EQ(chooseLevel(0.3, p).level, 0);               // a sub-pixel object: one cell
  EXPECT_EQ(chooseLevel(300.0, p).level, kPolygons);     // 300 / 512 > 0.5: polygons
  EXPECT_EQ(chooseLevel(INFINITY, p).level, kPolygons);  // reaches the near plane
  p.sprite = 4;
  EXPECT_EQ(chooseLevel(300.0, p).level, 8);  // 300 / 128 = 2.3 > 0.5 x 4; 300 / 256 fits
  EXPECT_EQ(p.grids[size_t(chooseLevel(300.0, p).level)], 256);
  EXPECT_EQ(chooseLevel(300.0, p).sprite, 3);  // 1.17 <= 0.5 d from d = 3
  p.disc = true;                               // a disc of d covers d / sqrt 2
  EXPECT_EQ(chooseLevel(300.0, p).sprite, 4);
  p.grids = {64, 128};
  EXPECT_EQ(chooseLevel(0.3, p).level, 0);
  EXPECT_EQ(chooseLevel(1000.0, p).level, kPolygons);
}

TEST(SurfelRenderer, InstancesShareOneSurfelSetPerObject) {
  const Scene scene = loadScene("builtin:sphereflake?depth=3", true);
  const Camera cam = test::pathFrame(scene, 0, 4, 256, 192);
  SurfelRenderer r(scene, test::renderOptions("surfels", 2), defaults());
  FrameStats stats;
  test::renderFrame(r, cam, &stats);
  EXPECT_EQ(stats.shared["objects_surfels"], 1.0);  // the one sphere node
  EXPECT_GT(stats.shared["placements_surfels"].get<double>(), 500.0);
  double sprites = 0.0;  // every surfel placement has one sprite size
  for (const auto& n : stats.shared["sprite_placements"]) sprites += n.get<double>();
  EXPECT_EQ(sprites, stats.shared["placements_surfels"].get<double>());
  // One level per grid in use, whatever the number of placements.
  EXPECT_EQ(stats.shared["levels_cached"].get<double>(),
            double(stats.shared["grid_placements"].size()));
  EXPECT_EQ(stats.shared["collector_bytes_per_surfel"], 6.0);
  EXPECT_EQ(stats.shared["id_bytes_per_surfel"], 1.0);  // 200 triangles
  // The cache: a second frame builds nothing.
  test::renderFrame(r, cam, &stats);
  EXPECT_EQ(stats.shared["levels_built"], 0.0);
}

// The budget as a count: one fraction of every collector, its shuffled prefix.
TEST(SurfelRenderer, BudgetDrawsTheShuffledPrefixOnAnyThreadsAndRanks) {
  const Scene scene = loadScene("builtin:sphereflake?depth=2", true);
  const Camera cam = test::pathFrame(scene, 0, 4, 200, 150);
  SurfelParams full = defaults();
  full.sprite = 2;
  SurfelRenderer all(scene, test::renderOptions("surfels", 2), full);
  FrameStats fs;
  const Framebuffer whole = test::renderFrame(all, cam, &fs);
  const double selected = fs.shared["surfels_selected"].get<double>();
  ASSERT_GT(selected, 10000.0);

  SurfelParams p = full;
  p.budgetMs = 2.0;
  p.budgetRate = selected / 8.0 / p.budgetMs;  // buys an eighth
  SurfelRenderer one(scene, test::renderOptions("surfels", 1), p),
      two(scene, test::renderOptions("surfels", 2), p);
  FrameStats s1, s2;
  const Framebuffer a = test::renderFrame(one, cam, &s1), b = test::renderFrame(two, cam, &s2);
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.depth, b.depth);
  EXPECT_NEAR(s1.shared["budget_fraction"].get<double>(), 0.125, 0.01);
  EXPECT_NEAR(s1.counts["surfels_drawn"].get<double>(), selected / 8.0, 0.01 * selected);
  for (int size : {2, 3}) {
    Framebuffer composite(cam.width(), cam.height());
    double drawn = 0.0;
    for (int rank = 0; rank < size; ++rank) {
      SurfelRenderer part(scene, test::renderOptions("surfels", 1), p);
      FrameStats s;
      compositeNearer(composite, test::renderFrame(part, cam, &s, {rank, size}));
      drawn += s.counts["surfels_drawn"].get<double>();
    }
    EXPECT_EQ(composite.id, a.id) << size << " ranks";
    EXPECT_EQ(composite.depth, a.depth) << size << " ranks";
    EXPECT_EQ(drawn, s1.counts["surfels_drawn"].get<double>());
  }
  // The prefix is spread over the whole object: it reaches the full image's extent.
  const auto extent = [](const Framebuffer& fb) {
    int x0 = fb.width, x1 = -1, y0 = fb.height, y1 = -1;
    for (int y = 0; y < fb.height; ++y)
      for (int x = 0; x < fb.width; ++x)
        if (fb.covered(fb.index(x, y)))
          x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    return glm::ivec2(x1 - x0, y1 - y0);
  };
  EXPECT_GE(extent(a).x, 0.9 * extent(whole).x);
  EXPECT_GE(extent(a).y, 0.9 * extent(whole).y);
  EXPECT_LT(a.coveredCount(), whole.coveredCount());
}

TEST(SurfelRenderer, BudgetRateIsMeasuredAtSetUpWhenNotGiven) {
  const Scene scene = test::spheres({{0.0, 0.0, 0.0}});
  SurfelParams p = defaults();
  p.budgetMs = 5.0;
  SurfelRenderer r(scene, test::renderOptions("surfels", 2), p);
  EXPECT_GT(r.budgetRate(), 100.0);  // surfels per ms: any machine splats more than 1e5 per second
  EXPECT_GT(r.setupStats().shared["budget_rate_measured_per_ms"].get<double>(), 100.0);
  // Each rank would measure its own rate: several ranks need a given one.
  const Camera cam = test::lookAtCamera({0.0, 0.0, 4.5}, {0, 0, 0}, 0.05, 1000.0, 64, 48);
  EXPECT_THROW(test::renderFrame(r, cam, nullptr, {0, 2}), InputError);
  EXPECT_NO_THROW(test::renderFrame(r, cam, nullptr, {0, 1}));
}

}  // namespace
}  // namespace lzb::surfels
