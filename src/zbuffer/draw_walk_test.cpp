#include "src/zbuffer/draw_walk.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace lzb {
namespace {

void addQuad(Mesh& m, float z) {
  m.add({-1, -1, z}, {1, -1, z}, {1, 1, z}, packRgba8(200, 100, 50));
  m.add({-1, -1, z}, {1, 1, z}, {-1, 1, z}, packRgba8(200, 100, 50));
}

// Root (1 quad) -> 3 instances of a group (own quad + 2 instances of a leaf quad): 2 + 3 * 6 IDs.
Scene nestedScene() {
  Scene s;
  const uint32_t root = s.addNode("root"), group = s.addNode("group"), leaf = s.addNode("leaf");
  addQuad(s.nodes[root].mesh, 0.0f);
  addQuad(s.nodes[group].mesh, 0.0f);
  addQuad(s.nodes[leaf].mesh, 0.0f);
  for (int i = 0; i < 2; ++i)
    s.nodes[group].instances.push_back(
        {leaf, glm::translate(glm::dmat4(1.0), {0.0, 3.0 * (i + 1), 0.0})});
  for (int i = 0; i < 3; ++i)
    s.nodes[root].instances.push_back(
        {group, glm::translate(glm::dmat4(1.0), {5.0 * (i + 1), 0.0, 0.0})});
  s.root = root;
  s.finalize();
  return s;
}

Frustum everything() {
  CameraSpec spec;
  spec.position = {10.0, 3.0, 100.0};
  spec.lookAt = {10.0, 3.0, 0.0};
  spec.nearPlane = 1.0;
  spec.farPlane = 1000.0;
  return Camera(spec, 64, 64).frustum();
}

TEST(DrawWalk, FollowsFlattenSceneOrder) {
  const Scene s = nestedScene();
  const std::vector<DrawItem> items = flattenScene(s);
  std::vector<DrawCall> calls;
  const WalkCounts c = DrawWalk(s).walk(everything(), {0, s.expandedTriangles()},
                                        [&](const DrawCall& d) { calls.push_back(d); });
  ASSERT_EQ(calls.size(), items.size());
  for (size_t i = 0; i < calls.size(); ++i) {
    EXPECT_EQ(calls[i].node, items[i].node);
    EXPECT_EQ(calls[i].firstId, items[i].idBase);
    EXPECT_EQ(calls[i].first, 0u);
    EXPECT_EQ(calls[i].count, 2u);
    EXPECT_EQ(calls[i].world, items[i].transform);
  }
  EXPECT_EQ(c.items, items.size());
  EXPECT_EQ(c.culled, 0u);
  EXPECT_EQ(c.triangles, s.expandedTriangles());
}

TEST(DrawWalk, RankRangesCoverEveryTriangleOnceInOrder) {
  const Scene s = nestedScene();
  const DrawWalk walk(s);
  for (int size : {1, 2, 3, 5, 7, 25}) {
    uint64_t next = 0;
    for (int rank = 0; rank < size; ++rank) {
      const IdRange r = shareRange(s.expandedTriangles(), {rank, size});
      EXPECT_EQ(r.begin, next);
      walk.walk(everything(), r, [&](const DrawCall& d) {
        EXPECT_EQ(d.firstId, next);  // contiguous and ascending
        next += d.count;
      });
      EXPECT_EQ(next, r.end);
    }
    EXPECT_EQ(next, s.expandedTriangles()) << size;
  }
}

TEST(DrawWalk, CullsWholeSubtreesAndCountsTheirItems) {
  Scene s = nestedScene();
  // Move the second group behind the camera: its 3 draw items (own quad + 2 leaves) are culled.
  s.nodes[s.root].instances[1].transform = glm::translate(glm::dmat4(1.0), {0.0, 0.0, 500.0});
  s.finalize();
  std::vector<uint64_t> ids;
  const WalkCounts c = DrawWalk(s).walk(everything(), {0, s.expandedTriangles()},
                                        [&](const DrawCall& d) { ids.push_back(d.firstId); });
  EXPECT_EQ(c.items, 10u);
  EXPECT_EQ(c.culled, 3u);
  EXPECT_EQ(c.triangles, 14u);
  EXPECT_EQ(ids, (std::vector<uint64_t>{0, 2, 4, 6, 14, 16, 18}));
  // Only part of the culled subtree lies in this range: only those items are counted.
  const WalkCounts part = DrawWalk(s).walk(everything(), {10, 20}, [](const DrawCall&) {});
  EXPECT_EQ(part.items, 5u);  // culled group 1: leaves at 10 and 12 (not its quad at 8); group 2: 3
  EXPECT_EQ(part.culled, 2u);
}

TEST(DrawWalk, CutsDrawItemsAtRangeEdges) {
  const Scene s = nestedScene();
  std::vector<DrawCall> calls;
  DrawWalk(s).walk(everything(), {3, 7}, [&](const DrawCall& d) { calls.push_back(d); });
  ASSERT_EQ(calls.size(), 3u);
  EXPECT_EQ(calls[0].firstId, 3u);
  EXPECT_EQ(calls[0].first, 1u);
  EXPECT_EQ(calls[0].count, 1u);
  EXPECT_EQ(calls[1].firstId, 4u);
  EXPECT_EQ(calls[1].count, 2u);
  EXPECT_EQ(calls[2].firstId, 6u);
  EXPECT_EQ(calls[2].first, 0u);
  EXPECT_EQ(calls[2].count, 1u);
}

}  // namespace
}  // namespace lzb
