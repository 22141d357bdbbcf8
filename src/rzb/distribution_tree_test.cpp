// DistributionTree: the octree's invariants (extended boxes, one node per entry, shortcuts, linear
// storage), the accuracy of the prefix sums (also over 10^9+ instanced areas), dynamic updates.
#include "src/rzb/distribution_tree.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "src/rzb/sample_scene.hpp"
#include "src/scene/load.hpp"

namespace lzb::rzb {
namespace {

// count triangles of sizes spread over 4 decades in a cube of side 100.
Scene soupScene(size_t count, uint32_t seed) {
  Scene scene;
  scene.addNode("soup");
  Mesh& m = scene.nodes[0].mesh;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-50.0f, 50.0f), unit(-1.0f, 1.0f), expo(-2.0f, 2.0f);
  while (m.size() < count) {
    const glm::vec3 c(pos(rng), pos(rng), pos(rng));
    const float s = std::pow(10.0f, expo(rng)) * 0.5f;
    m.add(c + s * glm::vec3(unit(rng), unit(rng), unit(rng)),
          c + s * glm::vec3(unit(rng), unit(rng), unit(rng)),
          c + s * glm::vec3(unit(rng), unit(rng), unit(rng)), packRgba8(200, 100, 50));
  }
  scene.finalize();
  return scene;
}

long double exactArea(const Mesh& m) {
  long double sum = 0.0L;
  for (uint32_t t = 0; t < m.size(); ++t) sum += triangleArea(m, t);
  return sum;
}

// Checks every structural invariant of a tree and returns the number of entries it holds.
uint64_t checkInvariants(const DistributionTree& tree) {
  uint64_t entries = 0;
  std::set<uint32_t> seenRecs;
  const DistributionParams& p = tree.params();
  for (const DistributionTree::ClassRoot& c : tree.classes()) {
    std::vector<uint32_t> stack{c.root};
    while (!stack.empty()) {
      const uint32_t n = stack.back();
      stack.pop_back();
      const DistributionNode& t = tree.node(n);
      EXPECT_EQ(t.cls, c.cls);
      const double h = t.half * (1.0 + p.extension);
      double sum = t.ownTriArea + t.ownInstArea;
      int children = 0;
      for (uint32_t ch : t.child) {
        if (ch == kNone) continue;
        ++children;
        stack.push_back(ch);
        sum += tree.node(ch).area;
        EXPECT_EQ(tree.node(ch).parent, n);
        EXPECT_LT(tree.node(ch).half, t.half);
        EXPECT_LE(tree.node(ch).maxTri, t.maxTri);
      }
      EXPECT_NEAR(t.area, sum, 1e-9 * std::max(t.area, 1e-300));
      // Shortcuts: no stored inner node with a single child and nothing of its own.
      if (!tree.dynamic()) {
        EXPECT_FALSE(children == 1 && t.ownTriArea == 0.0 && t.ownInstArea == 0.0) << n;
      }
      // Own entries lie in the node's extended box; each record appears once.
      tree.forEachEntry(n, Part::kOwnTriangles, [&](uint32_t r) {
        const EntryRec& e = tree.rec(r);
        EXPECT_FALSE(e.instance());
        EXPECT_TRUE(seenRecs.insert(r).second);
        ++entries;
        for (glm::vec3 v : {e.v0, e.v0 + e.e1, e.v0 + e.e2})
          for (int k = 0; k < 3; ++k) {
            EXPECT_GE(double(v[k]), t.center[k] - h - 1e-9 * t.half);
            EXPECT_LE(double(v[k]), t.center[k] + h + 1e-9 * t.half);
          }
      });
      tree.forEachOwnInstance(n, [&](uint32_t i) {
        ++entries;
        const Bounds& b = tree.instance(i).bounds;
        for (int k = 0; k < 3; ++k) {
          EXPECT_GE(b.lo[k], t.center[k] - h);
          EXPECT_LE(b.hi[k], t.center[k] + h);
        }
      });
      if (!tree.dynamic()) {
        // Fig. 5: children's slices, then own triangles, then own instances.
        EXPECT_LE(t.begin, t.ownBegin);
        EXPECT_LE(t.ownBegin, t.instBegin);
        EXPECT_LE(t.instBegin, t.end);
        const double* P = tree.prefix();
        auto before = [&](uint64_t j) { return j ? P[j - 1] : 0.0; };
        EXPECT_NEAR(t.area, before(t.end) - before(t.begin), 1e-12 * P[tree.listSize() - 1]);
      }
    }
  }
  return entries;
}

TEST(DistributionTree, OctreeInvariantsAndLinearStorage) {
  const Scene scene = soupScene(20000, 1);
  const DistributionTree tree(scene, 0, {}, true, {}, DistributionParams{});
  EXPECT_EQ(checkInvariants(tree), 20000u);
  const TreeStats s = tree.stats();
  EXPECT_EQ(s.triangles, 20000u);
  EXPECT_GT(s.classes, 3u);  // four decades of size, ratio 4
  EXPECT_LT(s.nodes, 20000u);  // linear: fewer nodes than entries
  for (uint32_t t = 0; t < 20000; ++t) EXPECT_TRUE(tree.containsTriangle(t));
}

TEST(DistributionTree, AreaClassesSeparateLargeFromSmall) {
  const Scene scene = soupScene(5000, 2);
  DistributionParams p;
  p.areaRatio = 4.0;
  const DistributionTree tree(scene, 0, {}, true, {}, p);
  for (const DistributionTree::ClassRoot& c : tree.classes()) {
    const double lo = std::pow(4.0, c.cls), hi = lo * 4.0;
    tree.forEachEntry(c.root, Part::kSubtree, [&](uint32_t r) {
      const double a = tree.recArea(r);
      EXPECT_GE(a, lo * (1 - 1e-12));
      EXPECT_LT(a, hi * (1 + 1e-12));
    });
  }
}

TEST(DistributionTree, PrefixSumsAreAccurateOverAMillionAreas) {
  const Scene scene = soupScene(1000000, 3);
  const DistributionTree tree(scene, 0, {}, true, {}, DistributionParams{});
  const long double exact = exactArea(scene.nodes[0].mesh);
  EXPECT_NEAR(double(tree.prefix()[tree.listSize() - 1] / exact), 1.0, 1e-13);
  EXPECT_NEAR(double(tree.totalArea() / exact), 1.0, 1e-13);
  // Every prefix against a long double running sum.
  long double run = 0.0L;
  double worst = 0.0;
  for (uint64_t j = 0; j < tree.listSize(); ++j) {
    run += tree.recArea(uint32_t(j));
    worst = std::max(worst, double(std::abs(tree.prefix()[j] - run) / run));
  }
  EXPECT_LT(worst, 1e-13);
}

// area(node) over the whole instanced graph in long double, with each instance's area scale
// from its determinant (the forest's transforms are rotations times uniform scales).
long double exactExpandedArea(const Scene& scene, uint32_t node, std::vector<long double>& memo) {
  if (memo[node] >= 0.0L) return memo[node];
  long double a = exactArea(scene.nodes[node].mesh);
  for (const Instance& inst : scene.nodes[node].instances) {
    const long double s2 =
        std::pow(std::abs((long double)glm::determinant(glm::dmat3(inst.transform))), 2.0L / 3.0L);
    a += s2 * exactExpandedArea(scene, inst.node, memo);
  }
  return memo[node] = a;
}

TEST(DistributionTree, InstancedPrefixSumsOverTenBillionTrianglesAreAccurate) {
  const Scene scene = loadScene("builtin:forest?levels=4&trees=16", true);
  ASSERT_GE(scene.expandedTriangles(), uint64_t(1e9));
  const SampleScene trees(scene, DistributionParams{});
  std::vector<long double> memo(scene.nodes.size(), -1.0L);
  const long double exact = exactExpandedArea(scene, scene.root, memo);
  const DistributionTree& root = trees.root();
  EXPECT_NEAR(double(root.totalArea() / exact), 1.0, 1e-9);
  EXPECT_NEAR(double(root.prefix()[root.listSize() - 1] / exact), 1.0, 1e-9);
  // Every instance entry's weight, and every prefix of the root list.
  long double run = 0.0L;
  for (uint64_t j = 0; j < root.listSize(); ++j) {
    const EntryRec& e = root.rec(uint32_t(j));
    ASSERT_TRUE(e.instance());
    const InstanceRef& r = root.instance(e.index());
    const long double s2 = std::pow(std::abs((long double)r.transform.det()), 2.0L / 3.0L);
    run += s2 * exactExpandedArea(scene, r.node, memo);
    EXPECT_NEAR(double(root.prefix()[j] / run), 1.0, 1e-9) << j;
  }
}

TEST(DistributionTree, DynamicInsertAndRemoveKeepSumsRight) {
  const Scene scene = soupScene(6000, 4);
  // Start with the first 4000, insert the rest one by one, then remove them again.
  std::vector<uint32_t> first(4000);
  for (uint32_t t = 0; t < 4000; ++t) first[t] = t;
  DistributionTree tree(scene, 0, first, false, {}, DistributionParams{});
  const double before = tree.totalArea();
  for (uint32_t t = 4000; t < 6000; ++t) tree.insertTriangle(t);
  EXPECT_TRUE(tree.dynamic());
  EXPECT_EQ(checkInvariants(tree), 6000u);
  const DistributionTree full(scene, 0, {}, true, {}, DistributionParams{});
  EXPECT_NEAR(tree.totalArea() / full.totalArea(), 1.0, 1e-12);
  // Sampling through dirty nodes: the picked entry's frequency follows its area.
  for (const DistributionTree::ClassRoot& c : tree.classes()) {
    double rem, res = 0x1p-53;
    for (double u : {0.0, 0.3, 0.999999}) {
      const uint32_t r = tree.pick(c.root, Part::kSubtree, u, rem, res);
      EXPECT_FALSE(tree.rec(r).instance());
      EXPECT_GE(rem, 0.0);
      EXPECT_LT(rem, 1.0);
    }
  }
  for (uint32_t t = 4000; t < 6000; ++t) tree.removeTriangle(t);
  EXPECT_EQ(checkInvariants(tree), 4000u);
  EXPECT_NEAR(tree.totalArea() / before, 1.0, 1e-12);
  for (uint32_t t = 4000; t < 6000; ++t) EXPECT_FALSE(tree.containsTriangle(t));
  // Removing original triangles too, then compacting back to one static list.
  for (uint32_t t = 0; t < 1000; ++t) tree.removeTriangle(t);
  tree.compact();
  EXPECT_FALSE(tree.dynamic());
  EXPECT_EQ(checkInvariants(tree), 3000u);
  long double exact = 0.0L;
  for (uint32_t t = 1000; t < 4000; ++t) exact += triangleArea(scene.nodes[0].mesh, t);
  EXPECT_NEAR(double(tree.totalArea() / exact), 1.0, 1e-12);
  EXPECT_THROW(tree.removeTriangle(10), std::invalid_argument);
  EXPECT_THROW(tree.insertTriangle(2000), std::invalid_argument);
}

TEST(DistributionTree, DynamicInsertOutsideTheRootGrowsIt) {
  Scene scene = soupScene(100, 5);
  Mesh& m = scene.nodes[0].mesh;
  ASSERT_TRUE(m.add({1000, 0, 0}, {1001, 0, 0}, {1000, 1, 0}, packRgba8(1, 2, 3)));
  ASSERT_TRUE(m.add({-3000, 5, 0}, {-3000, 6, 0}, {-3000, 5, 1}, packRgba8(1, 2, 3)));
  scene.finalize();
  std::vector<uint32_t> first(100);
  for (uint32_t t = 0; t < 100; ++t) first[t] = t;
  DistributionTree tree(scene, 0, first, false, {}, DistributionParams{});
  tree.insertTriangle(100);
  tree.insertTriangle(101);
  EXPECT_EQ(checkInvariants(tree), 102u);
  EXPECT_TRUE(tree.bounds().contains({-3000, 5.5, 0.5}));
}

TEST(SampleScene, WholeObjectsInsertAndRemoveAsOneEntry) {
  // Node 0: the root with one triangle; node 1: an object of many triangles.
  Scene scene = soupScene(500, 6);
  const uint32_t obj = scene.addNode("object");
  scene.nodes[obj].mesh = scene.nodes[0].mesh;
  scene.nodes[0].mesh = Mesh{};
  ASSERT_TRUE(scene.nodes[0].mesh.add({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, packRgba8(9, 9, 9)));
  scene.nodes[0].instances.push_back({obj, glm::dmat4(1.0)});
  scene.finalize();
  SampleScene trees(scene, DistributionParams{});
  const double objArea = trees.tree(obj)->totalArea();
  const double start = trees.root().totalArea();
  EXPECT_NEAR(start, objArea + 0.5, 1e-9 * start);
  // A second copy, scaled by 2 (area x 4), then removed again.
  glm::dmat4 m(2.0);
  m[3] = glm::dvec4(200, 0, 0, 1);
  const uint32_t e = trees.insertInstance(0, obj, m, 1);
  EXPECT_NEAR(trees.root().totalArea(), start + 4.0 * objArea, 1e-9 * start);
  trees.removeInstance(0, e);
  EXPECT_NEAR(trees.root().totalArea(), start, 1e-9 * start);
  // Editing inside the instanced object reaches the root's entry.
  trees.removeTriangle(obj, 7);
  EXPECT_NEAR(trees.root().totalArea(),
              start - triangleArea(scene.nodes[obj].mesh, 7), 1e-9 * start);
  trees.compact();
  EXPECT_FALSE(trees.root().dynamic());
}

}  // namespace
}  // namespace lzb::rzb
