#include "raycast/exact/raycast_renderer.hpp"

#include <gtest/gtest.h>

#include "mpi/decomposition.hpp"
#include "src/core/shading.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/options.hpp"
#include "tests/support/render.hpp"
#include "tests/support/scenes.hpp"

namespace lzb {
namespace {

void expectSame(const Framebuffer& a, const Framebuffer& b) {
  ASSERT_EQ(a.size(), b.size());
  size_t differ = 0;
  for (size_t i = 0; i < a.size(); ++i)
    differ += a.id[i] != b.id[i] || a.depth[i] != b.depth[i] || a.color[i] != b.color[i];
  EXPECT_EQ(differ, 0u);
}

TEST(RaycastRenderer, PixelsAreCentreRaysAndColourIsLeftToTheDriver) {
  const Scene scene = test::nestedScene();
  RaycastRenderer r(scene, test::renderOptions("raycast", 2));
  const Camera cam = test::closeCamera(scene, 70, 50);
  FrameStats stats;
  const Framebuffer fb = test::renderFrame(r, cam, &stats);
  EmbreeScene embree(scene, {});
  size_t covered = 0;
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x) {
      const RayHit h = embree.intersect(cam.position(), cam.pixelDirection(x + 0.5, y + 0.5),
                                        cam.nearPlane(), cam.farPlane());
      const size_t i = fb.index(x, y);
      EXPECT_EQ(fb.id[i], h.id);
      EXPECT_EQ(fb.depth[i], h.hit() ? h.t : kEmptyDepth);
      covered += h.hit();
    }
  EXPECT_GT(covered, 500u);
  // Colour is left to the frame driver, which shades from the IDs after compositing.
  EXPECT_TRUE(r.colourFromIds());
  for (size_t i = 0; i < fb.size(); ++i) ASSERT_EQ(fb.color[i], kBackground);

  ASSERT_EQ(stats.stageSeconds.size(), 1u);
  EXPECT_EQ(stats.stageSeconds[0].first, "trace");
  EXPECT_EQ(stats.counts.value("rays", 0.0), 70.0 * 50.0);

  // The build is reported once, with the set-up, not with frames.
  for (const auto& stage : stats.stageSeconds) EXPECT_NE(stage.first, "build");
  const FrameStats setup = r.setupStats();
  ASSERT_EQ(setup.stageSeconds.size(), 1u);
  EXPECT_EQ(setup.stageSeconds[0].first, "build");
  EXPECT_GE(setup.shared.value("embree_scenes", 0.0), 1.0);
}

TEST(RaycastRenderer, CastsOnlyWhereTheSceneProjectsWithTheSameHits) {
  const Scene scene = test::nestedScene();
  RaycastRenderer r(scene, test::renderOptions("raycast", 2));
  // From far off the scene covers the middle of the frame; on each side the camera is inside or
  // beside its box (every tile cast).
  const glm::dvec3 c = scene.bounds().center();
  const double d = scene.bounds().diagonal();
  for (const glm::dvec3& eye : {c + glm::dvec3(0, 0, 6 * d), c + glm::dvec3(0.1 * d, 0, 0)}) {
    const Camera cam = test::lookAtCamera(eye, c - glm::dvec3(0, 0, 0.01 * d), 0.001 * d, 20 * d,
                                          96, 64);
    FrameStats stats;
    const Framebuffer fb = test::renderFrame(r, cam, &stats);
    EmbreeScene embree(scene, {});
    size_t covered = 0;
    for (int y = 0; y < cam.height(); ++y)
      for (int x = 0; x < cam.width(); ++x) {
        const RayHit h = embree.intersect(cam.position(), cam.pixelDirection(x + 0.5, y + 0.5),
                                          cam.nearPlane(), cam.farPlane());
        ASSERT_EQ(fb.id[fb.index(x, y)], h.id) << x << ", " << y;
        covered += h.hit();
      }
    EXPECT_GT(covered, 0u);
    const double rays = stats.counts.value("rays", 0.0);
    if (eye.z > c.z + d) {
      EXPECT_LT(rays, 0.5 * 96 * 64) << "tiles beyond the scene's projection cast no ray";
    } else {
      EXPECT_EQ(rays, 96.0 * 64.0) << "a box around the camera projects everywhere";
    }
  }
}

TEST(RaycastRenderer, RanksCompositeToTheSingleImage) {
  const Scene scene = test::nestedScene();
  RaycastRenderer r(scene, test::renderOptions("raycast", 2));
  const Camera cam = test::closeCamera(scene, 100, 70);  // partial tiles on both edges
  const Framebuffer single = test::renderFrame(r, cam);
  for (int size : {2, 3}) {
    Framebuffer composite(cam.width(), cam.height());
    const ScreenTiles tiles(cam.width(), cam.height());
    for (int rank = 0; rank < size; ++rank) {
      FrameStats stats;
      const Framebuffer part = test::renderFrame(r, cam, &stats, {rank, size});
      // Only this rank's tiles were traced.
      size_t mine = 0;
      for (int t = 0; t < tiles.count(); ++t) {
        const TileRect rect = tiles.tile(t);
        if (t % size == rank) {
          mine += size_t(rect.pixels());
          continue;
        }
        for (int y = rect.y0; y < rect.y1; ++y)
          for (int x = rect.x0; x < rect.x1; ++x) EXPECT_EQ(part.id[part.index(x, y)], kNoId);
      }
      EXPECT_EQ(stats.counts.value("rays", 0.0), double(mine));
      compositeNearer(composite, part);
    }
    expectSame(composite, single);
  }
}

TEST(RaycastRenderer, SameImageForAnyThreadCountAndRayMode) {
  const Scene scene = test::nestedScene(9);
  const Camera cam = test::closeCamera(scene, 90, 64);
  RaycastRenderer one(scene, test::renderOptions("raycast", 1));
  RaycastRenderer two(scene, test::renderOptions("raycast", 2));
  RaycastTuning single;
  single.packets = false;
  RaycastRenderer scalar(scene, test::renderOptions("raycast", 2), single);
  const Framebuffer reference = test::renderFrame(one, cam);
  EXPECT_GT(reference.coveredCount(), 500u);
  expectSame(test::renderFrame(two, cam), reference);
  expectSame(test::renderFrame(scalar, cam), reference);
}

TEST(RaycastRenderer, FramesDoNotDependOnEarlierFrames) {
  // Rendering frame b after frame a gives what a fresh renderer gives for b.
  const Scene scene = test::translated(test::nestedScene(), {3e6, 1e6, -2e6});
  const CameraSpec base = test::closeSpec(scene);
  RaycastRenderer r(scene, test::renderOptions("raycast", 2));
  test::renderFrame(r, Camera(pathCamera(scene, base, 0, 4), 64, 48));
  const Camera b(pathCamera(scene, base, 1, 4), 64, 48);
  const Framebuffer after = test::renderFrame(r, b);
  RaycastRenderer fresh(scene, test::renderOptions("raycast", 2));
  expectSame(after, test::renderFrame(fresh, b));
  EXPECT_GT(after.coveredCount(), 300u);
}

}  // namespace
}  // namespace lzb
