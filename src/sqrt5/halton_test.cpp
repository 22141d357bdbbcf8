// Halton prefixes: low star discrepancy in the unit square, and surface samples spread by area.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "src/sqrt5/halton.hpp"

namespace lzb::sqrt5 {
namespace {

// The star discrepancy of a point set in [0, 1)^2, exactly: the largest difference between the
// fraction of points in an anchored box [0, x) x [0, y) (or its closed variant) and its area,
// over the boxes whose corners lie on the points' coordinates or on 1 (O(N^2)).
double starDiscrepancy(const std::vector<glm::dvec2>& pts) {
  const size_t n = pts.size();
  std::vector<size_t> byX(n);
  std::iota(byX.begin(), byX.end(), 0);
  std::sort(byX.begin(), byX.end(), [&](size_t a, size_t b) { return pts[a].x < pts[b].x; });
  std::vector<double> ys(n);
  for (size_t i = 0; i < n; ++i) ys[i] = pts[i].y;
  std::sort(ys.begin(), ys.end());
  ys.push_back(1.0);
  std::vector<size_t> rank(n);
  for (size_t i = 0; i < n; ++i)
    rank[i] = size_t(std::lower_bound(ys.begin(), ys.end(), pts[i].y) - ys.begin());
  std::vector<int> in(n + 1, 0);  // per y rank: points with x before the current box edge
  double worst = 0.0;
  for (size_t k = 0; k <= n; ++k) {
    const double x = k < n ? pts[byX[k]].x : 1.0;
    // open in x: the first k points; closed: also point k
    size_t open = 0;
    for (size_t m = 0; m <= n; ++m) {
      const double y = ys[m];
      const size_t closed = open + in[m] + (k < n && rank[byX[k]] <= m ? 1 : 0);
      worst = std::max(worst, double(closed) / n - x * y);
      worst = std::max(worst, x * y - double(open) / n);
      open += in[m];
    }
    if (k < n) ++in[rank[byX[k]]];
  }
  return worst;
}

// Niederreiter's bound for the 2-D Halton sequence in bases 2 and 3:
// D*_N <= (2 + prod_b ((b - 1) / (2 ln b) ln N + (b + 1) / 2)) / N, i.e. O(log^2 N / N).
double haltonBound(size_t n) {
  const double l = std::log(double(n));
  return (2.0 + (l / (2.0 * std::log(2.0)) + 1.5) * (l / std::log(3.0) + 2.0)) / double(n);
}

TEST(Halton, RadicalInverses) {
  EXPECT_EQ(radicalInverse(1, 2), 0.5);
  EXPECT_EQ(radicalInverse(6, 2), 0.375);  // 110 -> 0.011
  EXPECT_NEAR(radicalInverse(5, 3), 7.0 / 9.0, 1e-15);  // 12 -> 0.21
}

TEST(Halton, PrefixesHaveLowStarDiscrepancy) {
  double previous = 1.0;
  for (size_t n : {16u, 64u, 256u, 1024u}) {
    std::vector<glm::dvec2> pts;
    for (size_t k = 1; k <= n; ++k) pts.emplace_back(radicalInverse(k, 2), radicalInverse(k, 3));
    const double d = starDiscrepancy(pts);
    EXPECT_LE(d, haltonBound(n)) << n;
    EXPECT_LT(d, previous) << n;
    previous = d;
    // a uniform random set's discrepancy is about sqrt(log log N / N): Halton does far better
    if (n >= 256) {
      EXPECT_LT(d, 0.5 / std::sqrt(double(n))) << n;
    }
  }
  // The exact discrepancy of a known set: one point at (0.5, 0.5) gives 0.75.
  EXPECT_NEAR(starDiscrepancy({{0.5, 0.5}}), 0.75, 1e-12);
}

TEST(Halton, SurfaceSamplesFollowTheArea) {
  Mesh m;
  m.add({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);  // area 0.5
  m.add({2, 0, 0}, {5, 0, 0}, {2, 1, 0}, 0);  // area 1.5
  HaltonSurface h(m);
  EXPECT_DOUBLE_EQ(h.area(), 2.0);
  h.reserve(4096);
  ASSERT_EQ(h.size(), 4096u);
  size_t first = 0;
  for (uint64_t k = 0; k < h.size(); ++k) {
    first += h[k].triangle == 0;
    EXPECT_GE(h[k].a, 0.0f);
    EXPECT_GE(h[k].c, 0.0f);
    EXPECT_LE(h[k].a + h[k].c, 1.0f + 1e-6f);
  }
  EXPECT_NEAR(double(first) / 4096.0, 0.25, 2.0 / 4096.0);
  h.reserve(100);  // never shrinks: a shorter prefix is the same vector's start
  EXPECT_EQ(h.size(), 4096u);
}

}  // namespace
}  // namespace lzb::sqrt5
