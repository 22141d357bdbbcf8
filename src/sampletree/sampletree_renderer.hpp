#pragma once
// --method sampletree: the randomized sample tree's frame. Every rank traverses the tree alike
// (traversal.hpp); the visited nodes, in preorder, are dealt to ranks as runs of equal cost
// (dealByCost: a node costs its triangles, a splat 1); each rank draws its nodes' triangles with
// the native z-buffer and its splats with the splatting core into one key buffer, so compositing
// the ranks by (depth, ID) gives the 1-rank image for any rank or thread count.
#include <memory>
#include <string>

#include "src/core/depth_key.hpp"
#include "src/core/renderer.hpp"
#include "src/sampletree/sample_tree.hpp"
#include "src/sampletree/traversal.hpp"
#include "src/zbuffer/native_raster.hpp"

namespace lzb::sampletree {

struct SampleTreeOptions {
  std::string treePath;  // empty: build the tree in memory from the scene
  double c = 13.8;
  int splat = 1;  // stop at cells of at most splat^2 pixels, drawn as splat x splat splats
  uint32_t leafTriangles = 32;
  StopDraw stopDraw = StopDraw::kSplat;  // what a stopped node draws
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
  const SampleTree& tree() const { return tree_; }

 private:
  const Scene& scene_;
  RenderOptions options_;
  SampleTreeOptions st_;
  SampleTree tree_;
  FrameStats setup_;
  NativeRasterizer raster_;
  KeyBuffer keys_;
};

}  // namespace lzb::sampletree
