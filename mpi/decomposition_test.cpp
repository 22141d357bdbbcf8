#include "mpi/decomposition.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <omp.h>

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

// Units on a 3-D grid with uneven costs: the regions are boxes of about equal cost.
struct GridUnits {
  std::vector<glm::dvec3> centres;
  std::vector<uint64_t> triangles;
};

GridUnits gridUnits(int side) {
  GridUnits g;
  for (int z = 0; z < side; ++z)
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        g.centres.push_back({x * 2.0, y * 1.0, z * 0.5});  // x the widest: cut first
        g.triangles.push_back(1 + uint64_t((x * 7 + y * 3 + z) % 5));
      }
  return g;
}

TEST(Regions, EveryUnitGoesToOneRegionOfAboutEqualTriangles) {
  const GridUnits g = gridUnits(12);
  const uint64_t total = std::accumulate(g.triangles.begin(), g.triangles.end(), uint64_t(0));
  for (uint32_t regions : {1u, 2u, 3u, 8u, 13u}) {
    const std::vector<uint32_t> regionOf = splitIntoRegions(g.centres, g.triangles, regions);
    ASSERT_EQ(regionOf.size(), g.centres.size());
    std::vector<uint64_t> count(regions, 0);
    for (size_t u = 0; u < regionOf.size(); ++u) {
      ASSERT_LT(regionOf[u], regions);
      count[regionOf[u]] += g.triangles[u];
    }
    // Each of the log2(regions) cuts is off by at most one unit (5 triangles) per level.
    for (uint32_t r = 0; r < regions; ++r)
      EXPECT_NEAR(double(count[r]), double(total) / regions, 5.0 * 4) << r << " of " << regions;
  }
}

TEST(Regions, TwoRegionsAreTwoHalfSpacesAlongTheWidestAxis) {
  const GridUnits g = gridUnits(6);
  const std::vector<uint32_t> regionOf = splitIntoRegions(g.centres, g.triangles, 2);
  double leftMax = -1e300, rightMin = 1e300;
  for (size_t u = 0; u < regionOf.size(); ++u) {
    if (regionOf[u] == 0) leftMax = std::max(leftMax, g.centres[u].x);
    else rightMin = std::min(rightMin, g.centres[u].x);
  }
  EXPECT_LE(leftMax, rightMin) << "region 0 lies below region 1 along x";
}

TEST(Regions, DependOnTheUnitsAloneAndSpreadOverTheRanksBalanced) {
  const GridUnits g = gridUnits(8);
  const std::vector<uint32_t> a = splitIntoRegions(g.centres, g.triangles, 7);
  EXPECT_EQ(a, splitIntoRegions(g.centres, g.triangles, 7)) << "deterministic";
  std::vector<uint64_t> regionTriangles(7, 0);
  for (size_t u = 0; u < a.size(); ++u) regionTriangles[a[u]] += g.triangles[u];
  const uint64_t largest = *std::max_element(regionTriangles.begin(), regionTriangles.end());
  for (int size : {1, 2, 3, 7, 9}) {
    std::vector<int> owner(7, -1);
    std::vector<uint64_t> held(size_t(size), 0);
    for (int rank = 0; rank < size; ++rank)
      for (uint32_t r : regionsOfRank(regionTriangles, {rank, size})) {
        EXPECT_EQ(owner[r], -1) << "region " << r << " held twice";
        owner[r] = rank;
        held[size_t(rank)] += regionTriangles[r];
      }
    for (size_t r = 0; r < owner.size(); ++r) {
      EXPECT_GE(owner[r], 0) << "region " << r << " held by no rank of " << size;
    }
    const auto [least, most] = std::minmax_element(held.begin(), held.end());
    if (size <= 7) {
      EXPECT_LE(*most - *least, largest) << size << " ranks";
    }
  }
}

TEST(Regions, EqualRegionsGoRoundRobinUnevenOnesStillBalance) {
  // Neighbours in the k-d order (in space) on different ranks.
  const std::vector<uint64_t> equal(5, 5);
  EXPECT_EQ(regionsOfRank(equal, {0, 3}), (std::vector<uint32_t>{0, 3}));
  EXPECT_EQ(regionsOfRank(equal, {1, 3}), (std::vector<uint32_t>{1, 4}));
  EXPECT_EQ(regionsOfRank(equal, {2, 3}), (std::vector<uint32_t>{2}));
  const std::vector<uint64_t> uneven = {10, 1, 10, 1};
  EXPECT_EQ(regionsOfRank(uneven, {0, 2}), (std::vector<uint32_t>{0, 3}));
  EXPECT_EQ(regionsOfRank(uneven, {1, 2}), (std::vector<uint32_t>{1, 2}));
}

TEST(Regions, UnitTrianglesGiveTheWeightedSplitOnAnyThreadCount) {
  // More units than a task's threshold (2^16), in a scattered order, with ties on an axis.
  const size_t n = 300000;
  std::vector<glm::dvec3> centres(n);
  uint64_t x = 88172645463325252ull;
  for (glm::dvec3& c : centres) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    c = {double(x % 1000), double((x >> 20) % 1000) * 0.5, double((x >> 40) % 7)};
  }
  const std::vector<uint64_t> ones(n, 1);
  omp_set_num_threads(1);
  const std::vector<uint32_t> weighted = splitIntoRegions(centres, ones, 37);
  omp_set_num_threads(2);
  EXPECT_EQ(splitIntoRegions(centres, {}, 37), weighted) << "one triangle each, 2 threads";
  EXPECT_EQ(splitIntoRegions(centres, ones, 37), weighted) << "weighted, 2 threads";
  std::vector<uint64_t> perRegion(37, 0);
  for (uint32_t r : weighted) ++perRegion[r];
  const auto [fewest, most] = std::minmax_element(perRegion.begin(), perRegion.end());
  EXPECT_LE(*most - *fewest, 1u) << "equal counts";
}

TEST(Regions, FewerUnitsThanRegionsLeaveRegionsEmpty) {
  const std::vector<glm::dvec3> centres = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const std::vector<uint64_t> triangles = {5, 5, 5};
  const std::vector<uint32_t> regionOf = splitIntoRegions(centres, triangles, 8);
  std::vector<uint32_t> sorted = regionOf;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::unique(sorted.begin(), sorted.end()) - sorted.begin(), 3) << "one unit each";
  EXPECT_TRUE(splitIntoRegions({}, {}, 4).empty());
}

}  // namespace
}  // namespace lzb
