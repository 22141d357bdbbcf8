#include "src/regions/region_cut.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <numeric>

namespace lzb::regions {
namespace {

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
    if (regionOf[u] == 0)
      leftMax = std::max(leftMax, g.centres[u].x);
    else
      rightMin = std::min(rightMin, g.centres[u].x);
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
}  // namespace lzb::regions
