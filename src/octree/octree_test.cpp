#include "src/octree/octree.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <limits>
#include <random>

#include "src/core/error.hpp"
#include "tests/support/random_geometry.hpp"
#include "src/octree/tri_box_overlap.hpp"

namespace lzb {
namespace {

using test::randomMesh;
using test::vertex;

bool overlaps(const Mesh& m, uint32_t t, const Bounds& box) {
  return triBoxOverlap(box, vertex(m, t, 0), vertex(m, t, 1), vertex(m, t, 2));
}

bool contains(std::span<const uint32_t> sorted, uint32_t e) {
  return std::binary_search(sorted.begin(), sorted.end(), e);
}

// Triangle sets per leaf are exactly {t : triBoxOverlap(t, leaf box)}.
void expectExactAssignment(const Octree& tree, const Mesh& mesh) {
  std::vector<int> leavesPerTriangle(mesh.size(), 0);
  for (uint32_t i = 0; i < tree.nodeCount(); ++i) {
    if (!tree.node(i).leaf()) continue;
    const auto entries = tree.leafEntries(i);
    ASSERT_TRUE(std::adjacent_find(entries.begin(), entries.end(), std::greater_equal<>()) ==
                entries.end())
        << "leaf " << i << " entries not strictly ascending";
    for (uint32_t e : entries) {
      ASSERT_FALSE(Octree::isInstance(e));
      ASSERT_TRUE(overlaps(mesh, e, tree.nodeBox(i))) << "triangle " << e << " in leaf " << i;
      ++leavesPerTriangle[e];
    }
    for (uint32_t t = 0; t < mesh.size(); ++t)
      if (!contains(entries, t) && overlaps(mesh, t, tree.nodeBox(i)))
        FAIL() << "triangle " << t << " overlaps leaf " << i << " but is not listed";
  }
  for (uint32_t t = 0; t < mesh.size(); ++t) EXPECT_GE(leavesPerTriangle[t], 1) << t;
}

TEST(Octree, EveryTriangleInExactlyTheLeavesItOverlaps) {
  const Mesh mesh = randomMesh(3000, 1, 0.03);
  OctreeParams p;
  p.maxLeafEntries = 12;
  p.maxDepth = 7;
  const Octree tree(mesh, {}, p);
  EXPECT_GT(tree.stats().leaves, 200u);
  EXPECT_GT(tree.stats().entries, mesh.size()) << "large triangles should be duplicated";
  expectExactAssignment(tree, mesh);
}

TEST(Octree, InnerNodesSplitAtTheMidpointAndRootIsACubeAroundTheContent) {
  const Mesh mesh = randomMesh(2000, 2);
  OctreeParams p;
  p.maxLeafEntries = 20;
  const Octree tree(mesh, {}, p);
  const Bounds& root = tree.bounds();
  for (const glm::vec3& v : mesh.positions) EXPECT_TRUE(root.contains(glm::dvec3(v)));
  const glm::dvec3 e = root.extent();
  EXPECT_NEAR(e.x, e.y, 1e-12 * e.x);
  EXPECT_NEAR(e.x, e.z, 1e-12 * e.x);
  EXPECT_EQ(tree.nodeDepth(0), 0);
  for (uint32_t i = 0; i < tree.nodeCount(); ++i) {
    const Octree::Node& n = tree.node(i);
    if (n.leaf()) continue;
    EXPECT_EQ(n.count, 0u);
    ASSERT_LE(n.firstChild + 8, tree.nodeCount());
    const Bounds& b = tree.nodeBox(i);
    const glm::dvec3 mid = 0.5 * (b.lo + b.hi);
    for (int c = 0; c < 8; ++c) {
      const Bounds& k = tree.nodeBox(n.firstChild + c);
      EXPECT_EQ(tree.nodeDepth(n.firstChild + c), tree.nodeDepth(i) + 1);
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(k.lo[a], (c >> a) & 1 ? mid[a] : b.lo[a]);
        EXPECT_EQ(k.hi[a], (c >> a) & 1 ? b.hi[a] : mid[a]);
      }
    }
  }
}

TEST(Octree, LeafSizeBoundedUnlessMaxDepthOrRefusedSplit) {
  // Random triangles plus a stack of 300 large, nearly coplanar triangles: no split separates
  // them, so their leaves must stop by the growth rule instead of multiplying to max depth.
  Mesh mesh = randomMesh(4000, 3);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> u(-0.01f, 0.01f);
  for (int i = 0; i < 300; ++i)
    mesh.add({-0.9f, -0.9f + u(rng), 0.1f + u(rng)}, {0.9f, -0.85f, 0.1f + u(rng)},
             {0.0f, 0.9f, 0.12f + u(rng)}, 0);
  OctreeParams p;
  p.maxLeafEntries = 40;
  p.maxDepth = 10;
  const Octree tree(mesh, {}, p);
  uint64_t refused = 0;
  for (uint32_t i = 0; i < tree.nodeCount(); ++i) {
    const Octree::Node& n = tree.node(i);
    if (!n.leaf() || n.count <= p.maxLeafEntries || tree.nodeDepth(i) == p.maxDepth) continue;
    ++refused;
    // Splitting it would have multiplied its entries by more than maxSplitGrowth.
    const Bounds& b = tree.nodeBox(i);
    const glm::dvec3 mid = 0.5 * (b.lo + b.hi);
    uint64_t childEntries = 0;
    for (uint32_t e : tree.leafEntries(i))
      for (int c = 0; c < 8; ++c) {
        Bounds k;
        for (int a = 0; a < 3; ++a) {
          k.lo[a] = (c >> a) & 1 ? mid[a] : b.lo[a];
          k.hi[a] = (c >> a) & 1 ? b.hi[a] : mid[a];
        }
        childEntries += overlaps(mesh, e, k);
      }
    EXPECT_GT(double(childEntries), p.maxSplitGrowth * n.count) << "leaf " << i;
  }
  EXPECT_GT(refused, 0u);
  EXPECT_EQ(refused, tree.stats().growthStoppedLeaves);
  EXPECT_LT(tree.stats().nodes, 200000u);
  expectExactAssignment(tree, mesh);
}

TEST(Octree, MaxDepthStopsSplitting) {
  Mesh mesh;
  // 500 copies of one small triangle: only max depth (or growth) can stop the splitting.
  for (int i = 0; i < 500; ++i)
    mesh.add({0.1f, 0.1f, 0.1f}, {0.1001f, 0.1f, 0.1f}, {0.1f, 0.1001f, 0.1f}, 0);
  mesh.add({-1.0f, -1.0f, -1.0f}, {-0.9f, -1.0f, -1.0f}, {-1.0f, -0.9f, -1.0f}, 0);
  mesh.add({1.0f, 1.0f, 1.0f}, {0.9f, 1.0f, 1.0f}, {1.0f, 0.9f, 1.0f}, 0);
  OctreeParams p;
  p.maxDepth = 6;
  p.maxLeafEntries = 100;
  const Octree tree(mesh, {}, p);
  EXPECT_EQ(tree.stats().maxDepth, 6);
  EXPECT_GE(tree.stats().maxLeafEntries, 500u);
  EXPECT_LE(tree.stats().nodes, 1u + 8u * 6u * 8u);
  expectExactAssignment(tree, mesh);
}

bool sameTree(const Octree& a, const Octree& b) {
  if (a.nodeCount() != b.nodeCount() || a.entries() != b.entries()) return false;
  for (uint32_t i = 0; i < a.nodeCount(); ++i) {
    const Octree::Node &x = a.node(i), &y = b.node(i);
    if (x.offset != y.offset || x.count != y.count || x.firstChild != y.firstChild) return false;
    if (a.nodeBox(i).lo != b.nodeBox(i).lo || a.nodeBox(i).hi != b.nodeBox(i).hi) return false;
    if (a.nodeDepth(i) != b.nodeDepth(i)) return false;
  }
  return true;
}

TEST(Octree, IdenticalForAnyThreadCount) {
  // Large enough for the parallel classification and child tasks to run.
  const Mesh mesh = randomMesh(150000, 4);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const Octree one(mesh, {}, {});
  omp_set_num_threads(2);
  const Octree two(mesh, {}, {});
  omp_set_num_threads(3);
  const Octree three(mesh, {}, {});
  omp_set_num_threads(saved);
  EXPECT_GT(one.nodeCount(), 1000u);
  EXPECT_TRUE(sameTree(one, two));
  EXPECT_TRUE(sameTree(one, three));
}

TEST(Octree, InstancesListedInLeavesTheirBoxesOverlap) {
  Scene scene;
  const uint32_t root = scene.addNode("root");
  const uint32_t child = scene.addNode("child");
  const uint32_t empty = scene.addNode("empty");
  scene.root = root;
  scene.nodes[root].mesh = randomMesh(1500, 5);
  scene.nodes[child].mesh = randomMesh(200, 6);
  std::mt19937_64 rng(5);
  for (int i = 0; i < 60; ++i) {
    glm::dmat4 m = test::randomRigidMotion(rng, i % 2 == 1);
    m = glm::dmat4(glm::dmat3(m) * 0.1);
    m[3] = glm::dvec4(glm::dvec3(std::uniform_real_distribution<double>(-1.2, 1.2)(rng),
                                 std::uniform_real_distribution<double>(-1.2, 1.2)(rng),
                                 std::uniform_real_distribution<double>(-1.2, 1.2)(rng)),
                      1.0);
    scene.nodes[root].instances.push_back({child, m});
  }
  scene.nodes[root].instances.push_back({empty, glm::dmat4(1.0)});
  scene.finalize();
  OctreeParams p;
  p.maxLeafEntries = 16;
  const Octree tree(scene, root, p);
  const std::vector<Bounds> boxes = Octree::instanceBoxes(scene, root);
  ASSERT_EQ(boxes.size(), 61u);
  EXPECT_TRUE(boxes[60].empty());
  for (const glm::vec3& v : scene.nodes[root].mesh.positions)
    EXPECT_TRUE(tree.bounds().contains(glm::dvec3(v)));
  for (size_t k = 0; k + 1 < boxes.size(); ++k)
    EXPECT_TRUE(tree.bounds().contains(boxes[k].lo) && tree.bounds().contains(boxes[k].hi));
  std::vector<int> seen(boxes.size(), 0);
  const Mesh& mesh = scene.nodes[root].mesh;
  for (uint32_t i = 0; i < tree.nodeCount(); ++i) {
    if (!tree.node(i).leaf()) continue;
    const auto entries = tree.leafEntries(i);
    for (uint32_t e : entries) {
      if (Octree::isInstance(e)) {
        ++seen[Octree::entryIndex(e)];
        EXPECT_TRUE(boxes[Octree::entryIndex(e)].overlaps(tree.nodeBox(i)));
      } else {
        EXPECT_TRUE(overlaps(mesh, e, tree.nodeBox(i)));
      }
    }
    for (uint32_t k = 0; k < boxes.size(); ++k) {
      if (boxes[k].overlaps(tree.nodeBox(i))) {
        EXPECT_TRUE(contains(entries, k | Octree::kInstanceBit)) << "instance " << k;
      }
    }
  }
  for (size_t k = 0; k + 1 < boxes.size(); ++k) EXPECT_GE(seen[k], 1);
  EXPECT_EQ(seen[60], 0) << "an instance of an empty node has no content";

  // A node made of instances only.
  scene.nodes[root].mesh = Mesh{};
  scene.finalize();
  const Octree instancesOnly(scene, root, p);
  EXPECT_FALSE(instancesOnly.empty());
  EXPECT_GE(instancesOnly.stats().entries, 60u);
}

TEST(Octree, StatisticsMatchTheTree) {
  const Mesh mesh = randomMesh(5000, 7);
  OctreeParams p;
  p.maxLeafEntries = 30;
  const Octree tree(mesh, {}, p);
  const OctreeStats& s = tree.stats();
  uint64_t leaves = 0, nonEmpty = 0, entries = 0, maxEntries = 0;
  int maxDepth = 0;
  for (uint32_t i = 0; i < tree.nodeCount(); ++i) {
    if (!tree.node(i).leaf()) continue;
    ++leaves;
    nonEmpty += tree.node(i).count > 0;
    entries += tree.node(i).count;
    maxEntries = std::max<uint64_t>(maxEntries, tree.node(i).count);
    maxDepth = std::max(maxDepth, tree.nodeDepth(i));
  }
  EXPECT_EQ(s.nodes, tree.nodeCount());
  EXPECT_EQ(s.nodes, 1 + 8 * (s.nodes - s.leaves));
  EXPECT_EQ(s.leaves, leaves);
  EXPECT_EQ(s.nonEmptyLeaves, nonEmpty);
  EXPECT_EQ(s.entries, entries);
  EXPECT_EQ(s.entries, tree.entries().size());
  EXPECT_EQ(s.maxLeafEntries, maxEntries);
  EXPECT_EQ(s.maxDepth, maxDepth);
  EXPECT_DOUBLE_EQ(s.meanLeafEntries, double(entries) / double(nonEmpty));
  EXPECT_GE(s.memoryBytes, s.nodes * (sizeof(Octree::Node) + sizeof(Bounds)) + 4 * s.entries);
  EXPECT_GE(s.buildSeconds, 0.0);
  const nlohmann::json j = s.toJson();
  EXPECT_EQ(j.at("entries").get<uint64_t>(), entries);
  EXPECT_EQ(j.at("leaves").get<uint64_t>(), leaves);
}

TEST(Octree, EmptyTinyAndNonFiniteInput) {
  const Octree none(Mesh{}, {}, {});
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.stats().entries, 0u);
  int visits = 0;
  none.traverseRay({0, 0, 0}, {1, 0, 0}, 0.0, 1e30,
                   [&](uint32_t, double, double) { return ++visits > 0; });
  none.cullFrustum(Frustum{}, glm::dmat4(1.0), [&](uint32_t, Cull) { ++visits; });
  EXPECT_EQ(visits, 0);

