// The sqrt(5) lattice: spacing and rotation per level, one parent per point, and the boundary
// children that let the refined samples cover the whole unit square.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <utility>

#include "src/sqrt5/lattice.hpp"

namespace lzb::sqrt5 {
namespace {

TEST(Sqrt5Lattice, SpacingShrinksBySqrt5AndRotatesByAtanHalf) {
  const Sqrt5Lattice l(4);
  for (int i = 0; i <= kMaxLevels; ++i) {
    const double h = 0.25 / std::pow(std::sqrt(5.0), i);
    EXPECT_NEAR(glm::length(l.u(i)), h, 1e-12 * h);
    EXPECT_NEAR(glm::length(l.v(i)), h, 1e-12 * h);
    EXPECT_NEAR(glm::dot(l.u(i), l.v(i)), 0.0, 1e-12 * h * h);
    const double angle = std::atan2(l.u(i).y, l.u(i).x);
    EXPECT_NEAR(std::remainder(angle - i * std::atan(0.5), 2 * std::numbers::pi), 0.0, 1e-9);
  }
  // Level i is a sublattice of level i + 1 (index 5): u_i = 2 u_{i+1} - v_{i+1}, v_i = u + 2 v.
  for (int i = 0; i < kMaxLevels; ++i) {
    const glm::dvec2 u = 2.0 * l.u(i + 1) - l.v(i + 1), v = l.u(i + 1) + 2.0 * l.v(i + 1);
    EXPECT_NEAR(glm::length(u - l.u(i)), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(v - l.v(i)), 0.0, 1e-15);
  }
}

// Every sample of a global refinement to `levels`, each once (the leaves of the forest).
std::vector<glm::dvec2> refineEverywhere(const Sqrt5Lattice& l, int levels) {
  std::vector<std::pair<glm::dvec2, int>> stack;
  for (int j = 0; j <= l.initialSide(); ++j)
    for (int i = 0; i <= l.initialSide(); ++i) stack.emplace_back(l.root(i, j), 0);
  std::vector<glm::dvec2> out, kids;
  while (!stack.empty()) {
    auto [p, level] = stack.back();
    stack.pop_back();
    for (; level < levels; ++level) {
      kids.clear();
      l.children(p, level, kids);
      for (const glm::dvec2& k : kids) stack.emplace_back(k, level + 1);
    }
    out.push_back(p);
  }
  return out;
}

// The largest distance from a point of the square to its nearest sample, over a fine grid.
double coveringRadius(const std::vector<glm::dvec2>& samples) {
  double worst = 0.0;
  constexpr int kProbe = 120;
  for (int j = 0; j <= kProbe; ++j)
    for (int i = 0; i <= kProbe; ++i) {
      const glm::dvec2 q(double(i) / kProbe, double(j) / kProbe);
      double best = 1e300;
      for (const glm::dvec2& s : samples) best = std::min(best, glm::dot(s - q, s - q));
      worst = std::max(worst, std::sqrt(best));
    }
  return worst;
}

TEST(Sqrt5Lattice, RefinedSamplesAreDistinctInsideAndCoverTheSquare) {
  const Sqrt5Lattice l(2);
  for (int levels = 1; levels <= 4; ++levels) {
    const std::vector<glm::dvec2> s = refineEverywhere(l, levels);
    std::set<std::pair<long, long>> seen;
    for (const glm::dvec2& p : s) {
      EXPECT_TRUE(Sqrt5Lattice::inside(p));
      EXPECT_TRUE(seen.emplace(std::lround(p.x * 1e9), std::lround(p.y * 1e9)).second)
          << "duplicate sample " << p.x << " " << p.y;
    }
    // An infinite square lattice of step h leaves no point farther than h / sqrt 2 from a
    // sample; the boundary children keep the square's edges and corners within h too (without
    // them the fractal edges of Fig. 3d leave gaps of several h).
    const double h = glm::length(l.u(levels));
    EXPECT_LE(coveringRadius(s), 1.0 * h) << "levels " << levels;
    // The square holds about 1 / h^2 lattice points; the border adds a ring.
    EXPECT_LE(double(s.size()), 1.0 / (h * h) + 4.0 / h + 4.0);
  }
}

}  // namespace
}  // namespace lzb::sqrt5
