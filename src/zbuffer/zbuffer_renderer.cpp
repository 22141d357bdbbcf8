#include "src/zbuffer/zbuffer_renderer.hpp"

#include <stdexcept>

#include "src/core/shading.hpp"
#include "src/core/timer.hpp"
#include "src/zbuffer/depth_mapping.hpp"
#include "src/zbuffer/gl_api.hpp"
#include "src/zbuffer/id_depth_target.hpp"
#include "src/zbuffer/id_program.hpp"
#include "src/zbuffer/mesh_buffers.hpp"
#include "src/zbuffer/osmesa_context.hpp"
#include "src/zbuffer/share_range.hpp"

namespace lzb {

ZBufferRenderer::ZBufferRenderer(const Scene& scene, const RenderOptions& options)
    : scene_(scene), walk_(scene) {
  context_ = std::make_unique<gl::OsMesaContext>();
  glDescription_ = context_->description();
  const gl::Api& g = gl::api();
  program_ = std::make_unique<gl::IdProgram>();
  target_ = std::make_unique<gl::IdDepthTarget>();
  meshes_.resize(scene.nodes.size());
  g.GenVertexArrays(1, &vertexArray_);
  g.BindVertexArray(vertexArray_);
  g.EnableVertexAttribArray(0);
  // Exact IDs and depths: no dithering, blending, face culling or multisampling.
  g.Disable(GL_DITHER);
  g.Disable(GL_BLEND);
  g.Disable(GL_CULL_FACE);
  g.Disable(GL_MULTISAMPLE);
  g.Disable(GL_DEPTH_CLAMP);
  g.ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  g.Enable(GL_DEPTH_TEST);
  // Strict: on equal depths the first drawn, i.e. the smaller ID, stays (as in compositeNearer).
  g.DepthFunc(GL_LESS);
  gl::check("setting up the z-buffer");
}

ZBufferRenderer::~ZBufferRenderer() {
  // GL objects go while their context is current, and before it.
  try {
    context_->makeCurrent();
  } catch (...) {
    return;  // nothing can be released without the context; the process is going down anyway
  }
  meshes_.clear();
  if (vertexArray_) gl::api().DeleteVertexArrays(1, &vertexArray_);
  target_.reset();
  program_.reset();
  context_.reset();
}

std::string ZBufferRenderer::decomposition() const {
  return "sort-last by triangle ID: rank r draws the r-th of equal contiguous ranges of the "
         "expanded triangle-ID order (cutting a draw item where needed) in ascending ID order with "
         "a strict depth test, so compositing by the nearest (depth, ID) reproduces the 1-rank "
         "image exactly";
}

void ZBufferRenderer::render(const Camera& camera, int frame, const WorkShare& share,
                             Framebuffer& fb, FrameStats& stats) {
  if (fb.width != camera.width() || fb.height != camera.height())
    throw std::invalid_argument("zbuffer: framebuffer and camera sizes differ");
  context_->makeCurrent();
  const gl::Api& g = gl::api();
  Stopwatch clock;
  double uploadSeconds = 0.0;

  target_->bind(fb.width, fb.height);
  target_->clear();
  program_->use();
  program_->setProjection(glm::mat4(reversedZProjection(camera)));
  const float depthScale = depthStorageScale(camera.farPlane());
  program_->setDepthScale(depthScale);
  g.BindVertexArray(vertexArray_);

  const glm::dmat4 view = camera.view();
  double drawCalls = 0.0;
  const IdRange range = shareRange(scene_.expandedTriangles(), share);
  const WalkCounts counts = walk_.walk(camera.frustum(), range, [&](const DrawCall& d) {
    auto& mesh = meshes_[d.node];
    if (!mesh) {
      Stopwatch upload;
      mesh = std::make_unique<gl::MeshBuffers>();
      mesh->upload(scene_.nodes[d.node].mesh);
      uploadSeconds += upload.seconds();
    }
    // Camera-relative: the double product cancels large translations before rounding to float.
    program_->setModelView(glm::mat4(view * d.world));
    drawCalls += mesh->draw(*program_, d.first, d.count, d.firstId);
  });
  g.Finish();
  gl::check("drawing the z-buffer");
  const double drawSeconds = clock.lap() - uploadSeconds;

  target_->read(depthScratch_, idScratch_);
  // GL rows go bottom-up; depth back to view depth by the exact inverse of the storage scale.
  const float unscale = 1.0f / depthScale;
  const int w = fb.width, h = fb.height;
#pragma omp parallel for schedule(static)
  for (int y = 0; y < h; ++y) {
    const size_t src = size_t(h - 1 - y) * size_t(w);
    for (int x = 0; x < w; ++x) {
      const size_t i = fb.index(x, y), j = src + size_t(x);
      const uint64_t id = uint64_t(idScratch_[2 * j]) | uint64_t(idScratch_[2 * j + 1]) << 32;
      fb.id[i] = id;
      fb.depth[i] = id == kNoId ? kEmptyDepth : depthScratch_[j] * unscale;
    }
  }
  const double readbackSeconds = clock.lap();

  shadeFromIds(scene_, camera, fb);
  stats.addStage("upload", uploadSeconds);
  stats.addStage("draw", drawSeconds);
  stats.addStage("readback", readbackSeconds);
  stats.addStage("shade", clock.lap());
  stats.addCount("triangles_drawn", double(counts.triangles));
  stats.addCount("draw_items", double(counts.items));
  stats.addCount("draw_items_culled", double(counts.culled));
  stats.addCount("draw_calls", drawCalls);
}

}  // namespace lzb