  Mesh one;
  one.add({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
  // A triangle with a NaN vertex pushed past Mesh::add's check is left out and counted.
  one.positions.insert(one.positions.end(), {glm::vec3(std::numeric_limits<float>::quiet_NaN()),
                                             glm::vec3(1.0f), glm::vec3(2.0f)});
  one.indices.insert(one.indices.end(), {3, 4, 5});
  one.colors.push_back(0);
  const Octree tree(one, {}, {});
  EXPECT_EQ(tree.nodeCount(), 1u);
  EXPECT_EQ(tree.stats().skippedTriangles, 1u);
  ASSERT_EQ(tree.leafEntries(0).size(), 1u);
  EXPECT_EQ(tree.leafEntries(0)[0], 0u);
  // Flat content still gets a cube root.
  EXPECT_DOUBLE_EQ(tree.bounds().extent().z, 1.0);
}

TEST(Octree, RejectsBadParameters) {
  const Mesh mesh = randomMesh(10, 8);
  OctreeParams p;
  p.maxDepth = -1;
  EXPECT_THROW(Octree(mesh, {}, p), InputError);
  p = {};
  p.maxDepth = 31;
  EXPECT_THROW(Octree(mesh, {}, p), InputError);
  p = {};
  p.maxLeafEntries = 0;
  EXPECT_THROW(Octree(mesh, {}, p), InputError);
  p = {};
  p.maxSplitGrowth = 0.5;
  EXPECT_THROW(Octree(mesh, {}, p), InputError);
}

TEST(Octree, ProgressLineForLargeBuilds) {
  const Mesh mesh = randomMesh(140000, 9);
  OctreeParams p;
  p.progress = true;
  testing::internal::CaptureStderr();
  const Octree tree(mesh, {}, p);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("octree"), std::string::npos);
  EXPECT_NE(err.find("100.0%"), std::string::npos);
  p.progress = false;
  testing::internal::CaptureStderr();
  const Octree quiet(mesh, {}, p);
  EXPECT_TRUE(testing::internal::GetCapturedStderr().empty());
}

}  // namespace
}  // namespace lzb
