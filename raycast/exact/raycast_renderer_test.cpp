#include "raycast/exact/raycast_renderer.hpp"

#include <gtest/gtest.h>

#include "raycast/exact/raycast_test_util.hpp"
#include "mpi/decomposition.hpp"
#include "src/core/shading.hpp"

namespace lzb {
namespace {

Framebuffer render(RaycastRenderer& r, const Camera& cam, WorkShare share = {},
                   FrameStats* statsOut = nullptr) {
  Framebuffer fb(cam.width(), cam.height());
  FrameStats stats;
  r.render(cam, 0, share, fb, stats);
  if (statsOut) *statsOut = stats;
  return fb;
}

void expectSame(const Framebuffer& a, const Framebuffer& b) {
  ASSERT_EQ(a.size(), b.size());
  size_t differ = 0;
  for (size_t i = 0; i < a.size(); ++i)
    differ += a.id[i] != b.id[i] || a.depth[i] != b.depth[i] || a.color[i] != b.color[i];
  EXPECT_EQ(differ, 0u);
}

RenderOptions options(int threads) {
  RenderOptions o;
  o.method = "raycast";
  o.threads = threads;
  return o;
}

TEST(RaycastRenderer, PixelsAreCentreRaysAndColourIsLeftToTheDriver) {
  const Scene scene = testing::nestedScene();
  RaycastRenderer r(scene, options(2));
  const Camera cam = testing::camera(scene, 70, 50);
  FrameStats stats;
  const Framebuffer fb = render(r, cam, {}, &stats);
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

TEST(RaycastRenderer, RanksCompositeToTheSingleImage) {
  const Scene scene = testing::nestedScene();
  RaycastRenderer r(scene, options(2));
  const Camera cam = testing::camera(scene, 100, 70);  // partial tiles on both edges
  const Framebuffer single = render(r, cam);
  for (int size : {2, 3}) {
    Framebuffer composite(cam.width(), cam.height());
    const ScreenTiles tiles(cam.width(), cam.height());
    for (int rank = 0; rank < size; ++rank) {
      FrameStats stats;
      const Framebuffer part = render(r, cam, {rank, size}, &stats);
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
  const Scene scene = testing::nestedScene(9);
  const Camera cam = testing::camera(scene, 90, 64);
  RaycastRenderer one(scene, options(1));
  RaycastRenderer two(scene, options(2));
  RaycastTuning single;
  single.packets = false;
  RaycastRenderer scalar(scene, options(2), single);
  const Framebuffer reference = render(one, cam);
  EXPECT_GT(reference.coveredCount(), 500u);
  expectSame(render(two, cam), reference);
  expectSame(render(scalar, cam), reference);
}

TEST(RaycastRenderer, FramesDoNotDependOnEarlierFrames) {
  // Rendering frame b after frame a gives what a fresh renderer gives for b.
  const Scene scene = testing::translated(testing::nestedScene(), {3e6, 1e6, -2e6});
  const CameraSpec base = testing::closeSpec(scene);
  RaycastRenderer r(scene, options(2));
  render(r, Camera(pathCamera(scene, base, 0, 4), 64, 48));
  const Camera b(pathCamera(scene, base, 1, 4), 64, 48);
  const Framebuffer after = render(r, b);
  RaycastRenderer fresh(scene, options(2));
  expectSame(after, render(fresh, b));
  EXPECT_GT(after.coveredCount(), 300u);
}

}  // namespace
}  // namespace lzb
