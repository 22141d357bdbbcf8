// searchForward against std::upper_bound: every step length (none, inside the eight compares,
// past them into the gallop, to the end), zero-area entries, targets beyond the list.
#include "src/core/area_sampling.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace lzb {
namespace {

uint64_t expected(const std::vector<double>& P, uint64_t from, double target) {
  const auto it = std::upper_bound(P.begin() + long(from), P.end(), target);
  return it == P.end() ? P.size() - 1 : uint64_t(it - P.begin());
}

TEST(AreaSampling, SearchForwardFindsTheFirstPrefixAboveTheTarget) {
  std::mt19937_64 rng(7);
  for (const size_t size : {1u, 7u, 8u, 9u, 40u, 1000u}) {
    std::vector<double> P(size);
    double sum = 0.0;
    for (double& p : P) {
      // One entry in four has no area: equal prefix sums must be skipped alike.
      sum += rng() % 4 == 0 ? 0.0 : double(rng() % 100 + 1);
      p = sum;
    }
    for (int trial = 0; trial < 2000; ++trial) {
      const uint64_t from = rng() % size;
      const double lo = from ? P[from - 1] : 0.0;
      // From just past the entry before `from` up to beyond the end.
      const double target = lo + double(rng() % 1000) / 1000.0 * (sum * 1.1 - lo);
      ASSERT_EQ(searchForward(P.data(), size, from, target), expected(P, from, target))
          << "size " << size << " from " << from << " target " << target;
    }
  }
}

}  // namespace
}  // namespace lzb
