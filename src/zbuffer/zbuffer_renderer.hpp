#pragma once
// --method zbuffer: the exact conventional z-buffer through OSMesa (Mesa llvmpipe), the reference
// the other methods are measured against.
//
// Per frame: walk the scene graph in expanded-ID order with hierarchical frustum culling, draw each
// visible node mesh (uploaded once as vertex buffers) with a camera-relative modelview composed in
// double, into a 64-bit ID + float32 depth target (see depth_mapping.hpp); read back, flip to
// row 0 = top, and shade from the IDs with lzb::shadeFromIds.
#include <memory>
#include <string>
#include <vector>

#include "src/core/renderer.hpp"
#include "src/zbuffer/draw_walk.hpp"

namespace lzb {

namespace gl {
class OsMesaContext;
class IdProgram;
class IdDepthTarget;
class MeshBuffers;
}  // namespace gl

class ZBufferRenderer : public Renderer {
 public:
  // Creates the GL context. options.threads reaches llvmpipe through LP_NUM_THREADS, which
  // lzb::useThreads has set; scene must be finalized and outlive the renderer.
  ZBufferRenderer(const Scene& scene, const RenderOptions& options);
  ~ZBufferRenderer() override;

  std::string name() const override { return "zbuffer"; }
  std::string decomposition() const override;
  // Renders from the calling thread (the context is made current there).
  void render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
              FrameStats& stats) override;
  // The GL version and renderer in use, for the report.
  const std::string& glDescription() const { return glDescription_; }

 private:
  const Scene& scene_;
  DrawWalk walk_;
  std::unique_ptr<gl::OsMesaContext> context_;
  std::unique_ptr<gl::IdProgram> program_;
  std::unique_ptr<gl::IdDepthTarget> target_;
  std::vector<std::unique_ptr<gl::MeshBuffers>> meshes_;  // per node, uploaded on first draw
  unsigned vertexArray_ = 0;
  std::string glDescription_;
  std::vector<float> depthScratch_;
  std::vector<uint32_t> idScratch_;
};

}  // namespace lzb
