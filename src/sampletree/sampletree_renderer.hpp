#pragma once
// --method sampletree: the randomized sample tree's frame. Every rank traverses the tree alike
// (traversal.hpp); the visited nodes, in preorder, are dealt to ranks as runs of equal cost
// (dealByCost: a node costs its triangles, a splat 1); each rank draws its nodes' triangles with
// the native z-buffer and its splats with the splatting core into one key buffer, so compositing
// the ranks by (depth, ID) gives the 1-rank image for any rank or thread count. Out of core
// (a store and cacheMb > 0) only the node table is resident: the drawn nodes' triangles come
// from the node cache (node_cache.hpp, paged_draw.hpp), the same image as in core. With a node
// server (nodeServer, >= 2 ranks) the last rank serves the payloads (node_server.hpp) and draws
// nothing; the others split the frame among themselves as above and load through it. Colour comes
// from the tree's own triangles (tree_shading.hpp), so `scene` may be an outline without any.
#include <memory>
#include <string>
#include <vector>

#include "src/core/depth_key.hpp"
#include "src/core/renderer.hpp"
#include "src/sampletree/node_cache.hpp"
#include "src/sampletree/node_client.hpp"
#include "src/sampletree/node_link.hpp"
#include "src/sampletree/node_server.hpp"
#include "src/sampletree/paged_draw.hpp"
#include "src/sampletree/sample_tree.hpp"
#include "src/sampletree/store_reader.hpp"
#include "src/sampletree/traversal.hpp"
#include "src/sampletree/tree_shading.hpp"
#include "src/zbuffer/native_raster.hpp"

namespace lzb::sampletree {

struct SampleTreeOptions {
  std::string treePath;  // empty: build the tree in memory from the scene
  double c = 13.8;
  int splat = 1;  // stop at cells of at most splat^2 pixels, drawn as splat x splat splats
  uint32_t leafTriangles = kDefaultLeafTriangles;
  StopDraw stopDraw = StopDraw::kSplat;  // what a stopped node draws
  double cacheMb = 0.0;  // with treePath: > 0 renders out of core with a node cache this big
  int cacheLevels = 1;   // out of core: levels below the stops prefetched (0: none)
  bool nodeServer = false;  // out of core: the last rank serves the nodes to the others
};

class SampleTreeRenderer : public Renderer {
 public:
  // Reads the store (or builds the tree); InputError for a bad store or one built from another
  // scene.
  SampleTreeRenderer(const Scene& scene, const RenderOptions& options, const SampleTreeOptions& st);
  std::string name() const override { return "sampletree"; }
  std::string decomposition() const override;
  void render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
              FrameStats& stats) override;
  FrameStats setupStats() const override { return setup_; }
  // Each rank shades its pixels from the tree's own triangles (tree_shading.hpp): no scene needed.
  bool colourFromIds() const override { return false; }
  // The tree; out of core its nodes only (no triangles).
  const SampleTree& tree() const { return source_ ? source_->table() : tree_; }
  // Out of core: the node cache (tests wait for its prefetch); null in core.
  NodeCache* cache() { return cache_.get(); }

  // One frame as it passes through the stages.
  struct Frame {
    const Camera* camera = nullptr;
    WorkShare share;  // among the render ranks
    const SampleTree* tree = nullptr;
    Traversal walk;
    std::vector<uint32_t> splats, drawn;  // this rank's nodes: splatted, drawn as triangles
    std::vector<SoupRange> ranges;        // the drawn nodes' triangles
    uint64_t triangles = 0, splatted = 0;
  };

 private:
  // The stages, timed as traverse (the first two), splat, triangles; then shade and approximated.
  void traverseAndDeal(Frame& f) const;
  void prefetchBelow(const Frame& f);
  void splat(Frame& f, Framebuffer& fb);
  void drawTriangles(const Frame& f, Framebuffer& fb, FrameStats& stats);
  void report(const Frame& f, FrameStats& stats);
  void openStore();
  void openNodeServer();
  uint64_t cacheBudget() const;
  void checkBudget();
  void serveFrame(FrameStats& stats);
  void reportCache(FrameStats& stats);

  const Scene& scene_;
  RenderOptions options_;
  SampleTreeOptions st_;
  SampleTree tree_;  // in core
  uint64_t treeTriangles_ = 0, treeBytes_ = 0;
  std::unique_ptr<StoreReader> store_;  // out of core
  std::unique_ptr<NodeLink> link_;      // with a node server: every rank
  std::unique_ptr<NodeServer> server_;  // the serving rank
  std::unique_ptr<NodeClient> client_;  // the render ranks
  const NodeSource* source_ = nullptr;  // out of core: the one of the above with the node table
  std::unique_ptr<NodeCache> cache_;    // after the sources: it stops before they close
  SoupStaging staging_;
  TreeShading shading_;
  FrameStats setup_;
  NativeRasterizer raster_;
  KeyBuffer keys_;
};

}  // namespace lzb::sampletree
