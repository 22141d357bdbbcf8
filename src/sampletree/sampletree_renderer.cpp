#include "src/sampletree/sampletree_renderer.hpp"

#include <string>
#include <vector>

#include "mpi/decomposition.hpp"
#include "src/core/error.hpp"
#include "src/core/timer.hpp"
#include "src/sampletree/approximated_pixels.hpp"
#include "src/sampletree/traversal.hpp"
#include "src/sampletree/tree_build.hpp"
#include "src/sampletree/tree_store.hpp"
#include "src/splat/splatter.hpp"

namespace lzb::sampletree {

namespace {

// The splats of `nodes`, each its representative triangle's centroid in camera space.
template <bool kWide, bool kPixel>
uint64_t splatNodes(const SampleTree& tree, const std::vector<uint32_t>& nodes,
                    const Camera& camera, const SplatSetup& setup, KeyBuffer& keys) {
  PointSplatter<kWide, kPixel> splatter(setup, keys);
  for (uint32_t i : nodes) {
    const TreeNode& n = tree.nodes[i];
    const glm::dvec3 d = glm::dvec3(n.representativePoint[0], n.representativePoint[1],
                                    n.representativePoint[2]) - camera.position();
    splatter.add(float(glm::dot(d, camera.right())), float(glm::dot(d, camera.up())),
                 float(glm::dot(d, camera.forward())), n.representativeId);
  }
  splatter.flush();
  return splatter.splatted();
}

}  // namespace

SampleTreeRenderer::SampleTreeRenderer(const Scene& scene, const RenderOptions& options,
                                       const SampleTreeOptions& st)
    : scene_(scene), options_(options), st_(st) {
  Stopwatch clock;
  if (st.treePath.empty()) {
    tree_ = buildTree(scene, TreeParams{st.c, options.seed, st.leafTriangles}, options.threads);
    setup_.addStage("build_tree", clock.lap());
  } else {
    tree_ = readTree(st.treePath);
    require(tree_.sceneTriangles == scene.expandedTriangles(), st.treePath + " (sample tree store)",
            "built from a scene of " + std::to_string(tree_.sceneTriangles) +
                " expanded triangles, but " + scene.source + " has " +
                std::to_string(scene.expandedTriangles()));
    setup_.addStage("read_tree", clock.lap());
  }
  // The construction's own c and seed: a store's, whatever --c and --seed say.
  setup_.setShared("tree_c", tree_.params.c);
  setup_.setShared("tree_seed", double(tree_.params.seed));
  setup_.setShared("tree_nodes", double(tree_.nodes.size()));
  setup_.setShared("tree_triangles", double(tree_.triangles()));
  setup_.setShared("tree_bytes", double(storeBytes(tree_)));
}

std::string SampleTreeRenderer::decomposition() const {
  return "the tree traversal on every rank; the visited nodes, in preorder, dealt to ranks as "
         "contiguous runs of equal cost (a node's triangles, 1 per splat); each rank draws its "
         "nodes' triangles (native z-buffer) and splats into one key buffer; depth compositing "
         "by (depth, id)";
}

void SampleTreeRenderer::render(const Camera& camera, int /*frame*/, const WorkShare& share,
                                Framebuffer& fb, FrameStats& stats) {
  Stopwatch clock;
  const Traversal walk = traverse(tree_, camera, st_.splat, st_.stopDraw);
  std::vector<double> costs;
  costs.reserve(walk.visits.size());
  for (const Visit& v : walk.visits)
    costs.push_back(v.splat ? 1.0 : double(tree_.nodes[v.node].triangleCount));
  std::vector<SoupRange> ranges;
  std::vector<uint32_t> splats;
  uint64_t triangles = 0;
  for (uint32_t k : dealByCost(costs, share)) {
    const Visit& v = walk.visits[k];
    const TreeNode& n = tree_.nodes[v.node];
    if (v.splat) {
      splats.push_back(v.node);
    } else {
      ranges.push_back({n.firstTriangle, n.firstTriangle + n.triangleCount});
      triangles += n.triangleCount;
    }
  }
  stats.addStage("traverse", clock.lap());

  keys_.reset(camera.width(), camera.height(), scene_.expandedTriangles() > 0xffffffffull,
              options_.threads);
  const SplatSetup setup = SplatSetup::from(camera, st_.splat);
  uint64_t splatted = 0;
  if (keys_.wide())
    splatted = st_.splat == 1 ? splatNodes<true, true>(tree_, splats, camera, setup, keys_)
                              : splatNodes<true, false>(tree_, splats, camera, setup, keys_);
  else
    splatted = st_.splat == 1 ? splatNodes<false, true>(tree_, splats, camera, setup, keys_)
                              : splatNodes<false, false>(tree_, splats, camera, setup, keys_);
  keys_.resolve(fb, options_.threads);
  stats.addStage("splat", clock.lap());

  // The native z-buffer keeps the nearer (depth, ID) against the splats already in fb.
  raster_.drawSoup(camera, TriangleSoup{tree_.positions, tree_.ids, ranges}, options_.threads, fb);
  stats.addStage("triangles", clock.lap());

  stats.setShared("approximated_pixels",
                  double(approximatedPixels(
                      tree_, walk.stops, camera, st_.stopDraw == StopDraw::kSplat ? st_.splat : 0)));
  stats.addStage("approximated", clock.lap());
  stats.setShared("nodes_visited", double(walk.visited));
  stats.setShared("nodes_stopped", double(walk.stops.size()));
  stats.setShared("subtrees_culled", double(walk.culled));
  stats.setShared("tree_bytes", double(storeBytes(tree_)));
  stats.addCount("nodes_drawn", double(ranges.size()));
  stats.addCount("triangles_drawn", double(triangles));
  stats.addCount("splats_drawn", double(splats.size()));
  stats.addCount("splats_in_image", double(splatted));
}

}  // namespace lzb::sampletree
