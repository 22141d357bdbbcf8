// Compositing across 2 ranks equals compositing the same buffers in one process.
#include <gtest/gtest.h>

#include "mpi/composite.hpp"
#include "mpi/group.hpp"

namespace lzb {
namespace {

// Every rank can build every rank's buffer, so each can check the root's result locally.
Framebuffer bufferOfRank(int rank, int w, int h) {
  Framebuffer fb(w, h);
  uint64_t state = 1000 + uint64_t(rank);
  for (size_t i = 0; i < fb.size(); ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    if ((state >> 60) < 6) continue;  // leave some pixels empty
    const float depth = float((state >> 40) % 8);  // few distinct depths: many exact ties
    fb.keepNearer(i, depth, Rgba8(state >> 8), (state >> 20) % 1000);
  }
  return fb;
}

TEST(MpiComposite, EqualsSerialComposite) {
  const mpi::Group g = mpi::Group::world();
  ASSERT_GE(g.size, 2) << "run under mpiexec -n 2";
  const int w = 97, h = 31;
  Framebuffer mine = bufferOfRank(g.rank, w, h);
  const mpi::CompositeStats stats = mpi::compositeAtRoot(g, mine);
  if (!g.root()) {
    EXPECT_DOUBLE_EQ(stats.bytesSent, double(w * h * 16));
    return;
  }
  Framebuffer expected = bufferOfRank(g.size - 1, w, h);
  for (int r = g.size - 2; r >= 0; --r) compositeNearer(expected, bufferOfRank(r, w, h));
  EXPECT_EQ(mine.id, expected.id);
  EXPECT_EQ(mine.depth, expected.depth);
  EXPECT_EQ(mine.color, expected.color);
}

TEST(MpiComposite, GatherAndBroadcastStrings) {
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

int main(int argc, char** argv) {
  lzb::mpi::Session session(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  const int failed = RUN_ALL_TESTS();
  // Every rank must agree on the verdict, or mpiexec could report success for a failing rank.
  int anyFailed = 0;
  MPI_Allreduce(&failed, &anyFailed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return anyFailed;
}
