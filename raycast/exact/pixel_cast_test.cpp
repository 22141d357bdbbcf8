#include "raycast/exact/pixel_cast.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

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

// A box's rectangle holds the projection of every point of it (a pixel of margin), is the whole
// frame when the box reaches behind the eye, and nothing when it lies wholly before the near
// plane, beyond the far one or beside the frame; under a placement as under its world box.
TEST(PixelCast, PixelsUnderABoxHoldTheProjectionOfEveryPointOfIt) {
  const Camera cam = test::lookAtCamera({0, 0, 10}, {0, 0, 0}, 1.0, 100.0, 80, 60, 45.0);
  const CameraPlacement world(cam, glm::dmat4(1.0));
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const glm::dmat4 place = test::randomTransform(rng, 0.5, 2.0);
  const CameraPlacement placed(cam, place);
  for (int k = 0; k < 40; ++k) {
    const glm::dvec3 lo(u(rng) * 4 - 2, u(rng) * 4 - 2, u(rng) * 4 - 2);
    const Bounds box{lo, lo + glm::dvec3(u(rng), u(rng), u(rng))};
    for (const auto& [p, toWorld] :
         {std::pair{&world, glm::dmat4(1.0)}, std::pair{&placed, place}}) {
      const TileRect r = pixelsUnder(box, *p, cam);
      for (int s = 0; s < 50; ++s) {
        const glm::dvec3 q = box.lo + (box.hi - box.lo) * glm::dvec3(u(rng), u(rng), u(rng));
        const glm::dvec3 px = cam.project(glm::dvec3(toWorld * glm::dvec4(q, 1.0)));
        if (px.x < 0 || px.x >= cam.width() || px.y < 0 || px.y >= cam.height()) continue;
        ASSERT_TRUE(px.x >= r.x0 && px.x < r.x1 && px.y >= r.y0 && px.y < r.y1) << k;
      }
    }
  }
  const auto whole = [&](const TileRect& r) {
    return r.x0 == 0 && r.y0 == 0 && r.x1 == cam.width() && r.y1 == cam.height();
  };
  EXPECT_TRUE(whole(pixelsUnder(Bounds{{-1, -1, 9}, {1, 1, 11}}, world, cam)));  // around the eye
  const auto none = [](const TileRect& r) { return r.x0 >= r.x1 || r.y0 >= r.y1; };
  EXPECT_TRUE(none(pixelsUnder(Bounds{{-1, -1, 9.2}, {1, 1, 9.5}}, world, cam)));  // before near
  EXPECT_TRUE(none(pixelsUnder(Bounds{{-1, -1, -95}, {1, 1, -91}}, world, cam)));  // beyond far
  EXPECT_TRUE(none(pixelsUnder(Bounds{{50, 0, 0}, {51, 1, 1}}, world, cam)));      // beside
  EXPECT_TRUE(none(pixelsUnder(Bounds{}, world, cam)));
}

TEST(PixelCast, BlockCoverMarksTheBlocksARectangleMeets) {
  BlockCover cover(10, 9);  // 3 x 3 blocks, the last row and column partial
  EXPECT_EQ(cover.blocks(), 0u);
  EXPECT_TRUE(cover.allIn({2, 2, 2, 5})) << "an empty rectangle";
  cover.add({3, 3, 5, 4});  // pixels 3..4: blocks (0, 0) and (1, 0)
  EXPECT_EQ(cover.blocks(), 2u);
  EXPECT_TRUE(cover.covers(0, 0) && cover.covers(7, 3));
  EXPECT_FALSE(cover.covers(8, 0) || cover.covers(0, 4));
  EXPECT_TRUE(cover.anyIn({7, 3, 10, 9}));
  EXPECT_FALSE(cover.anyIn({8, 0, 10, 9}));
  EXPECT_TRUE(cover.allIn({0, 0, 8, 4}));
  EXPECT_FALSE(cover.allIn({0, 0, 9, 4}));
  cover.add({9, 8, 10, 9});
  EXPECT_TRUE(cover.covers(9, 8));
  EXPECT_EQ(cover.blocks(), 3u);
}

// With a cover, castEveryPixel casts only its blocks and leaves every other pixel untouched;
// what it casts is the frame cast without one.
TEST(PixelCast, ACoverLimitsTheRaysToItsBlocks) {
  const Scene scene = test::nestedScene();
  const EmbreeScene embree(scene, {});
  const Camera cam = test::closeCamera(scene, 70, 50);
  std::vector<uint8_t> touched;
  Framebuffer whole(cam.width(), cam.height());
  castEveryPixel(embree, cam, WorkShare{}, whole, touched, 2);
  BlockCover cover(cam.width(), cam.height());
  cover.add({5, 6, 33, 21});  // blocks 1..8 x 1..5
  cover.add({60, 40, 70, 50});
  for (bool packets : {true, false}) {
    Framebuffer fb(cam.width(), cam.height());
    const uint64_t rays = castEveryPixel(embree, cam, WorkShare{}, fb, touched, 2, packets, &cover);
    EXPECT_EQ(rays, uint64_t(32 * 20 + 10 * 10)) << packets;
    for (int y = 0; y < cam.height(); ++y)
      for (int x = 0; x < cam.width(); ++x) {
        const size_t i = fb.index(x, y);
        const bool cast = cover.covers(x, y);
        ASSERT_EQ(fb.id[i], cast ? whole.id[i] : kNoId) << x << ", " << y;
        ASSERT_EQ(fb.depth[i], cast ? whole.depth[i] : kEmptyDepth) << x << ", " << y;
      }
  }
}

}  // namespace
}  // namespace lzb
