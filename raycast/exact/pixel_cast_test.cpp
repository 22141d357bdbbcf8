#include "raycast/exact/pixel_cast.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/cameras.hpp"
#include "tests/support/scenes.hpp"

namespace lzb {
namespace {

// A share drawn after others (WorkShare::drawnDepth) finds exactly the hits that can still win:
// its own hit where nothing nearer is drawn, a tie at the drawn depth too (the IDs settle it),
// nothing where the drawn surface is nearer; and it casts no ray where the drawn surface hides
// all it holds.
TEST(PixelCast, AShareDrawnAfterOthersFindsOnlyTheHitsThatCanWin) {
  const Scene scene = test::nestedScene();
  const EmbreeScene embree(scene, {});
  const Camera cam = test::closeCamera(scene, 70, 50);
  std::vector<uint8_t> touched;
  Framebuffer whole(cam.width(), cam.height());
  const uint64_t allRays = castEveryPixel(embree, cam, WorkShare{}, whole, touched, 2);
  ASSERT_EQ(allRays, 70u * 50u);

  // Left half: drawn just beyond the near plane, in front of the whole scene. Right half, by
  // pixel: the same depth, just nearer, twice as far, or nothing.
  std::vector<float> drawn(whole.size(), kEmptyDepth);
  size_t hits = 0, ties = 0, hidden = 0;
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x) {
      const size_t i = whole.index(x, y);
      if (x < cam.width() / 2) {
        drawn[i] = float(cam.nearPlane() * 1.01);
        continue;
      }
      if (whole.depth[i] == kEmptyDepth) continue;
      ++hits;
      switch ((x + y) % 3) {
        case 0:
          drawn[i] = whole.depth[i], ++ties;
          break;
        case 1:
          drawn[i] = std::nextafter(whole.depth[i], 0.0f), ++hidden;
          break;
        default:
          drawn[i] = 2.0f * whole.depth[i];
      }
    }
  ASSERT_GT(ties, 50u);
  ASSERT_GT(hidden, 50u);

  WorkShare after{};
  after.drawnDepth = &drawn;
  Framebuffer fb(cam.width(), cam.height());
  const uint64_t rays = castEveryPixel(embree, cam, after, fb, touched, 2);
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x) {
      const size_t i = whole.index(x, y);
      const bool canWin = whole.depth[i] != kEmptyDepth && !(drawn[i] < whole.depth[i]);
      ASSERT_EQ(fb.id[i], canWin ? whole.id[i] : kNoId) << x << ", " << y;
      ASSERT_EQ(fb.depth[i], canWin ? whole.depth[i] : kEmptyDepth) << x << ", " << y;
    }
  EXPECT_LE(rays, 35u * 50u) << "no ray where the drawn surface hides the whole scene";
  EXPECT_GE(rays, hits - hidden);
}

}  // namespace
}  // namespace lzb
