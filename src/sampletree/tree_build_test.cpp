// The sample tree's construction: every triangle stored once, sample sizes by Theorem 1, every
// triangle inside its node's bounding sphere, the same tree on any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <cmath>
#include <vector>

#include "src/core/error.hpp"
#include "src/sampletree/cell_octree.hpp"
#include "src/sampletree/sample_draw.hpp"
#include "tests/support/random_geometry.hpp"
#include "src/sampletree/tree_build.hpp"
#include "src/scene/load.hpp"

namespace lzb::sampletree {
namespace {

SampleTree scatteredTree(double c = 13.8, int threads = 1) {
  return buildTree(test::scatteredTriangles(20000, 0.01f), TreeParams{c, 5, 16}, threads);
}

TEST(TreeBuild, EveryTriangleStoredExactlyOnce) {
  const TriangleInput in = test::scatteredTriangles(20000, 0.01f);
  const SampleTree tree = buildTree(in, TreeParams{13.8, 5, 16}, 2);
  ASSERT_EQ(tree.triangles(), in.size());
  std::vector<uint64_t> ids = tree.ids;
  std::sort(ids.begin(), ids.end());
  for (size_t k = 0; k < ids.size(); ++k) ASSERT_EQ(ids[k], k);
  // And with the input's own geometry and colour.
  for (size_t k = 0; k < tree.triangles(); ++k) {
    const uint64_t id = tree.ids[k];
    for (int v = 0; v < 3; ++v) ASSERT_EQ(tree.positions[3 * k + size_t(v)], in.vertex(id, v));
    ASSERT_EQ(tree.colours[k], in.colours[id]);
  }
}

TEST(TreeBuild, SceneTrianglesStoredExactlyOnce) {
  const Scene scene = loadScene("builtin:sphereflake?depth=2", true);
  const SampleTree tree = buildTree(scene, TreeParams{}, 2);
  ASSERT_EQ(tree.triangles(), scene.expandedTriangles());
  std::vector<uint64_t> ids = tree.ids;
  std::sort(ids.begin(), ids.end());
  EXPECT_TRUE(std::adjacent_find(ids.begin(), ids.end()) == ids.end());
  EXPECT_EQ(ids.back(), scene.expandedTriangles() - 1);
}

// P(u) of every cell, from the octree before sampling, summed here from its triangles.
struct CellTotals {
  double area = 0.0;
  uint64_t count = 0;
};
CellTotals subtreeTotals(const CellOctree& oct, const std::vector<double>& areas, int32_t u,
                         std::map<std::array<uint32_t, 4>, CellTotals>& out) {
  const BuildNode& n = oct.nodes[size_t(u)];
  CellTotals t;
  for (uint32_t k : n.own) t.area += areas[k];
  t.count = n.own.size();
  for (int32_t ch : n.child) {
    if (ch == kNoChild) continue;
    const CellTotals c = subtreeTotals(oct, areas, ch, out);
    t.area += c.area;
    t.count += c.count;
  }
  out[{n.level, n.cell[0], n.cell[1], n.cell[2]}] = t;
  return t;
}

TEST(TreeBuild, SampleSizesFollowTheorem1) {
  const double c = 13.8;
  const TriangleInput in = test::scatteredTriangles(20000, 0.01f);
  const SampleTree tree = buildTree(in, TreeParams{c, 5, 16}, 1);
  std::vector<double> areas(in.size());
  for (size_t k = 0; k < in.size(); ++k) areas[k] = in.area(k);
  const CellOctree oct = buildCellOctree(in, areas, 16);
  std::map<std::array<uint32_t, 4>, CellTotals> cells;
  subtreeTotals(oct, areas, 0, cells);
  size_t inner = 0;
  for (size_t i = 0; i < tree.nodes.size(); ++i) {
    const TreeNode& n = tree.nodes[i];
    const CellTotals& p = cells.at({n.level, n.cell[0], n.cell[1], n.cell[2]});
    ASSERT_EQ(p.count, n.subtreeTriangles) << "node " << i;
    if (n.draws == 0) continue;  // a leaf of the octree
    ++inner;
    const double side = tree.cellSize(n);
    const double q = std::max(1.0, std::ceil(p.area / (side * side)));
    ASSERT_EQ(double(n.draws), std::ceil(q * std::log(q) + c * q)) << "node " << i << " q " << q;
    // Drawings with replacement: never more distinct triangles than drawings.
    ASSERT_LE(n.triangleCount, n.draws) << "node " << i;
  }
  EXPECT_GT(inner, 50u);
}

TEST(TreeBuild, SampleSizeFormula) {
  EXPECT_EQ(sampleFactor(0.5, 1.0), 1u);
  EXPECT_EQ(sampleFactor(2.01, 1.0), 3u);
  EXPECT_EQ(sampleFactor(8.0, 2.0), 2u);
  EXPECT_EQ(sampleDraws(1, 13.8), 14u);                                     // 0 + 13.8
  EXPECT_EQ(sampleDraws(10, 13.8), uint32_t(std::ceil(10 * std::log(10.0) + 138.0)));  // 161.03
  EXPECT_EQ(sampleDraws(10, 13.8), 162u);
}

TEST(TreeBuild, TrianglesLieInTheirNodesBoundingSphere) {
  const SampleTree tree = scatteredTree();
  for (const TreeNode& n : tree.nodes) {
    const glm::dvec3 centre = tree.cellBounds(n).center();
    const double r = 0.5 * std::sqrt(3.0) * tree.cellSize(n) * (1 + 1e-9);
    for (uint64_t k = n.firstTriangle; k < n.firstTriangle + n.triangleCount; ++k)
      for (int v = 0; v < 3; ++v)
        ASSERT_LE(glm::length(glm::dvec3(tree.positions[3 * k + size_t(v)]) - centre), r);
  }
}

TEST(TreeBuild, SmallTrianglesOnCellBordersSinkToLeaves) {
  // Tiny triangles straddling the root's mid-planes fit a child's bounding sphere.
  TriangleInput in;
  for (int k = 0; k < 200; ++k) {
    const float x = 0.5f, y = 0.1f + 0.004f * float(k), z = 0.3f;
    in.add({x - 1e-3f, y, z}, {x + 1e-3f, y, z}, {x, y + 1e-3f, z}, uint64_t(k), 0xffffffffu);
  }
  in.add({0, 0, 0}, {1, 0, 0}, {0, 1, 1}, 200, 0xffffffffu);  // spans the cube: stays at the root
  const SampleTree tree = buildTree(in, TreeParams{0.0, 1, 4}, 1);
  EXPECT_GT(tree.nodes.size(), 1u);
  // With c = 0, q = 1: the root draws 0 triangles, so it holds exactly the one large triangle.
  ASSERT_EQ(tree.nodes[0].triangleCount, 1u);
  EXPECT_EQ(tree.ids[tree.nodes[0].firstTriangle], 200u);
}

// Preorder with children in octant order: a subtree is one run of nodes inside its cell, and the
// children of a node come in Morton order, so neighbouring cells' nodes lie together.
TEST(TreeBuild, NodesAreLaidOutInPreorderByCell) {
  const SampleTree tree = scatteredTree();
  ASSERT_EQ(tree.nodes[0].subtreeEnd, tree.nodes.size());
  for (size_t i = 0; i < tree.nodes.size(); ++i) {
    const TreeNode& u = tree.nodes[i];
    int lastOctant = -1;
    for (size_t j = i + 1; j < u.subtreeEnd; j = tree.nodes[j].subtreeEnd) {
      const TreeNode& d = tree.nodes[j];
      ASSERT_EQ(d.level, u.level + 1) << "node " << j << " is not a child of " << i;
      for (int k = 0; k < 3; ++k) ASSERT_EQ(d.cell[k] >> 1, u.cell[k]) << "child " << j << " of " << i;
      const int octant = int(d.cell[0] & 1) | int(d.cell[1] & 1) << 1 | int(d.cell[2] & 1) << 2;
      ASSERT_GT(octant, lastOctant) << "children of " << i << " out of octant order";
      lastOctant = octant;
      ASSERT_LE(d.subtreeEnd, u.subtreeEnd);
    }
  }
}

TEST(TreeBuild, SameTreeOnOneAndTwoThreads) {
  const SampleTree a = scatteredTree(13.8, 1), b = scatteredTree(13.8, 2);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  EXPECT_EQ(a.ids, b.ids);
  for (size_t i = 0; i < a.nodes.size(); ++i)
    ASSERT_EQ(std::memcmp(&a.nodes[i], &b.nodes[i], sizeof(TreeNode)), 0) << i;
}

TEST(TreeBuild, RepresentativeIsOneOfTheNodesTriangles) {
  const SampleTree tree = scatteredTree();
  for (const TreeNode& n : tree.nodes) {
    if (n.triangleCount == 0) {
      EXPECT_EQ(n.representativeId, kNoId);
      continue;
    }
    const auto begin = tree.ids.begin() + long(n.firstTriangle);
    const auto it = std::find(begin, begin + n.triangleCount, n.representativeId);
    ASSERT_NE(it, begin + n.triangleCount);
    EXPECT_EQ(tree.colours[size_t(it - tree.ids.begin())], n.representativeColour);
  }
}

TEST(TreeBuild, RefusesScenesAboveTheInCoreLimit) {
  const Scene scene = loadScene("builtin:sphereflake?depth=2", true);
  try {
    gatherTriangles(scene, scene.expandedTriangles() - 1);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("in memory"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lzb::sampletree
