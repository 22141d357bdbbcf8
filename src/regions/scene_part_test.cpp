#include "src/regions/scene_part.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <set>

namespace lzb::regions {
namespace {

// A root with 4 triangles of its own and 3 instances of a 2-triangle mesh, one of them through
// a node that instances the mesh twice more: expanded IDs 0-3 (root), 4-5, 6-9 (2 + 2), 10-11.
Scene mixedScene() {
  Scene s;
  s.root = s.addNode("root");
  const uint32_t mesh = s.addNode("mesh"), pair = s.addNode("pair");
  for (int k = 0; k < 4; ++k)
    s.nodes[s.root].mesh.add({float(k), 0, 0}, {k + 1.0f, 0, 0}, {float(k), 1, 0},
                             packRgba8(uint8_t(k), 0, 0));
  s.nodes[mesh].mesh.add({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, packRgba8(0, 9, 0));
  s.nodes[mesh].mesh.add({0, 0, 1}, {1, 0, 1}, {0, 1, 1}, packRgba8(0, 8, 0));
  s.nodes[pair].instances = {{mesh, glm::translate(glm::dmat4(1.0), {0, 5, 0})},
                             {mesh, glm::translate(glm::dmat4(1.0), {0, 6, 0})}};
  s.nodes[s.root].instances = {{mesh, glm::translate(glm::dmat4(1.0), {10, 0, 0})},
                               {pair, glm::dmat4(1.0)},
                               {mesh, glm::translate(glm::dmat4(1.0), {-10, 0, 0})}};
  s.finalize();
  return s;
}

// The world position of corner k of the triangle `id` names in `scene`.
glm::dvec3 corner(const Scene& scene, uint64_t id, int k) {
  const auto ref = scene.resolve(id);
  EXPECT_TRUE(ref.has_value()) << id;
  const glm::vec3 p = scene.nodes[ref->node].mesh.vertex(ref->triangle, k);
  return glm::dvec3(ref->transform * glm::dvec4(glm::dvec3(p), 1.0));
}

// Part 0 holds the odd units (odd) or the even ones.
PartOf pattern(size_t n, bool odd) {
  PartOf partOf(n);
  for (size_t i = 0; i < n; ++i) partOf[i] = (i % 2 == 1) == odd ? 0 : kNoPart;
  return partOf;
}

TEST(ScenePart, UnitsAreTheRootsTrianglesThenInstancesOpenedWhileLarge) {
  const Scene s = mixedScene();
  // 12 triangles, 1 region: instances over 12 / 8 triangles are opened where they can be (the
  // pair: into its two instances; the mesh instances are leaves).
  const SceneUnits units = sceneUnits(s, 1);
  ASSERT_EQ(units.size(), 8u);
  EXPECT_EQ(units.meshTriangles, 4u);
  std::vector<uint64_t> bases, triangles;
  for (size_t u = 0; u < units.size(); ++u) triangles.push_back(units.triangles(u));
  for (const SceneUnit& u : units.opened) bases.push_back(u.idBase);
  EXPECT_EQ(bases, (std::vector<uint64_t>{4, 6, 8, 10}));
  EXPECT_EQ(triangles, (std::vector<uint64_t>{1, 1, 1, 1, 2, 2, 2, 2}));
  EXPECT_EQ(units.opened[1].path, (std::vector<uint32_t>{1, 0})) << "the pair's first instance";
  EXPECT_TRUE(units.opened[1].subtree);
  std::vector<glm::dvec3> centres;
  units.centres(s, centres);
  EXPECT_NEAR(centres[4].x, 10.5, 1e-12) << "the instance's world box centre";
  EXPECT_NEAR(centres[5].y, 5.5, 1e-12) << "placed through both transforms";
  EXPECT_NEAR(centres[0].x, 1.0 / 3.0, 1e-6) << "the triangle's centroid";
}

TEST(ScenePart, APartKeepsItsUnitsWithTheWholeScenesIds) {
  const Scene whole = mixedScene();
  const SceneUnits units = sceneUnits(whole, 1);
  const ScenePart part = cutScene(whole, units, pattern(units.size(), true), 1)[0];
  EXPECT_EQ(part.units, 4u);
  EXPECT_EQ(part.ids.size(), part.scene.expandedTriangles());
  const std::vector<uint64_t> expected = {1, 3, 6, 7, 10, 11};
  ASSERT_EQ(part.ids.size(), expected.size());
  for (uint64_t local = 0; local < part.ids.size(); ++local) {
    const uint64_t global = part.ids.global(local);
    EXPECT_EQ(global, expected[local]);
    EXPECT_EQ(part.ids.local(global), local);
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(corner(part.scene, local, k), corner(whole, global, k)) << local << " corner " << k;
    const auto a = part.scene.resolve(local), b = whole.resolve(global);
    EXPECT_EQ(part.scene.nodes[a->node].mesh.color(a->triangle),
              whole.nodes[b->node].mesh.color(b->triangle));
  }
  EXPECT_EQ(part.ids.global(part.ids.size()), kNoId);
  EXPECT_EQ(part.ids.global(kNoId), kNoId);
  for (const uint64_t absent : {uint64_t(0), uint64_t(2), uint64_t(8), uint64_t(12), kNoId})
    EXPECT_EQ(part.ids.local(absent), kNoId) << absent;
  // The opened pair is a node of its own holding one of its two instances, with the pair's box.
  ASSERT_EQ(part.scene.nodes.size(), whole.nodes.size() + 1);
  EXPECT_EQ(part.scene.nodes.back().instances.size(), 1u);
  EXPECT_EQ(part.scene.nodeBounds.back().lo, whole.nodeBounds[2].lo);
  EXPECT_EQ(part.scene.nodeBounds[part.scene.root].hi, whole.bounds().hi) << "the whole root's box";
}

TEST(ScenePart, PartsOfComplementaryUnitsHoldEveryIdOnce) {
  const Scene whole = mixedScene();
  const SceneUnits units = sceneUnits(whole, 3);
  std::multiset<uint64_t> ids;
  PartOf both(units.size());
  for (size_t u = 0; u < units.size(); ++u) both[u] = uint32_t(u % 2);
  const std::vector<ScenePart> parts = cutScene(whole, units, both, 2);
  ASSERT_EQ(parts.size(), 2u);
  for (bool odd : {false, true}) {
    const ScenePart& part = parts[odd];
    const ScenePart alone = cutScene(whole, units, pattern(units.size(), odd), 1)[0];
    ASSERT_EQ(part.ids.size(), alone.ids.size()) << "one cut into two parts is two cuts";
    EXPECT_EQ(part.units, alone.units);
    EXPECT_EQ(part.scene.nodes.size(), alone.scene.nodes.size());
    for (uint64_t local = 0; local < part.ids.size(); ++local) {
      ids.insert(part.ids.global(local));
      EXPECT_EQ(part.ids.global(local), alone.ids.global(local));
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(corner(part.scene, local, k), corner(alone.scene, local, k));
    }
  }
  ASSERT_EQ(ids.size(), whole.expandedTriangles());
  uint64_t next = 0;
  for (uint64_t id : ids) EXPECT_EQ(id, next++);
}

// Three mesh files as a TOML scene places them: A (6 triangles) and, through a recentring node,
// C (5) each placed once; D (3) placed twice. Expanded IDs: A 0-5, C 6-10, D 11-13 and 14-16.
Scene filesScene() {
  Scene s;
  s.root = s.addNode("root");
  const uint32_t a = s.addNode("a"), b = s.addNode("b"), c = s.addNode("c"), d = s.addNode("d");
  for (int k = 0; k < 6; ++k)
    s.nodes[a].mesh.add({float(k), 0, 0}, {k + 1.0f, 0, 0}, {float(k), 1, 0}, packRgba8(1, 0, 0));
  for (int k = 0; k < 5; ++k)
    s.nodes[c].mesh.add({0, float(k), 0}, {0, k + 1.0f, 0}, {1, float(k), 0}, packRgba8(0, 1, 0));
  for (int k = 0; k < 3; ++k)
    s.nodes[d].mesh.add({0, 0, float(k)}, {1, 0, float(k)}, {0, 1, float(k)}, packRgba8(0, 0, 1));
  s.nodes[b].instances = {{c, glm::translate(glm::dmat4(1.0), {0, 0, 100})}};
  s.nodes[s.root].instances = {{a, glm::translate(glm::dmat4(1.0), {50, 0, 0})},
                               {b, glm::dmat4(1.0)},
                               {d, glm::dmat4(1.0)},
                               {d, glm::translate(glm::dmat4(1.0), {0, 50, 0})}};
  s.finalize();
  return s;
}

TEST(ScenePart, AMeshPlacedOnceIsCutIntoItsTriangles) {
  const Scene whole = filesScene();
  const SceneUnits units = sceneUnits(whole, 4);
  ASSERT_EQ(units.size(), 6u + 5u + 2u) << "A's and C's triangles, D's two placements";
  std::vector<glm::dvec3> centres;
  units.centres(whole, centres);
  for (size_t u = 0; u < units.size(); ++u) {
    EXPECT_EQ(units.triangles(u), u < 11 ? 1u : 3u) << u;
    if (u < 11) {  // a split mesh's unit sits at its triangle's placed centroid
      glm::dvec3 c(0.0);
      for (int k = 0; k < 3; ++k) c += corner(whole, u, k) / 3.0;
      EXPECT_LT(glm::length(centres[u] - c), 1e-9) << u;
    }
  }
  PartOf both(units.size());
  for (size_t u = 0; u < units.size(); ++u) both[u] = uint32_t(u % 3 == 0);
  const std::vector<ScenePart> parts = cutScene(whole, units, both, 2);
  std::set<uint64_t> ids;
  for (const ScenePart& part : parts) {
    uint64_t last = 0;
    for (uint64_t local = 0; local < part.ids.size(); ++local) {
      const uint64_t global = part.ids.global(local);
      EXPECT_TRUE(local == 0 || global > last) << "IDs rise with the whole scene's";
      last = global;
      EXPECT_EQ(part.ids.local(global), local);
      EXPECT_TRUE(ids.insert(global).second) << global << " held twice";
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(corner(part.scene, local, k), corner(whole, global, k)) << global;
    }
  }
  EXPECT_EQ(ids.size(), whole.expandedTriangles());
}

TEST(ScenePart, AnEmptyPartHoldsNothing) {
  const Scene whole = mixedScene();
  const SceneUnits units = sceneUnits(whole, 1);
  const ScenePart part = cutScene(whole, units, PartOf(units.size(), kNoPart), 1)[0];
  EXPECT_EQ(part.scene.expandedTriangles(), 0u);
  EXPECT_EQ(part.scene.uniqueTriangles(), 0u);
  EXPECT_EQ(part.ids.size(), 0u);
  EXPECT_THROW(cutScene(whole, units, PartOf(units.size() - 1, 0), 1), std::invalid_argument);
}

}  // namespace
}  // namespace lzb::regions
