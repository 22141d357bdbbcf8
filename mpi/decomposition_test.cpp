#include "mpi/decomposition.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "src/core/error.hpp"

namespace lzb {
namespace {

TEST(Decomposition, IdRangesCoverTheTotalOnceInRankOrder) {
  for (uint64_t total : {0ull, 1ull, 7ull, 1000ull, (1ull << 46) + 3}) {
    for (int size : {1, 2, 3, 5, 64}) {
      uint64_t next = 0, longest = 0, shortest = ~0ull;
      for (int rank = 0; rank < size; ++rank) {
        const IdRange r = shareRange(total, {rank, size});
        EXPECT_EQ(r.begin, next);
        // The holder of a range's first and last items is its rank.
        if (r.end > r.begin) {
          EXPECT_EQ(shareRankOf(r.begin, total, size), rank);
          EXPECT_EQ(shareRankOf(r.end - 1, total, size), rank);
        }
        longest = std::max(longest, r.end - r.begin);
        shortest = std::min(shortest, r.end - r.begin);
        next = r.end;
      }
      EXPECT_EQ(next, total);
      EXPECT_LE(longest - shortest, 1u) << total << " over " << size;
    }
  }
}

TEST(Decomposition, ScreenTilesCoverTheImageOnceAcrossRanks) {
  const ScreenTiles tiles(100, 37);
  EXPECT_EQ(tiles.count(), 7 * 3);
  for (int size : {1, 2, 3, 4}) {
    std::vector<int> hits(100 * 37, 0);
    for (int rank = 0; rank < size; ++rank)
      for (int t : tiles.owned({rank, size})) {
        EXPECT_EQ(t % size, rank);
        const TileRect r = tiles.tile(t);
        for (int y = r.y0; y < r.y1; ++y)
          for (int x = r.x0; x < r.x1; ++x) ++hits[size_t(y * 100 + x)];
      }
    for (int h : hits) ASSERT_EQ(h, 1) << size << " ranks";
  }
}

TEST(Decomposition, TilesByCostGoOnceWithEqualShares) {
  const ScreenTiles tiles(100, 37);
  // A skyline: the rays of a street view gather in one band of tiles.
  std::vector<double> costs(size_t(tiles.count()), 0.0);
  for (int t = 7; t < 14; ++t) costs[size_t(t)] = 10.0 + t;
  for (int size : {1, 2, 3}) {
    std::vector<int> owner(size_t(tiles.count()), -1);
    for (int rank = 0; rank < size; ++rank) {
      double cost = 0.0;
      for (int t : tiles.ownedByCost(costs, {rank, size})) {
        EXPECT_EQ(owner[size_t(t)], -1);
        owner[size_t(t)] = rank;
        cost += costs[size_t(t)];
      }
      EXPECT_GT(cost, 0.0) << rank << " of " << size << ": every rank casts rays";
      EXPECT_NEAR(cost, 126.0 / size, 23.0) << rank << " of " << size;
    }
    for (int o : owner) EXPECT_GE(o, 0);
  }
  EXPECT_EQ(parseTileDeal("cost", "--tile-deal"), TileDeal::kCost);
  EXPECT_EQ(toString(parseTileDeal("interleaved", "--tile-deal")), "interleaved");
  EXPECT_THROW(parseTileDeal("random", "--tile-deal"), InputError);
}

TEST(Decomposition, ItemsByCostGoOnceInContiguousRunsOfAboutEqualCost) {
  std::vector<double> costs;
  for (int i = 0; i < 200; ++i) costs.push_back(1.0 + (i * 37) % 11);
  const double total = std::accumulate(costs.begin(), costs.end(), 0.0);
  for (int size : {1, 2, 3, 7}) {
    std::vector<int> owner(costs.size(), -1);
    for (int rank = 0; rank < size; ++rank) {
      const std::vector<uint32_t> mine = dealByCost(costs, {rank, size});
      double cost = 0.0;
      for (size_t k = 0; k < mine.size(); ++k) {
        EXPECT_EQ(owner[mine[k]], -1);
        owner[mine[k]] = rank;
        if (k) {
          EXPECT_EQ(mine[k], mine[k - 1] + 1) << "contiguous";
        }
        cost += costs[mine[k]];
      }
      // A run is within one item's cost (at most 11) of its equal share.
      EXPECT_NEAR(cost, total / size, 11.0) << rank << " of " << size;
    }
    for (size_t i = 1; i < owner.size(); ++i) EXPECT_GE(owner[i], owner[i - 1]) << "rank order";
    for (int o : owner) EXPECT_GE(o, 0);
  }
}

TEST(Decomposition, ZeroCostItemsAllGoToTheFirstRank) {
  const std::vector<double> costs(5, 0.0);
  EXPECT_EQ(dealByCost(costs, {0, 3}).size(), 5u);
  EXPECT_TRUE(dealByCost(costs, {1, 3}).empty());
}

}  // namespace
}  // namespace lzb
