#include "mpi/frame_tiles.hpp"

#include <gtest/gtest.h>

namespace lzb {
namespace {

// 40 x 20 pixels: tiles of 16 make a 3 x 2 grid whose last column and row are partial.
Framebuffer frameWith(std::initializer_list<std::pair<int, int>> covered) {
  Framebuffer fb(40, 20);
  for (const auto& [x, y] : covered) fb.keepNearer(fb.index(x, y), 1.0f, Rgba8(7), 3);
  return fb;
}

TEST(FrameTiles, TouchedTilesAreThoseWithACoveredPixel) {
  const Framebuffer fb = frameWith({{0, 0}, {39, 19}, {17, 3}});
  EXPECT_EQ(touchedTiles(fb, ScreenTiles(40, 20)), (std::vector<uint8_t>{1, 1, 0, 0, 0, 1}));
}

TEST(FrameTiles, TilePixelsListsTheMarkedTilesRowByRow) {
  const Framebuffer fb(40, 20);
  const std::vector<uint32_t> pixels = tilePixels(fb, ScreenTiles(40, 20), {0, 0, 0, 0, 0, 1});
  ASSERT_EQ(pixels.size(), 8u * 4u);  // the corner tile: x 32..39, y 16..19
  EXPECT_EQ(pixels.front(), fb.index(32, 16));
  EXPECT_EQ(pixels[8], fb.index(32, 17));
  EXPECT_EQ(pixels.back(), fb.index(39, 19));
}

TEST(FrameTiles, ClearTilesEmptiesTheMarkedTilesAlone) {
  Framebuffer fb = frameWith({{0, 0}, {39, 19}, {17, 3}});
  clearTiles(fb, ScreenTiles(40, 20), {1, 0, 0, 0, 0, 1});
  EXPECT_EQ(fb.coveredCount(), 1u);
  EXPECT_TRUE(fb.covered(fb.index(17, 3)));
  EXPECT_EQ(fb.color[fb.index(0, 0)], kBackground);
  EXPECT_EQ(fb.depth[fb.index(39, 19)], kEmptyDepth);
}

}  // namespace
}  // namespace lzb
