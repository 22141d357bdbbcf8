#include "src/scene/builtin.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "src/core/error.hpp"
#include "src/scene/load.hpp"
#include "tests/support/files.hpp"

namespace lzb {
namespace {

using test::errorOf;
using test::ScratchDir;

Scene generate(const std::string& spec) {
  return loadScene("builtin:" + spec, true);
}

// Every triangle of the expanded scene in world space, as (rounded centroid, colour), sorted:
// equal lists mean equal geometry whatever the instancing structure.
std::vector<std::tuple<long, long, long, Rgba8>> worldTriangles(const Scene& s) {
  std::vector<std::tuple<long, long, long, Rgba8>> out;
  for (const DrawItem& d : flattenScene(s)) {
    const Mesh& m = s.nodes[d.node].mesh;
    for (size_t t = 0; t < m.size(); ++t) {
      glm::dvec3 c(0.0);
      for (int k = 0; k < 3; ++k)
        c += glm::dvec3(d.transform * glm::dvec4(glm::dvec3(m.vertex(t, k)), 1.0));
      c *= 1e4 / 3.0;
      out.emplace_back(std::lround(c.x), std::lround(c.y), std::lround(c.z), m.color(t));
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

bool sameMeshes(const Scene& a, const Scene& b) {
  if (a.nodes.size() != b.nodes.size()) return false;
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    const Mesh &x = a.nodes[i].mesh, &y = b.nodes[i].mesh;
    if (x.positions != y.positions || x.indices != y.indices || x.colors != y.colors) return false;
    if (a.nodes[i].instances.size() != b.nodes[i].instances.size()) return false;
    for (size_t k = 0; k < a.nodes[i].instances.size(); ++k)
      if (a.nodes[i].instances[k].transform != b.nodes[i].instances[k].transform) return false;
  }
  return true;
}

// ---- parameters ----

TEST(Builtin, UnknownGeneratorIsNamed) {
  const std::string e = errorOf([] { generate("teapot?n=3"); });
  EXPECT_NE(e.find("unknown generator 'teapot'"), std::string::npos) << e;
}

TEST(Builtin, UnknownKeyIsNamed) {
  const std::string e = errorOf([] { generate("chessboard?n=8&size=3"); });
  EXPECT_NE(e.find("size"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown parameter"), std::string::npos) << e;
}

TEST(Builtin, BadValuesNameTheKey) {
  for (const std::string spec : {"chessboard?n=0", "chessboard?n=-4", "chessboard?n=abc",
                                 "chessboard?n=", "chessboard?n=3.5",
                                 "chessboard?n=99999999999999999999", "chessboard?n=2147483648"}) {
    const std::string e = errorOf([&] { generate(spec); });
    EXPECT_NE(e.find(": n: "), std::string::npos) << spec << " -> " << e;
  }
  EXPECT_NE(errorOf([] { generate("city?blocks=100000"); }).find("blocks"), std::string::npos);
  EXPECT_NE(errorOf([] { generate("city?seed=-1"); }).find("seed"), std::string::npos);
  EXPECT_NE(errorOf([] { generate("forest?trees=x"); }).find("trees"), std::string::npos);
  EXPECT_NE(errorOf([] { generate("forest?levels=12"); }).find("levels"), std::string::npos);
  EXPECT_NE(errorOf([] { generate("sphereflake?depth=17"); }).find("depth"), std::string::npos);
  EXPECT_NE(errorOf([] { generate("chessboard?n=4&n=8"); }).find("given twice"), std::string::npos);
  EXPECT_NE(errorOf([] { generate("chessboard?n"); }).find("key=value"), std::string::npos);
}

// ---- chessboard ----

TEST(Chessboard, FlatCountsAndLayout) {
  const Scene s = generate("chessboard?n=8&block=64");
  EXPECT_EQ(s.nodes.size(), 1u);
  EXPECT_EQ(s.uniqueTriangles(), 128u);
  EXPECT_EQ(s.expandedTriangles(), 128u);
  EXPECT_NEAR(s.bounds().lo.x, -50.0, 1e-9);
  EXPECT_NEAR(s.bounds().hi.z, 50.0, 1e-9);
  EXPECT_EQ(s.bounds().lo.y, 0.0);
  EXPECT_EQ(s.bounds().hi.y, 0.0);
  ASSERT_TRUE(s.camera.has_value());
  // Two colours, alternating; normals up.
  const Mesh& m = s.rootNode().mesh;
  EXPECT_NE(m.color(0), m.color(2));
  EXPECT_EQ(m.color(0), m.color(1));
  EXPECT_EQ(m.color(0), m.color(4));
  for (size_t t = 0; t < m.size(); ++t) EXPECT_FLOAT_EQ(m.normal(t).y, 1.0f);
}

TEST(Chessboard, NestedEqualsFlat) {
  const Scene flat = generate("chessboard?n=16&block=16");
  const Scene nested = generate("chessboard?n=16&block=2");
  EXPECT_EQ(nested.uniqueTriangles(), 8u);
  EXPECT_EQ(nested.nodes.size(), 1u + 3u);  // block + log2(16 / 2) levels
  EXPECT_EQ(nested.expandedTriangles(), 2u * 16 * 16);
  EXPECT_EQ(worldTriangles(flat), worldTriangles(nested));
}

TEST(Chessboard, ReachesTenToTheTwelve) {
  const Scene s = generate("chessboard?n=1048576&block=64");
  EXPECT_EQ(s.expandedTriangles(), 2ull << 40);  // 2 * (2^20)^2
  EXPECT_GE(s.expandedTriangles(), 1000000000000ull);
  EXPECT_EQ(s.uniqueTriangles(), 2u * 64 * 64);
  EXPECT_EQ(s.nodes.size(), 1u + 14u);
  EXPECT_NEAR(s.bounds().lo.x, -50.0, 1e-9);
  EXPECT_NEAR(s.bounds().hi.x, 50.0, 1e-9);
  // The last expanded triangle resolves to the far corner of the board.
  const auto ref = s.resolve(s.expandedTriangles() - 1);
  ASSERT_TRUE(ref.has_value());
  const glm::dvec3 v =
      glm::dvec3(ref->transform *
                 glm::dvec4(glm::dvec3(s.nodes[ref->node].mesh.vertex(ref->triangle, 0)), 1.0));
  EXPECT_GT(v.x, 49.9);
  EXPECT_GT(v.z, 49.9);
}

TEST(Chessboard, NestingNeedsBlockTimesPowerOfTwo) {
  EXPECT_NE(errorOf([] { generate("chessboard?n=96&block=64"); }).find(": n: "), std::string::npos);
  EXPECT_NE(errorOf([] { generate("chessboard?n=12&block=3"); }).find(": block: "),
            std::string::npos);
  EXPECT_NO_THROW(generate("chessboard?n=3&block=3"));  // odd is fine without nesting
}

// ---- sphereflake ----

TEST(Sphereflake, ExpandedCountFormula) {
  for (int d = 0; d <= 5; ++d) {
    const Scene s = generate("sphereflake?depth=" + std::to_string(d));
    uint64_t spheres = 0, p = 1;
    for (int k = 0; k <= d; ++k, p *= 9) spheres += p;
    EXPECT_EQ(s.uniqueTriangles(), 200u);
    EXPECT_EQ(s.expandedTriangles(), 200u * spheres) << "depth " << d;
  }
  EXPECT_EQ(generate("sphereflake").expandedTriangles(), 164000u);  // 820 spheres
}

TEST(Sphereflake, ChildrenTouchTheParentAndNotEachOther) {
  const Scene s = generate("sphereflake?depth=1");
  // The level-1 node: the sphere, then 9 children.
  const Node* level1 = nullptr;
  for (const Node& n : s.nodes)
    if (n.name == "sphereflake/level1") level1 = &n;
  ASSERT_NE(level1, nullptr);
  ASSERT_EQ(level1->instances.size(), 10u);
  std::vector<glm::dvec3> centres;
  for (size_t i = 1; i < 10; ++i) {
    const glm::dmat4& m = level1->instances[i].transform;
    centres.push_back(glm::dvec3(m[3]));
    EXPECT_NEAR(glm::length(glm::dvec3(m[0])), 1.0 / 3.0, 1e-12);  // radius a third
    EXPECT_NEAR(glm::length(centres.back()), 4.0 / 3.0, 1e-12);    // resting on the surface
    // Facing away from the parent: the child's +z axis is its direction.
    EXPECT_GT(glm::dot(glm::normalize(glm::dvec3(m[2])), glm::normalize(centres.back())), 0.999);
  }
  for (size_t i = 0; i < 9; ++i)
    for (size_t j = i + 1; j < 9; ++j)
      EXPECT_GE(glm::length(centres[i] - centres[j]), 2.0 / 3.0 - 1e-9);
  // Unit sphere: 200 outward triangles.
  const Mesh& sphere = s.nodes[level1->instances[0].node].mesh;
  ASSERT_EQ(sphere.size(), 200u);
  for (size_t t = 0; t < sphere.size(); ++t)
    EXPECT_GT(
        glm::dot(sphere.normal(t), sphere.vertex(t, 0) + sphere.vertex(t, 1) + sphere.vertex(t, 2)),
        0.0f);
}

// ---- city ----

TEST(City, DefaultSizeAndDeterminism) {
  const Scene a = generate("city");
  EXPECT_GT(a.uniqueTriangles(), 1800000u);
  EXPECT_LT(a.uniqueTriangles(), 2300000u);
  EXPECT_EQ(a.expandedTriangles(), a.uniqueTriangles());  // every block stored once
  EXPECT_EQ(a.stats.loaded, a.uniqueTriangles());
  EXPECT_EQ(a.stats.degenerate + a.stats.nonFinite, 0u);
  ASSERT_TRUE(a.camera.has_value());
  EXPECT_LT(a.camera->position.y, 10.0);  // street level
  const Scene b = generate("city?blocks=13&seed=1");
  EXPECT_TRUE(sameMeshes(a, b));
}

TEST(City, SeedChangesItAndThreadsDoNot) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const Scene one = generate("city?blocks=3&seed=7");
  omp_set_num_threads(std::max(2, threads));
  const Scene many = generate("city?blocks=3&seed=7");
  omp_set_num_threads(threads);
  EXPECT_TRUE(sameMeshes(one, many));
  EXPECT_FALSE(sameMeshes(one, generate("city?blocks=3&seed=8")));
}

TEST(City, ScalesWithBlocksSquared) {
  const Scene s1 = generate("city?blocks=2"), s2 = generate("city?blocks=4");
  EXPECT_EQ(s1.nodes.size(), 1u + 4u);
  EXPECT_EQ(s2.nodes.size(), 1u + 16u);
  const double ratio = double(s2.uniqueTriangles()) / double(s1.uniqueTriangles());
  EXPECT_GT(ratio, 2.5);
  EXPECT_LT(ratio, 6.0);
}

// ---- forest ----

uint64_t tileTriangles(const Scene& s, const Node& tile) {
  uint64_t n = tile.mesh.size();
  for (const Instance& i : tile.instances) n += s.nodes[i.node].mesh.size();
  return n;
}

TEST(Forest, ExactCountsAndTenToTheTwelve) {
  const Scene s0 = generate("forest?trees=20&levels=0");
  const Node& tile = s0.rootNode();
  EXPECT_EQ(tile.mesh.size(), 8192u);
  EXPECT_EQ(tile.instances.size(), 20u);
  const uint64_t perTile = tileTriangles(s0, tile);
  EXPECT_EQ(s0.expandedTriangles(), perTile);
  // 4 tree variants of a few thousand triangles each.
  for (int v = 0; v < 4; ++v) {
    EXPECT_GE(s0.nodes[size_t(v)].mesh.size(), 1800u);
    EXPECT_LE(s0.nodes[size_t(v)].mesh.size(), 2900u);
  }
  const Scene s6 = generate("forest?trees=20&levels=6");
  EXPECT_EQ(s6.expandedTriangles(), perTile << 24);  // 16^6 tiles
  EXPECT_EQ(s6.uniqueTriangles(), s0.uniqueTriangles());
  EXPECT_GE(generate("forest?levels=6").expandedTriangles(), 1000000000000ull);
}

TEST(Forest, TilesJoinSeamlesslyAndTreesStandOnTheGround) {
  const Scene s = generate("forest?trees=50&levels=0&seed=3");
  const Mesh& terrain = s.rootNode().mesh;
  // Heights of edge vertices at x = -64 and x = +64 must agree at each z.
  std::map<long, float> left, right;
  for (const glm::vec3& p : terrain.positions) {
    if (p.x == -64.0f) left[std::lround(p.z * 100)] = p.y;
    if (p.x == 64.0f) right[std::lround(p.z * 100)] = p.y;
  }
  ASSERT_EQ(left.size(), 65u);
  EXPECT_EQ(left, right);
  Bounds ground;
  for (const glm::vec3& p : terrain.positions) ground.extend(glm::dvec3(p));
  for (const Instance& i : s.rootNode().instances) {
    const double y = i.transform[3].y;  // the trunk base, sunk at most 0.3 * 1.25
    EXPECT_GE(y, ground.lo.y - 0.4);
    EXPECT_LE(y, ground.hi.y);
  }
}

TEST(Forest, Deterministic) {
  EXPECT_TRUE(sameMeshes(generate("forest?trees=10&levels=1&seed=5"),
                         generate("forest?trees=10&levels=1&seed=5")));
  EXPECT_FALSE(sameMeshes(generate("forest?trees=10&levels=1&seed=5"),
                          generate("forest?trees=10&levels=1&seed=6")));
}

// ---- landscape ----

TEST(Landscape, EveryTriangleStoredAndDistinct) {
  const Scene s = generate("landscape?objects=300&seed=4");
  EXPECT_EQ(s.expandedTriangles(), s.uniqueTriangles()) << "no instances";
  EXPECT_EQ(s.expandedTriangles(), 2u * 128 * 128 + 300u * 24);
  // Distinct objects: no two triangles alike (centroid and colour, to 1e-4).
  const auto all = worldTriangles(s);
  EXPECT_EQ(std::adjacent_find(all.begin(), all.end()), all.end());
  EXPECT_EQ(generate("landscape?objects=0").expandedTriangles(), 2u * 128 * 128);
  // The terrain's grid shares its vertices: 129^2 for its 2 * 128^2 triangles, but for the few
  // that MeshBuilder's cache of recent corners evicted before they recurred (under 1 %).
  const size_t vertices = generate("landscape?objects=0").rootNode().mesh.positions.size();
  EXPECT_GE(vertices, 129u * 129u);
  EXPECT_LT(vertices, 129u * 129u * 101 / 100);
  EXPECT_NE(errorOf([] { generate("landscape?objects=-1"); }).find("objects"), std::string::npos);
  EXPECT_NE(errorOf([] { generate("landscape?objects=5000000"); }).find("objects"), std::string::npos);
}

TEST(Landscape, Deterministic) {
  EXPECT_TRUE(sameMeshes(generate("landscape?objects=50&seed=2"), generate("landscape?objects=50&seed=2")));
  EXPECT_FALSE(sameMeshes(generate("landscape?objects=50&seed=2"), generate("landscape?objects=50&seed=3")));
}

// ---- replicated ----

const char* kTetrahedron =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

TEST(Replicated, GridCounts) {
  ScratchDir dir;
  const auto obj = dir.write("tet.obj", kTetrahedron);
  const Scene s = generate("replicated?mesh=" + obj.string() + "&k=3&levels=2");
  EXPECT_EQ(s.uniqueTriangles(), 4u);
  EXPECT_EQ(s.expandedTriangles(), 4u * 81);
  // Spacing 1.25 per copy: the grid spans about 9 * 1.25 along x.
  EXPECT_NEAR(s.bounds().extent().x, 8 * 1.25 + 1.0, 1e-9);
  const Scene one = generate("replicated?mesh=" + obj.string() + "&k=1&levels=0");
  EXPECT_EQ(one.expandedTriangles(), 4u);
}

TEST(Replicated, BadInputNamesTheKey) {
  ScratchDir dir;
  const auto obj = dir.write("tet.obj", kTetrahedron);
  EXPECT_NE(errorOf([] { generate("replicated?k=2"); }).find(": mesh: "), std::string::npos);
  const std::string missing =
      errorOf([&] { generate("replicated?mesh=" + (dir.path() / "no.obj").string()); });
  EXPECT_NE(missing.find(": mesh: "), std::string::npos) << missing;
  EXPECT_NE(missing.find("no.obj"), std::string::npos) << missing;
  EXPECT_NE(errorOf([&] {
              generate("replicated?mesh=" + obj.string() + "&k=1024&levels=10");
            }).find(": levels: "),
            std::string::npos);
  EXPECT_NE(errorOf([&] { generate("replicated?mesh=" + obj.string() + "&k=0"); }).find(": k: "),
            std::string::npos);
}

}  // namespace
}  // namespace lzb
