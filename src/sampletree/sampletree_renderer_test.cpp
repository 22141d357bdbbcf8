// The sample tree's frame: without stopping it is the exact z-buffer image; far away it is one
// splat; rank shares composite to the 1-rank image on any thread count.
#include "src/sampletree/sampletree_renderer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "src/sampletree/cube_projection.hpp"
#include "src/sampletree/traversal.hpp"
#include "src/sampletree/tree_build.hpp"
#include "src/scene/load.hpp"
#include "src/zbuffer/native_raster.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/frames.hpp"
#include "tests/support/render.hpp"

namespace lzb::sampletree {
namespace {

constexpr int kW = 160, kH = 120;

struct Rendered {
  Framebuffer fb;
  FrameStats stats;
};

Rendered renderTree(const Scene& scene, const Camera& camera, const SampleTreeOptions& st,
                    int threads, WorkShare share = {}) {
  RenderOptions options;
  options.threads = threads;
  options.seed = 9;
  SampleTreeRenderer r(scene, options, st);
  Rendered out;
  out.fb = test::renderFrame(r, camera, &out.stats, share);
  return out;
}

Camera nearCamera(const Scene& scene) {
  const Bounds b = scene.bounds();
  return test::lookAtCamera(b.center() + glm::dvec3(0.3, 0.5, 1.2) * b.diagonal(), b.center(),
                            0.01 * b.diagonal(), 10 * b.diagonal(), kW, kH);
}

TEST(SampleTreeRenderer, WithoutStoppingItIsTheExactZBuffer) {
  const Scene scene = loadScene("builtin:city?blocks=1", true);
  const Camera camera = nearCamera(scene);
  // One leaf holding every triangle, larger than a pixel: the traversal draws all of them.
  SampleTreeOptions st;
  st.leafTriangles = uint32_t(scene.expandedTriangles());
  const Rendered tree = renderTree(scene, camera, st, 2);
  EXPECT_EQ(tree.stats.counts["triangles_drawn"].get<double>(), double(scene.expandedTriangles()));
  DrawLists lists;
  for (const DrawItem& item : flattenScene(scene)) {
    DrawList l{item.node, item.transform, item.idBase, {}};
    for (uint32_t t = 0; t < scene.nodes[item.node].mesh.size(); ++t) l.triangles.push_back(t);
    lists.triangles += l.triangles.size();
    lists.lists.push_back(std::move(l));
  }
  Framebuffer exact(kW, kH);
  exact.clear();
  NativeRasterizer().draw(scene, camera, lists, {}, 2, exact);
  EXPECT_GT(exact.coveredCount(), 1000u);
  EXPECT_TRUE(test::sameKeys(tree.fb, exact));
}

TEST(SampleTreeRenderer, FarAwayTheRootIsOneSplat) {
  const Scene scene = loadScene("builtin:sphereflake?depth=2", true);
  const Bounds b = scene.bounds();
  const Camera camera = test::lookAtCamera(b.center() + glm::dvec3(0, 0, 1e4) * b.diagonal(),
                                           b.center(), 1.0, 1e6 * b.diagonal(), kW, kH);
  const Rendered r = renderTree(scene, camera, SampleTreeOptions{}, 1);
  EXPECT_EQ(r.stats.counts["splats_drawn"].get<double>(), 1.0);
  EXPECT_EQ(r.stats.counts["triangles_drawn"].get<double>(), 0.0);
  EXPECT_EQ(r.fb.coveredCount(), 1u);
}

TEST(SampleTreeRenderer, FarAwayTheRootDrawsItsTrianglesWhenAsked) {
  const Scene scene = loadScene("builtin:sphereflake?depth=2", true);
  const Bounds b = scene.bounds();
  const Camera camera = test::lookAtCamera(b.center() + glm::dvec3(0, 0, 1e4) * b.diagonal(),
                                           b.center(), 1.0, 1e6 * b.diagonal(), kW, kH);
  SampleTreeOptions st;
  st.stopDraw = StopDraw::kTriangles;
  RenderOptions options;
  options.threads = 1;
  options.seed = 9;
  SampleTreeRenderer r(scene, options, st);
  Framebuffer fb(kW, kH);
  fb.clear();
  FrameStats stats;
  r.render(camera, 0, WorkShare{}, fb, stats);
  EXPECT_EQ(stats.counts["splats_drawn"].get<double>(), 0.0);
  EXPECT_EQ(stats.counts["triangles_drawn"].get<double>(), double(r.tree().nodes[0].triangleCount));
  EXPECT_GT(r.tree().nodes[0].triangleCount, 0u);
}

TEST(SampleTreeRenderer, LargerSplatsStopEarlier) {
  const Scene scene = loadScene("builtin:sphereflake?depth=2", true);
  const Camera camera = nearCamera(scene);
  double previous = 1e300;
  for (int splat : {1, 3, 5}) {
    SampleTreeOptions st;
    st.splat = splat;
    const Rendered r = renderTree(scene, camera, st, 2);
    const double triangles = r.stats.counts["triangles_drawn"].get<double>();
    EXPECT_LE(triangles, previous) << "splat " << splat;
    previous = triangles;
    if (splat > 1) {
      EXPECT_GT(r.stats.counts["splats_drawn"].get<double>(), 0.0) << "splat " << splat;
    }
  }
  EXPECT_LT(previous, double(scene.expandedTriangles()));
}

TEST(SampleTreeRenderer, RankSharesAndThreadsGiveTheSameImage) {
  const Scene scene = loadScene("builtin:sphereflake?depth=2", true);
  const Camera camera = nearCamera(scene);
  for (int splat : {1, 2}) {
    SampleTreeOptions st;
    st.splat = splat;
    const Rendered one = renderTree(scene, camera, st, 2);
    EXPECT_TRUE(test::sameKeys(one.fb, renderTree(scene, camera, st, 1).fb));
    for (int size : {2, 3}) {
      Framebuffer all(kW, kH);
      all.clear();
      double triangles = 0, splats = 0;
      for (int rank = 0; rank < size; ++rank) {
        const Rendered part = renderTree(scene, camera, st, 1, WorkShare{rank, size});
        compositeNearer(all, part.fb);
        triangles += part.stats.counts["triangles_drawn"].get<double>();
        splats += part.stats.counts["splats_drawn"].get<double>();
      }
      EXPECT_TRUE(test::sameKeys(one.fb, all)) << size << " ranks, splat " << splat;
      EXPECT_EQ(triangles, one.stats.counts["triangles_drawn"].get<double>());
      EXPECT_EQ(splats, one.stats.counts["splats_drawn"].get<double>());
    }
  }
}

TEST(Traversal, ProjectedCellShrinksWithDistance) {
  SampleTree tree;
  tree.size = 1.0;
  TreeNode root;
  root.subtreeEnd = 1;
  tree.nodes.push_back(root);
  const auto at = [&](double z) {
    return projectedCellPixels(tree, tree.nodes[0],
                               test::lookAtCamera({0.5, 0.5, z}, {0.5, 0.5, 0}, 0.1, 1e9, kW, kH));
  };
  EXPECT_GT(at(10), at(100));
  EXPECT_NEAR(at(1000) / at(2000), 4.0, 0.05);
  // A corner behind the near plane: never a stop.
  EXPECT_TRUE(std::isinf(at(0.5)));
}

TEST(Traversal, ThreadsWalkSubtreesAndGiveTheOneThreadWalk) {
  const Scene scene = loadScene("builtin:landscape?objects=300", true);
  const SampleTree tree = buildTree(scene, TreeParams{13.8, 9, 8}, 2);
  const Camera camera = nearCamera(scene);
  const Traversal one = traverse(tree, camera, 1, StopDraw::kSplat, 1);
  // Deep enough that subtrees of the task level are walked by the threads.
  size_t deep = 0;
  for (const Visit& v : one.visits) deep += tree.nodes[v.node].level > 4;
  ASSERT_GT(deep, 100u);
  for (int threads : {2, 3}) {
    const Traversal many = traverse(tree, camera, 1, StopDraw::kSplat, threads);
    ASSERT_EQ(many.visits.size(), one.visits.size()) << threads;
    for (size_t k = 0; k < one.visits.size(); ++k) {
      EXPECT_EQ(many.visits[k].node, one.visits[k].node);
      EXPECT_EQ(many.visits[k].splat, one.visits[k].splat);
    }
    EXPECT_EQ(many.stops, one.stops);
    EXPECT_EQ(many.visited, one.visited);
    EXPECT_EQ(many.culled, one.culled);
  }
}

TEST(CubeProjector, GivesTheRectangleOfTheCornersProjections) {
  const Camera camera = test::lookAtCamera({3, 2, 9}, {0.5, 0.2, 0}, 0.1, 100, kW, kH);
  const CubeProjector cubes(camera);
  for (const glm::dvec3 lo : {glm::dvec3(0, 0, 0), glm::dvec3(-2, 1, 3), glm::dvec3(1, -1, -4)}) {
    const double side = 0.7;
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 p = camera.project(lo + side * glm::dvec3(k & 1, (k >> 1) & 1, k >> 2));
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y),
      y1 = std::max(y1, p.y);
    }
    const ScreenRect r = cubes.rect(lo, side);
    EXPECT_FALSE(r.behind);
    EXPECT_NEAR(r.x0, x0, 1e-9);
    EXPECT_NEAR(r.x1, x1, 1e-9);
    EXPECT_NEAR(r.y0, y0, 1e-9);
    EXPECT_NEAR(r.y1, y1, 1e-9);
  }
  // A cube around the eye reaches behind the near plane.
  EXPECT_TRUE(cubes.rect({2.5, 1.5, 8.5}, 1.0).behind);
}

}  // namespace
}  // namespace lzb::sampletree
