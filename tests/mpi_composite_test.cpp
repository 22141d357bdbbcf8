// Compositing across ranks equals compositing the same buffers in one process, for every
// strategy and both key widths.
#include <gtest/gtest.h>

#include "mpi/collectives.hpp"
#include "mpi/composite.hpp"
#include "mpi/frame_tiles.hpp"
#include "mpi/group.hpp"

namespace lzb {
namespace {

// Every rank can build every rank's buffer, so each can check the root's result locally. Each
// rank covers a window of its own (so touched rectangles differ) with holes and many exact ties.
Framebuffer bufferOfRank(int rank, int w, int h, bool wideIds) {
  Framebuffer fb(w, h);
  uint64_t state = 1000 + uint64_t(rank);
  const int x0 = (rank * 7) % (w / 2), y0 = (rank * 5) % (h / 2);
  for (int y = y0; y < h - rank; ++y)
    for (int x = x0; x < w - 2 * rank; ++x) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      if ((state >> 60) < 6) continue;                // leave some pixels empty
      const float depth = float((state >> 40) % 8);  // few distinct depths: many exact ties
      uint64_t id = (state >> 20) % 1000;
      if (wideIds) id += uint64_t(1) << 40;
      fb.keepNearer(fb.index(x, y), depth + 1.0f, Rgba8(state >> 8), id);
    }
  return fb;
}

// In rank order: on equal (depth, ID) the lower rank's colour stays, as in the composite.
Framebuffer serialComposite(int size, int w, int h, bool wideIds) {
  Framebuffer expected = bufferOfRank(0, w, h, wideIds);
  for (int r = 1; r < size; ++r) compositeNearer(expected, bufferOfRank(r, w, h, wideIds));
  return expected;
}

// What the tiles composite sends for `touched`: each tile's 8-byte index and its pixels.
double tileBytesSent(const ScreenTiles& tiles, const std::vector<uint8_t>& touched, bool wide) {
  double bytes = 0.0;
  for (int t = 0; t < tiles.count(); ++t)
    if (touched[size_t(t)]) bytes += 8.0 + double(tiles.tile(t).pixels()) * (wide ? 16 : 12);
  return bytes;
}

class MpiComposite : public ::testing::TestWithParam<mpi::CompositeStrategy> {};

TEST_P(MpiComposite, KeysEqualTheSerialComposite) {
  const mpi::Group g = mpi::Group::world();
  ASSERT_GE(g.size, 2) << "run under mpiexec -n 2 or more";
  for (bool wide : {false, true}) {
    for (auto [w, h] : {std::pair{97, 31}, std::pair{64, 64}, std::pair{5, 300}}) {
      Framebuffer mine = bufferOfRank(g.rank, w, h, wide);
      const bool covered = mine.coveredCount() > 0;
      const mpi::CompositeStats stats = mpi::compositeAtRoot(g, mine, GetParam(), wide);
      if (!g.root()) {
        // A rank that drew something sends it.
        if (covered) {
          EXPECT_GT(stats.bytesSent, 0.0);
        }
        continue;
      }
      const Framebuffer expected = serialComposite(g.size, w, h, wide);
      EXPECT_EQ(mine.id, expected.id) << mpi::toString(GetParam()) << " wide " << wide;
      EXPECT_EQ(mine.depth, expected.depth) << mpi::toString(GetParam()) << " wide " << wide;
    }
  }
}

TEST_P(MpiComposite, NothingCoveredAnywhereStaysEmpty) {
  const mpi::Group g = mpi::Group::world();
  Framebuffer mine(40, 30);
  mpi::compositeAtRoot(g, mine, GetParam(), false);
  if (g.root()) {
    EXPECT_EQ(mine.coveredCount(), 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Strategies, MpiComposite,
                         ::testing::Values(mpi::CompositeStrategy::kReduce,
                                           mpi::CompositeStrategy::kBinarySwap,
                                           mpi::CompositeStrategy::kDirect,
                                           mpi::CompositeStrategy::kTiles),
                         [](const auto& info) { return mpi::toString(info.param); });

class MpiCompositeWithColour : public ::testing::TestWithParam<mpi::CompositeStrategy> {};

// 14 tiles, and 19 x 13 = 247 tiles: the tiles composite sends the latter in several chunks.
TEST_P(MpiCompositeWithColour, EqualsSerialComposite) {
  const mpi::Group g = mpi::Group::world();
  for (auto [w, h] : {std::pair{97, 31}, std::pair{300, 200}}) {
    const ScreenTiles tiles(w, h);
    for (const bool wide : {false, true}) {
      Framebuffer mine = bufferOfRank(g.rank, w, h, wide);
      std::vector<uint8_t> touched = touchedTiles(mine, tiles);
      const mpi::CompositeStats stats =
          mpi::compositeWithColour(g, mine, GetParam(), touched, wide);
      if (!g.root()) {
        if (GetParam() == mpi::CompositeStrategy::kTiles) {
          // Only the touched tiles: each rank's window leaves some of the frame's tiles out.
          EXPECT_DOUBLE_EQ(stats.bytesSent, tileBytesSent(tiles, touched, wide));
          if (w == 97) {
            EXPECT_LT(stats.bytesSent, double(w * h * (wide ? 16 : 12)));
          }
        } else {
          EXPECT_DOUBLE_EQ(stats.bytesSent, double(w * h * 16));
        }
        continue;
      }
      const Framebuffer expected = serialComposite(g.size, w, h, wide);
      EXPECT_EQ(mine.id, expected.id) << w << "x" << h << " wide " << wide;
      EXPECT_EQ(mine.depth, expected.depth) << w << "x" << h << " wide " << wide;
      EXPECT_EQ(mine.color, expected.color) << w << "x" << h << " wide " << wide;
      // The root's record holds every tile a rank sent: the tiles the composite covers.
      if (GetParam() == mpi::CompositeStrategy::kTiles) {
        EXPECT_EQ(touched, touchedTiles(expected, tiles));
      }
    }
  }
}

// Ranks that drew nothing (every other one) take part without sending a pixel.
TEST_P(MpiCompositeWithColour, RanksThatDrewNothingSendNothing) {
  const mpi::Group g = mpi::Group::world();
  const int w = 300, h = 200;
  const ScreenTiles tiles(w, h);
  const bool drew = g.rank % 2 == 0;
  Framebuffer mine = drew ? bufferOfRank(g.rank, w, h, false) : Framebuffer(w, h);
  std::vector<uint8_t> touched = touchedTiles(mine, tiles);
  const mpi::CompositeStats stats = mpi::compositeWithColour(g, mine, GetParam(), touched, false);
  if (!g.root()) {
    if (!drew && GetParam() == mpi::CompositeStrategy::kTiles) {
      EXPECT_EQ(stats.bytesSent, 0.0);
    }
    return;
  }
  Framebuffer expected(w, h);
  for (int r = 0; r < g.size; r += 2) compositeNearer(expected, bufferOfRank(r, w, h, false));
  EXPECT_EQ(mine.id, expected.id);
  EXPECT_EQ(mine.color, expected.color);
}

INSTANTIATE_TEST_SUITE_P(Strategies, MpiCompositeWithColour,
                         ::testing::Values(mpi::CompositeStrategy::kReduce,
                                           mpi::CompositeStrategy::kTiles),
                         [](const auto& info) { return mpi::toString(info.param); });

TEST(MpiCollectives, GatherAndBroadcastStrings) {
  const mpi::Group g = mpi::Group::world();
  const auto all = mpi::gatherStrings(g, "rank" + std::to_string(g.rank));
  if (g.root()) {
    ASSERT_EQ(all.size(), size_t(g.size));
    EXPECT_EQ(all[1], "rank1");
  }
  EXPECT_EQ(mpi::broadcastString(g, g.root() ? "from root" : ""), "from root");
  EXPECT_TRUE(mpi::broadcastFlag(g, g.root()));
}

}  // namespace
}  // namespace lzb
