// The sample tree's draw (a triangle soup from its nodes) against the native z-buffer's own draw
// lists on the same triangles, in one run; only with LZB_BENCH=1 (seconds; it prints figures and
// asserts only that both frames are drawn):
//   LZB_BENCH=1 build/src/sampletree/sampletree_test --gtest_filter='SampleTreeBench.*'
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numeric>

#include "src/core/timer.hpp"
#include "src/sampletree/traversal.hpp"
#include "src/sampletree/tree_build.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/native_raster.hpp"
#include "tests/support/bench.hpp"
#include "tests/support/cameras.hpp"

namespace lzb::sampletree {
namespace {

using test::benchEnabled;

double bestOf3(const std::function<void()>& draw) {
  double best = 1e30;
  for (int i = 0; i < 3; ++i) {
    Stopwatch clock;
    draw();
    best = std::min(best, clock.seconds());
  }
  return best;
}

TEST(SampleTreeBench, SoupDrawAgainstTheNativeZBufferOnTheSameTriangles) {
  if (!benchEnabled()) GTEST_SKIP() << "set LZB_BENCH=1";
  const Scene scene = loadScene("builtin:landscape?objects=100000", true);
  const SampleTree tree = buildTree(scene, TreeParams{}, 2);
  const Camera camera = test::sceneCamera(scene, 640, 480);
  std::vector<SoupRange> ranges;
  for (const Visit& v : traverse(tree, camera, 1, StopDraw::kSplat, 2).visits)
    if (!v.splat)
      ranges.push_back({tree.nodes[v.node].firstTriangle,
                        tree.nodes[v.node].firstTriangle + tree.nodes[v.node].triangleCount});
  // The same triangles as one mesh drawn through one ascending draw list.
  Scene same;
  same.addNode("drawn");
  Mesh& mesh = same.nodes[0].mesh;
  for (const SoupRange& r : ranges)
    mesh.positions.insert(mesh.positions.end(), tree.positions.begin() + long(3 * r.begin),
                          tree.positions.begin() + long(3 * r.end));
  const size_t n = mesh.positions.size() / 3;
  mesh.indices.resize(3 * n);
  std::iota(mesh.indices.begin(), mesh.indices.end(), 0u);
  mesh.colors.assign(n, Rgba8{});
  same.finalize();
  DrawLists lists;
  lists.lists.push_back(DrawList{0, glm::dmat4(1.0), 0, std::vector<uint32_t>(n)});
  std::iota(lists.lists[0].triangles.begin(), lists.lists[0].triangles.end(), 0u);
  lists.triangles = n;

  NativeRasterizer raster;
  Framebuffer soupFb(640, 480), listFb(640, 480);
  const double soup = bestOf3([&] {
    soupFb.clear();
    raster.drawSoup(camera, TriangleSoup{tree.positions, tree.ids, ranges}, 2, soupFb);
  });
  const double list = bestOf3([&] {
    listFb.clear();
    raster.draw(same, camera, lists, {}, 2, listFb);
  });
  std::printf("[ sampletree ] %zu triangles of %zu nodes, 640x480, 2 threads: soup %.1f ms "
              "(%.1f M/s), draw lists %.1f ms (%.1f M/s): soup/list %.2f\n",
              n, ranges.size(), 1e3 * soup, 1e-6 * double(n) / soup, 1e3 * list,
              1e-6 * double(n) / list, soup / list);
  RecordProperty("soup_over_list", std::to_string(soup / list));
  EXPECT_GT(soupFb.coveredCount(), soupFb.size() / 4);
  EXPECT_GT(listFb.coveredCount(), listFb.size() / 4);
}

}  // namespace
}  // namespace lzb::sampletree
