// Theorem 1 on synthetic cells: with m = q ln q + c q drawings, the sample of a cell holds a
// triangle of every one of its q face-sized groups -- so whatever group a viewpoint sees, a
// sampled triangle is visible -- with probability p = exp(-exp(-c)).
//
// The cell is the proof's worst case: q parallel layers, each as large as the cell's face
// (A(P(u)) / A(B(u)) = q), of equal-area triangles; a viewer looking along the layers' normal sees
// the first layer from one side and the last from the other, and a layer's worth of surface
// hides the rest. Each trial builds the tree with another seed; the root draws from all triangles
// (its eight children are leaves). The empirical rate must match the exact coupon-collector
// probability for this q and m within 4 binomial standard deviations, and the theorem's
// asymptotic p within that plus the finite-q gap (computed, < 0.02 at q = 64).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "src/sampletree/sample_draw.hpp"
#include "src/sampletree/tree_build.hpp"

namespace lzb::sampletree {
namespace {

constexpr int kLayers = 64;     // q
constexpr int kGrid = 4;        // squares per layer side (2 triangles each)
constexpr int kTrials = 2000;

TriangleInput layeredCell() {
  TriangleInput in;
  const float side = 0.99f, step = side / kGrid;
  uint64_t id = 0;
  for (int layer = 0; layer < kLayers; ++layer) {
    const float z = (float(layer) + 0.5f) / kLayers;
    for (int i = 0; i < kGrid; ++i)
      for (int j = 0; j < kGrid; ++j) {
        const glm::vec3 a(step * float(i), step * float(j), z), b = a + glm::vec3(step, 0, 0),
                        c = a + glm::vec3(0, step, 0), d = a + glm::vec3(step, step, 0);
        in.add(a, b, d, id++, 0xffffffffu);
        in.add(a, d, c, id++, 0xffffffffu);
      }
  }
  return in;
}

int layerOf(uint64_t id) { return int(id / (2 * kGrid * kGrid)); }

// P(every one of q bins holds a ball after m uniform throws), by the distribution of bins hit.
double coverProbability(int q, uint32_t m) {
  std::vector<double> p(size_t(q) + 1, 0.0);
  p[0] = 1.0;
  for (uint32_t t = 0; t < m; ++t)
    for (int k = q; k >= 0; --k)
      p[size_t(k)] = p[size_t(k)] * double(k) / q + (k > 0 ? p[size_t(k) - 1] * double(q - k + 1) / q : 0.0);
  return p[size_t(q)];
}

class Theorem1 : public ::testing::TestWithParam<double> {};

TEST_P(Theorem1, EmpiricalProbabilityMatches) {
  const double c = GetParam();
  const TriangleInput in = layeredCell();
  int covered = 0, frontSeen = 0, backSeen = 0;
  uint32_t draws = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const SampleTree tree =
        buildTree(in, TreeParams{c, uint64_t(trial) + 1, 4 * kLayers}, 1);
    const TreeNode& root = tree.nodes[0];
    ASSERT_EQ(root.level, 0);
    ASSERT_EQ(tree.nodes.size(), 9u) << "the root's children must be leaves";
    draws = root.draws;
    std::set<int> layers;
    for (uint64_t k = root.firstTriangle; k < root.firstTriangle + root.triangleCount; ++k)
      layers.insert(layerOf(tree.ids[k]));
    covered += int(layers.size()) == kLayers;
    frontSeen += layers.count(0) > 0;
    backSeen += layers.count(kLayers - 1) > 0;
  }
  ASSERT_EQ(draws, sampleDraws(kLayers, c)) << "q must come out as the layer count";
  const double exact = coverProbability(kLayers, draws);
  const double theorem = std::exp(-std::exp(-c));
  const double observed = double(covered) / kTrials;
  const double sigma = std::sqrt(exact * (1 - exact) / kTrials);
  EXPECT_NEAR(observed, exact, 4 * sigma) << "c " << c;
  const double gap = std::abs(exact - theorem);
  EXPECT_LT(gap, 0.02) << "finite-q gap at c " << c;
  EXPECT_NEAR(observed, theorem, 4 * sigma + gap) << "c " << c;
  // A single viewing direction sees a sampled triangle at least as often as every group is hit.
  EXPECT_GE(frontSeen, covered);
  EXPECT_GE(backSeen, covered);
}

INSTANTIATE_TEST_SUITE_P(SeveralC, Theorem1, ::testing::Values(0.5, 1.5, 3.0));

}  // namespace
}  // namespace lzb::sampletree
