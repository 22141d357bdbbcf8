#include "raycast/lzb/lzb_cull.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

#include "raycast/lzb/lzb_renderer.hpp"
#include "src/image/metrics.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"
#include "tests/support/cameras.hpp"

namespace lzb::localz {
namespace {

using test::pathFrame;

// The root's instances are culled in parallel; the parts are joined in instance order, so any
// thread count lists the same paths and leaves in the same order.
TEST(LzbCull, SameResultForAnyThreadCount) {
  const Scene scene = loadScene("builtin:city?blocks=4", true);
  const LzbAccel accel(scene, LzbAccelParams{});
  for (int f : {0, 1}) {
    const Camera cam = pathFrame(scene, f, 4, 160, 120);
    const CulledScene one = cullScene(accel, cam, 1), two = cullScene(accel, cam, 2);
    ASSERT_GT(one.paths.size(), 1u) << f;
    ASSERT_EQ(one.paths.size(), two.paths.size()) << f;
    for (size_t p = 0; p < one.paths.size(); ++p) {
      EXPECT_EQ(one.paths[p].node, two.paths[p].node);
      EXPECT_EQ(one.paths[p].idBase, two.paths[p].idBase);
      EXPECT_EQ(one.paths[p].firstLeaf, two.paths[p].firstLeaf);
      EXPECT_EQ(one.paths[p].leafCount, two.paths[p].leafCount);
      // A path's leaf range holds exactly its leaves (the lists are grouped by path).
      for (const CulledScene* c : {&one, &two})
        for (uint32_t l = 0; l < c->leaves.size(); ++l)
          EXPECT_EQ(c->leaves[l].path == p, l >= c->paths[p].firstLeaf &&
                                                l < c->paths[p].firstLeaf + c->paths[p].leafCount);
      if (p > 0) {
        EXPECT_LT(one.paths[p - 1].idBase, one.paths[p].idBase) << "ascending idBase";
      }
    }
    ASSERT_EQ(one.leaves.size(), two.leaves.size()) << f;
    for (size_t l = 0; l < one.leaves.size(); ++l) {
      EXPECT_EQ(one.leaves[l].path, two.leaves[l].path);
      EXPECT_EQ(one.leaves[l].leaf, two.leaves[l].leaf);
      EXPECT_EQ(one.leaves[l].depthMin, two.leaves[l].depthMin);
    }
    EXPECT_EQ(one.instancesVisited, two.instancesVisited);
  }
}

// A cull up to a view depth lists, of the whole cull's leaves, exactly those starting before it
// (a leaf's content box not wholly beyond).
TEST(LzbCull, UpToADepthListsTheLeavesStartingBeforeIt) {
  const Scene scene = loadScene("builtin:city?blocks=4", true);
  const LzbAccel accel(scene, LzbAccelParams{});
  const Camera cam = pathFrame(scene, 1, 4, 160, 120);
  const CulledScene whole = cullScene(accel, cam, 2);
  ASSERT_GT(whole.leaves.size(), 100u);
  std::vector<double> starts;
  for (const CullLeaf& l : whole.leaves) starts.push_back(l.depthMin);
  std::sort(starts.begin(), starts.end());
  for (double fraction : {0.05, 0.2, 0.5}) {  // depths between the leaves' starts
    const double depth = starts[size_t(fraction * double(starts.size()))];
    CulledScene part;
    cullScene(accel, cam, part, 2, nullptr, depth);
    std::set<std::pair<uint64_t, uint32_t>> listed, expected, all;
    for (const CullLeaf& l : whole.leaves) all.insert({whole.paths[l.path].idBase, l.leaf});
    for (const CullLeaf& l : part.leaves) {
      listed.insert({part.paths[l.path].idBase, l.leaf});
      EXPECT_LE(l.depthMin, depth * (1.0 + 1e-9));
    }
    for (const CullLeaf& l : whole.leaves)
      if (l.depthMin <= depth * (1.0 - 1e-9)) expected.insert({whole.paths[l.path].idBase, l.leaf});
    EXPECT_GT(expected.size(), 0u) << fraction;
    EXPECT_LT(listed.size(), whole.leaves.size()) << fraction;
    // Every leaf starting before the depth is listed, and only the whole cull's leaves are.
    for (const auto& key : expected) EXPECT_TRUE(listed.count(key)) << fraction;
    for (const auto& key : listed) EXPECT_TRUE(all.count(key)) << fraction;
  }
}

}  // namespace
}  // namespace lzb::localz
