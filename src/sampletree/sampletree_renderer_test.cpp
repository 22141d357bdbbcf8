// The sample tree's frame: without stopping it is the exact z-buffer image; far away it is one
// splat; rank shares composite to the 1-rank image on any thread count.
#include <gtest/gtest.h>

#include <cstring>

#include "src/sampletree/sampletree_renderer.hpp"
#include "src/sampletree/traversal.hpp"
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

}  // namespace
}  // namespace lzb::sampletree
