#include "src/splat/splatter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>

#include "src/core/framebuffer.hpp"

namespace lzb {
namespace {

SplatSetup setup(int splat) {
  SplatSetup s;
  s.width = 8;
  s.height = 6;
  s.pixelScale = 4.0;  // a point at depth z and x = z moves 4 pixels right of the centre
  s.nearPlane = 0.5;
  s.farPlane = 100.0;
  s.splat = splat;
  return s;
}

// Puts camera-space points (x, y, z, id) and returns the resolved frame.
template <bool kWide, bool kPixel>
Framebuffer splat(const SplatSetup& s, const std::vector<std::array<double, 4>>& points) {
  KeyBuffer keys;
  keys.reset(s.width, s.height, kWide, 1);
  PointSplatter<kWide, kPixel> out(s, keys);
  for (const auto& p : points) out.add(float(p[0]), float(p[1]), float(p[2]), uint64_t(p[3]));
  out.flush();
  Framebuffer fb(s.width, s.height);
  keys.resolve(fb, 1);
  return fb;
}

TEST(Splatter, PointLandsInThePixelHoldingItsProjection) {
  // x = 0.3 z -> px = 4 + 4 * 0.3 = 5.2; y = -0.1 z -> py = 3 + 0.4 = 3.4: pixel (5, 3).
  const Framebuffer fb = splat<false, true>(setup(1), {{0.6, -0.2, 2.0, 9}});
  EXPECT_EQ(fb.coveredCount(), 1u);
  EXPECT_EQ(fb.id[fb.index(5, 3)], 9u);
  EXPECT_EQ(fb.depth[fb.index(5, 3)], 2.0f);
}

TEST(Splatter, DropsPointsOutsideTheClipPlanesAndTheImage) {
  const Framebuffer fb = splat<false, true>(
      setup(1), {{0.0, 0.0, 0.25, 1}, {0.0, 0.0, 200.0, 2}, {10.0, 0.0, 1.0, 3}, {0.0, 0.0, 1.0, 4}});
  EXPECT_EQ(fb.coveredCount(), 1u);
  EXPECT_EQ(fb.id[fb.index(4, 3)], 4u);
}

TEST(Splatter, SplatCoversTheDByDPixelsNearestToThePoint) {
  // px = 5.2, py = 3.4; d = 2 covers the centres 4.5..5.5 and 2.5..3.5: pixels x 4-5, y 2-3.
  const Framebuffer fb = splat<false, false>(setup(2), {{0.6, -0.2, 2.0, 9}});
  EXPECT_EQ(fb.coveredCount(), 4u);
  for (int y : {2, 3})
    for (int x : {4, 5}) EXPECT_EQ(fb.id[fb.index(x, y)], 9u) << x << "," << y;
  // Clipped at the image border: d = 3 at the corner covers what is inside.
  const Framebuffer corner = splat<false, false>(setup(3), {{-1.0, 0.75, 1.0, 5}});
  EXPECT_EQ(corner.coveredCount(), 4u);
  EXPECT_EQ(corner.id[corner.index(0, 0)], 5u);
}

TEST(Splatter, DiscCoversOnlyTheCentresWithinHalfTheSize) {
  // px = 5.2, py = 3.4, d = 4: the square covers x 3-6, y 1-4 (16 pixels); the disc of radius 2
  // keeps the centres within 2 of the point, e.g. (5, 3) at 0.36 but not (3, 1) at 2.9.
  SplatSetup s = setup(4);
  s.disc = true;
  const Framebuffer fb = splat<false, false>(s, {{0.6, -0.2, 2.0, 9}});
  int expected = 0;
  for (int y = 1; y <= 4; ++y)
    for (int x = 3; x <= 6; ++x) {
      const double ex = x + 0.5 - 5.2, ey = y + 0.5 - 3.4;
      const bool in = ex * ex + ey * ey <= 4.0;
      expected += in;
      EXPECT_EQ(fb.id[fb.index(x, y)], in ? 9u : kNoId) << x << "," << y;
    }
  EXPECT_EQ(fb.coveredCount(), size_t(expected));
  EXPECT_LT(expected, 16);
  EXPECT_GE(expected, 9);
}

TEST(Splatter, NearestPointWinsWhateverTheOrderAndKeyWidth) {
  std::mt19937 rng(3);
  std::vector<std::array<double, 4>> points;
  for (int k = 0; k < 5000; ++k)
    points.push_back({std::uniform_real_distribution<double>(-1.0, 1.0)(rng),
                      std::uniform_real_distribution<double>(-0.7, 0.7)(rng),
                      double(1 + rng() % 4), double(rng() % 50)});
  const Framebuffer a = splat<false, true>(setup(1), points);
  std::reverse(points.begin(), points.end());
  const Framebuffer b = splat<false, true>(setup(1), points);
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.depth, b.depth);
  if (wideKeysSupported()) {
    const Framebuffer c = splat<true, true>(setup(1), points);
    EXPECT_EQ(a.id, c.id);
    const Framebuffer d2n = splat<false, false>(setup(2), points);
    const Framebuffer d2w = splat<true, false>(setup(2), points);
    EXPECT_EQ(d2n.id, d2w.id);
  }
}

}  // namespace
}  // namespace lzb
