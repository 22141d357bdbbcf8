#include "src/core/scene.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "src/core/error.hpp"
#include "src/core/framebuffer.hpp"
#include "tests/support/files.hpp"

namespace lzb {
namespace {

Mesh quad(Rgba8 c) {
  Mesh m;
  m.add({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, c);
  m.add({0, 0, 0}, {1, 1, 0}, {0, 1, 0}, c);
  return m;
}

TEST(Mesh, DropsDegenerateAndNonFiniteTriangles) {
  Mesh m;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_TRUE(m.add({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0));
  EXPECT_FALSE(m.add({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, 0));  // collinear
  EXPECT_FALSE(m.add({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, 0));  // repeated vertex
  EXPECT_FALSE(m.add({nan, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0));
  EXPECT_FALSE(m.add({0, 0, 0}, {inf, 0, 0}, {0, 1, 0}, 0));
  // Tiny but valid: the normal is computed in double, so it does not underflow.
  EXPECT_TRUE(m.add({0, 0, 0}, {1e-25f, 0, 0}, {0, 1e-25f, 0}, 0));
  EXPECT_EQ(m.size(), 2u);
  EXPECT_NEAR(m.normal(1).z, 1.0f, 1e-6f);
}

TEST(Mesh, IndexedTrianglesShareVerticesAndAppendOffsetsThem) {
  Mesh m;
  const uint32_t a = m.addVertex({0, 0, 0}), b = m.addVertex({1, 0, 0}), c = m.addVertex({1, 1, 0}),
                 d = m.addVertex({0, 1, 0});
  EXPECT_TRUE(m.addTriangle(a, b, c, 1));
  EXPECT_TRUE(m.addTriangle(a, c, d, 2));
  EXPECT_FALSE(m.addTriangle(a, a, c, 3));  // repeated vertex: nothing added
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.indices.size(), 6u);
  EXPECT_EQ(m.vertex(1, 2), glm::vec3(0, 1, 0));
  EXPECT_EQ(m.normal(1), glm::vec3(0, 0, 1));
  Mesh twice = m;
  twice.append(m);
  ASSERT_EQ(twice.size(), 4u);
  EXPECT_EQ(twice.positions.size(), 8u);
  for (size_t t = 0; t < 2; ++t)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(twice.vertex(t + 2, k), m.vertex(t, k));
      EXPECT_EQ(twice.indices[3 * (t + 2) + size_t(k)], m.indices[3 * t + size_t(k)] + 4u);
    }
  EXPECT_EQ(twice.color(3), 2u);
}

TEST(Mesh, OneColourStandsForAllAndSpreadsBackWhenTrianglesAreAdded) {
  Mesh m = quad(7);
  m.uniformColors();
  ASSERT_EQ(m.colors.size(), 1u);
  EXPECT_EQ(m.color(1), 7u);
  EXPECT_TRUE(m.add({0, 0, 1}, {1, 0, 1}, {0, 1, 1}, 9));
  ASSERT_EQ(m.colors.size(), 3u);
  EXPECT_EQ(m.color(0), 7u);
  EXPECT_EQ(m.color(1), 7u);
  EXPECT_EQ(m.color(2), 9u);
  m.uniformColors();
  EXPECT_EQ(m.colors.size(), 3u) << "colours that differ are kept";
  Mesh one = quad(5);
  one.uniformColors();
  Mesh both = quad(4);
  both.append(one);
  ASSERT_EQ(both.colors.size(), 4u);
  EXPECT_EQ(both.color(3), 5u);
}

// Root: 2 own triangles, instance of A (2 triangles) twice, instance of B which holds A thrice.
Scene nested() {
  Scene s;
  const uint32_t root = s.addNode("root");
  const uint32_t a = s.addNode("a");
  const uint32_t b = s.addNode("b");
  s.nodes[root].mesh = quad(1);
  s.nodes[a].mesh = quad(2);
  for (int i = 0; i < 3; ++i)
    s.nodes[b].instances.push_back({a, glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, i))});
  s.nodes[root].instances.push_back({a, glm::translate(glm::dmat4(1.0), glm::dvec3(5, 0, 0))});
  s.nodes[root].instances.push_back({a, glm::translate(glm::dmat4(1.0), glm::dvec3(7, 0, 0))});
  s.nodes[root].instances.push_back({b, glm::translate(glm::dmat4(1.0), glm::dvec3(0, 9, 0))});
  s.root = root;
  s.finalize();
  return s;
}

TEST(Scene, ExpandedCountsOffsetsAndBounds) {
  Scene s = nested();
  EXPECT_EQ(s.uniqueTriangles(), 4u);
  EXPECT_EQ(s.expandedTriangles(), 2u + 2 + 2 + 6);
  EXPECT_EQ(s.childOffset(0, 0), 2u);
  EXPECT_EQ(s.childOffset(0, 1), 4u);
  EXPECT_EQ(s.childOffset(0, 2), 6u);
  EXPECT_DOUBLE_EQ(s.bounds().hi.x, 8.0);
  EXPECT_DOUBLE_EQ(s.bounds().hi.y, 10.0);
  EXPECT_DOUBLE_EQ(s.bounds().hi.z, 2.0);
}

// resolve() sums nested translations instead of multiplying them: the same bits as the product
// flattenScene forms, with translations that do not add exactly and a rotation below them.
TEST(Scene, ResolveComposesTranslationsAsTheProductDoes) {
  Scene s;
  const uint32_t root = s.addNode("root"), c = s.addNode("c"), d = s.addNode("d");
  const uint32_t e = s.addNode("e");
  s.nodes[e].mesh = quad(0);
  s.nodes[root].instances.push_back(
      {c, glm::translate(glm::dmat4(1.0), glm::dvec3(0.1, 0.2, 0.3))});
  s.nodes[c].instances.push_back(
      {d, glm::translate(glm::dmat4(1.0), glm::dvec3(1e8 + 0.7, -0.3, 1.0 / 3.0))});
  s.nodes[d].instances.push_back(
      {e, glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(0.05, 0, 0)), 0.5,
                      glm::dvec3(0, 1, 0))});
  s.nodes[d].instances.push_back({e, glm::translate(glm::dmat4(1.0), glm::dvec3(-0.9, 0.01, 7))});
  s.root = root;
  s.finalize();
  const std::vector<DrawItem> items = flattenScene(s);
  ASSERT_EQ(items.size(), 2u);
  for (const DrawItem& item : items) {
    const auto ref = s.resolve(item.idBase);
    ASSERT_TRUE(ref);
    EXPECT_EQ(ref->transform, item.transform);
  }
}

TEST(Scene, ResolveAndFlattenAgree) {
  Scene s = nested();
  const std::vector<DrawItem> items = flattenScene(s);
  ASSERT_EQ(items.size(), 1u + 2 + 3);
  uint64_t checked = 0;
  for (const DrawItem& item : items)
    for (uint32_t t = 0; t < s.nodes[item.node].mesh.size(); ++t) {
      auto ref = s.resolve(item.idBase + t);
      ASSERT_TRUE(ref);
      EXPECT_EQ(ref->node, item.node);
      EXPECT_EQ(ref->triangle, t);
      EXPECT_EQ(ref->transform, item.transform);
      ++checked;
    }
  EXPECT_EQ(checked, s.expandedTriangles());
  EXPECT_FALSE(s.resolve(s.expandedTriangles()));
  EXPECT_FALSE(s.resolve(kNoId));
}

TEST(Scene, RejectsCyclesAndDanglingReferences) {
  Scene s;
  const uint32_t a = s.addNode("a"), b = s.addNode("b");
  s.nodes[a].mesh = quad(1);
  s.nodes[a].instances.push_back({b, glm::dmat4(1.0)});
  s.nodes[b].instances.push_back({a, glm::dmat4(1.0)});
  EXPECT_THROW(s.finalize(), InputError);
  s.nodes[b].instances = {{7, glm::dmat4(1.0)}};
  EXPECT_THROW(s.finalize(), InputError);
}

TEST(Scene, HugeNestedCountsDoNotOverflow) {
  // 2x2 instancing 25 levels deep over 2 triangles: 2 * 4^25 ≈ 2.25e15 expanded triangles.
  Scene s;
  uint32_t child = s.addNode("leaf");
  s.nodes[child].mesh = quad(1);
  for (int level = 0; level < 25; ++level) {
    const uint32_t parent = s.addNode("level" + std::to_string(level));
    for (int i = 0; i < 4; ++i)
      s.nodes[parent].instances.push_back(
          {child, glm::translate(glm::dmat4(1.0), glm::dvec3(i % 2, 0, i / 2) * std::ldexp(1.0, level))});
    child = parent;
  }
  s.root = child;
  s.finalize();
  EXPECT_EQ(s.expandedTriangles(), 2ull << 50);
  auto ref = s.resolve(s.expandedTriangles() - 1);
  ASSERT_TRUE(ref);
  EXPECT_EQ(ref->triangle, 1u);
  EXPECT_DOUBLE_EQ(ref->transform[3][0], std::ldexp(1.0, 25) - 1.0);
}

// A chain of `levels` instance levels over one quad: node k instances node k + 1, the last holds
// the quad; the root is node 0.
Scene chain(int levels) {
  Scene s;
  for (int k = 0; k <= levels; ++k) s.addNode("n" + std::to_string(k));
  for (int k = 0; k < levels; ++k)
    s.nodes[size_t(k)].instances.push_back({uint32_t(k + 1), glm::dmat4(1.0)});
  s.nodes[size_t(levels)].mesh = quad(1);
  return s;
}

using test::errorOf;

TEST(Scene, InstanceDepthIsBoundedAt64Levels) {
  Scene ok = chain(kMaxInstanceDepth);
  ok.finalize();
  EXPECT_EQ(ok.instanceDepth, kMaxInstanceDepth);
  EXPECT_EQ(ok.expandedTriangles(), 2u);
  Scene deep = chain(kMaxInstanceDepth + 1);
  const std::string e = errorOf([&] { deep.finalize(); });
  EXPECT_NE(e.find("deeper than 64 levels"), std::string::npos) << e;
  EXPECT_NE(e.find("'n65'"), std::string::npos) << e;  // the first node too deep
}

TEST(Scene, AChainOf100000NodesIsRefusedWithoutOverflowingTheStack) {
  Scene s = chain(100000);
  const std::string e = errorOf([&] { s.finalize(); });
  EXPECT_NE(e.find("deeper than 64 levels"), std::string::npos) << e;
}

TEST(Scene, DepthCountsTheLongestPathNotTheFirstOneFound) {
  // The root reaches the 60-level chain's middle (n30) directly first, then through the chain:
  // the walk meets n30 finished, and the height it carries puts the chain's top at level 64+.
  Scene s = chain(70);
  const uint32_t root = s.addNode("root");
  s.nodes[root].instances.push_back({30, glm::dmat4(1.0)});
  s.nodes[root].instances.push_back({0, glm::dmat4(1.0)});
  s.root = root;
  const std::string e = errorOf([&] { s.finalize(); });
  EXPECT_NE(e.find("deeper than 64 levels"), std::string::npos) << e;
}

TEST(Scene, ANodeInstancingItselfIsACycle) {
  Scene s;
  const uint32_t a = s.addNode("self");
  s.nodes[a].mesh = quad(1);
  s.nodes[a].instances.push_back({a, glm::dmat4(1.0)});
  const std::string e = errorOf([&] { s.finalize(); });
  EXPECT_NE(e.find("cycle through node 'self'"), std::string::npos) << e;
}

TEST(Scene, ExpandedCountsBeyond2To62AreRefusedNamingTheNode) {
  // 10 instances per level, 30 levels, over 2 triangles: 2e30 expanded (it used to saturate).
  Scene s;
  uint32_t child = s.addNode("leaf");
  s.nodes[child].mesh = quad(1);
  for (int level = 0; level < 30; ++level) {
    const uint32_t parent = s.addNode("level" + std::to_string(level));
    for (int i = 0; i < 10; ++i) s.nodes[parent].instances.push_back({child, glm::dmat4(1.0)});
    child = parent;
  }
  s.root = child;
  const std::string e = errorOf([&] { s.finalize(); });
  EXPECT_NE(e.find("more than 2^62 triangles"), std::string::npos) << e;
  // 2 * 10^18 (level17) is the last that fits; level18 (2e19) is the first refused.
  EXPECT_NE(e.find("'level18'"), std::string::npos) << e;
  // Exactly 2^62 fits.
  Scene edge;
  uint32_t c = edge.addNode("leaf");
  edge.nodes[c].mesh = quad(1);  // 2 = 2^1
  for (int level = 0; level < 61; ++level) {
    const uint32_t p = edge.addNode("x" + std::to_string(level));
    edge.nodes[p].instances = {{c, glm::dmat4(1.0)}, {c, glm::dmat4(1.0)}};
    c = p;
  }
  edge.root = c;
  edge.finalize();
  EXPECT_EQ(edge.expandedTriangles(), kMaxExpandedTriangles);
}

TEST(Framebuffer, CompositeIsOrderIndependent) {
  Framebuffer a(4, 1), b(4, 1), c(4, 1);
  a.keepNearer(0, 1.0f, 10, 5);
  b.keepNearer(0, 1.0f, 20, 3);  // same depth: the smaller ID wins
  c.keepNearer(0, 2.0f, 30, 1);
  b.keepNearer(1, 0.5f, 40, 9);
  Framebuffer ab = a, ba = b;
  compositeNearer(ab, b);
  compositeNearer(ab, c);
  compositeNearer(ba, c);
  compositeNearer(ba, a);
  EXPECT_EQ(ab.id, ba.id);
  EXPECT_EQ(ab.color, ba.color);
  EXPECT_EQ(ab.id[0], 3u);
  EXPECT_EQ(ab.id[1], 9u);
  EXPECT_EQ(ab.id[2], kNoId);
  EXPECT_EQ(ab.coveredCount(), 2u);
}

}  // namespace
}  // namespace lzb
