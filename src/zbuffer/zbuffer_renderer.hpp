#pragma once
// --method zbuffer: the exact conventional z-buffer through OSMesa (Mesa llvmpipe), the reference
// the other methods are measured against.
//
// Per frame: walk the scene graph in expanded-ID order with hierarchical frustum culling and draw
// each visible part of a node mesh with a TriangleRasterizer (one pass: begin, drawRange per draw
// call, end), then shade from the IDs with lzb::shadeFromIds.
#include <string>

#include "src/core/renderer.hpp"
#include "src/zbuffer/draw_walk.hpp"
#include "src/zbuffer/triangle_rasterizer.hpp"

namespace lzb {

class ZBufferRenderer : public Renderer {
 public:
  // Creates the GL context. options.threads reaches llvmpipe through LP_NUM_THREADS, which
  // lzb::useThreads has set; scene must be finalized and outlive the renderer.
  ZBufferRenderer(const Scene& scene, const RenderOptions& options);

  std::string name() const override { return "zbuffer"; }
  std::string decomposition() const override;
  // Renders from the calling thread (the context is made current there).
  void render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
              FrameStats& stats) override;
  // The GL version and renderer in use, for the report.
  const std::string& glDescription() const { return rasterizer_.description(); }

 private:
  const Scene& scene_;
  DrawWalk walk_;
  TriangleRasterizer rasterizer_;
};

}  // namespace lzb
