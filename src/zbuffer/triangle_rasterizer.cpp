#include "src/zbuffer/triangle_rasterizer.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "src/core/timer.hpp"
#include "src/zbuffer/depth_mapping.hpp"
#include "src/zbuffer/gl_api.hpp"
#include "src/zbuffer/id_depth_target.hpp"
#include "src/zbuffer/id_program.hpp"
#include "src/zbuffer/list_indices.hpp"
#include "src/zbuffer/mesh_buffers.hpp"
#include "src/zbuffer/osmesa_context.hpp"

namespace lzb {

namespace {

// The largest float <= depth: a float fragment depth d is <= it exactly when d <= depth.
float floatAtMost(double depth) {
  float f = float(depth);
  if (double(f) > depth) f = std::nextafter(f, 0.0f);
  return f;
}

}  // namespace

struct TriangleRasterizer::Impl {
  const Scene& scene;
  // Declared first so it is destroyed last: every GL object below needs it.
  std::unique_ptr<gl::OsMesaContext> context;
  std::string description;
  std::unique_ptr<gl::IdProgram> program;
  std::unique_ptr<gl::IdDepthTarget> target;
  std::unique_ptr<gl::ListIndices> listIndices;
  std::vector<std::unique_ptr<gl::MeshBuffers>> meshes;  // per node, uploaded on first draw
  unsigned vertexArray = 0;

  // The pass set begun last.
  bool drawing = false;
  glm::dmat4 view{1.0};
  double farPlane = 0.0;
  float depthScale = 1.0f;
  int width = 0, height = 0;
  std::vector<float> depthScratch;
  std::vector<uint32_t> idScratch;

  explicit Impl(const Scene& s) : scene(s) {
    context = std::make_unique<gl::OsMesaContext>();
    description = context->description();
    program = std::make_unique<gl::IdProgram>();
    target = std::make_unique<gl::IdDepthTarget>();
    listIndices = std::make_unique<gl::ListIndices>();
    meshes.resize(scene.nodes.size());
    const gl::Api& g = gl::api();
    g.GenVertexArrays(1, &vertexArray);
    g.BindVertexArray(vertexArray);
    g.EnableVertexAttribArray(0);
    // Exact IDs and depths: no dithering, blending, face culling or multisampling.
    g.Disable(GL_DITHER);
    g.Disable(GL_BLEND);
    g.Disable(GL_CULL_FACE);
    g.Disable(GL_MULTISAMPLE);
    g.Disable(GL_DEPTH_CLAMP);
    g.ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    g.Enable(GL_DEPTH_TEST);
    // Strict: on equal depths the first drawn stays (the smaller ID in ascending draws).
    g.DepthFunc(GL_LESS);
    gl::check("setting up the z-buffer");
  }

  ~Impl() {
    // GL objects go while their context is current, and before it.
    try {
      context->makeCurrent();
    } catch (...) {
      return;  // nothing can be released without the context; the process is going down anyway
    }
    meshes.clear();
    if (vertexArray) gl::api().DeleteVertexArrays(1, &vertexArray);
    listIndices.reset();
    target.reset();
    program.reset();
    context.reset();
  }

  // Inside a pass set, with this context current (another rasterizer may have taken the thread).
  void require(const char* what) const {
    if (!drawing)
      throw std::logic_error(std::string("TriangleRasterizer::") + what +
                             " outside begin() ... end()");
    context->makeCurrent();
  }

  const gl::MeshBuffers& mesh(uint32_t node, RasterCounts& counts) {
    if (node >= meshes.size())
      throw std::out_of_range("TriangleRasterizer: node " + std::to_string(node) + " of " +
                              std::to_string(meshes.size()));
    auto& m = meshes[node];
    if (!m) {
      Stopwatch upload;
      auto fresh = std::make_unique<gl::MeshBuffers>();
      fresh->upload(scene.nodes[node].mesh);  // kept only once complete
      m = std::move(fresh);
      counts.uploadSeconds += upload.seconds();
    }
    return *m;
  }

  // The shader's far clip for a requested one (validated; 0 or beyond the camera's far: none).
  float clipDepth(double farClip) const {
    if (!(farClip >= 0.0))
      throw std::invalid_argument("TriangleRasterizer: far clip " + std::to_string(farClip));
    if (farClip == 0.0 || farClip >= farPlane) return std::numeric_limits<float>::infinity();
    return floatAtMost(farClip);
  }

  void setModelView(const glm::dmat4& world) const {
    // Camera-relative: the double product cancels large translations before rounding to float.
    program->setModelView(glm::mat4(view * world));
  }
};

TriangleRasterizer::TriangleRasterizer(const Scene& scene) : impl_(std::make_unique<Impl>(scene)) {}

TriangleRasterizer::~TriangleRasterizer() = default;

const std::string& TriangleRasterizer::description() const {
  return impl_->description;
}

void TriangleRasterizer::begin(const Camera& camera, double farClip) {
  Impl& r = *impl_;
  r.drawing = false;
  r.farPlane = camera.farPlane();
  const float clip = r.clipDepth(farClip);
  r.context->makeCurrent();
  counts_ = {};
  r.width = camera.width();
  r.height = camera.height();
  r.target->bind(r.width, r.height);
  r.target->clear();
  r.program->use();
  r.program->setProjection(glm::mat4(reversedZProjection(camera)));
  r.depthScale = depthStorageScale(r.farPlane);
  r.program->setDepthScale(r.depthScale);
  r.view = camera.view();
  gl::api().BindVertexArray(r.vertexArray);
  // Per fragment (see IdProgram): a triangle keeps its rasterization and depths bit for bit, so
  // clipped and unclipped passes composite like one pass. The camera's far plane clips anyway.
  r.program->setFarClip(clip);
  r.drawing = true;
}

void TriangleRasterizer::setFarClip(double farClip) {
  Impl& r = *impl_;
  r.require("setFarClip");
  r.program->setFarClip(r.clipDepth(farClip));
}

void TriangleRasterizer::drawRange(uint32_t node, const glm::dmat4& world, uint64_t first,
                                   uint64_t count, uint64_t firstId) {
  Impl& r = *impl_;
  r.require("drawRange");
  const gl::MeshBuffers& mesh = r.mesh(node, counts_);
  if (first > mesh.triangles() || count > mesh.triangles() - first)
    throw std::out_of_range("TriangleRasterizer::drawRange: triangles [" + std::to_string(first) +
                            ", +" + std::to_string(count) + ") of a mesh of " +
                            std::to_string(mesh.triangles()));
  if (count == 0) return;
  r.setModelView(world);
  counts_.drawCalls += uint64_t(mesh.draw(*r.program, first, count, firstId));
  counts_.triangles += count;
}

void TriangleRasterizer::drawList(uint32_t node, const glm::dmat4& world,
                                  std::span<const uint32_t> triangles, uint64_t idBase) {
  Impl& r = *impl_;
  r.require("drawList");
  const gl::MeshBuffers& mesh = r.mesh(node, counts_);
  if (triangles.empty()) return;
  r.setModelView(world);
  counts_.drawCalls += uint64_t(mesh.drawList(*r.program, triangles, idBase, *r.listIndices));
  counts_.triangles += triangles.size();
}

void TriangleRasterizer::flush() {
  impl_->require("flush");
  gl::api().Flush();
}

void TriangleRasterizer::end(Framebuffer& fb) {
  Impl& r = *impl_;
  r.require("end");
  r.drawing = false;
  readInto(fb);
}

void TriangleRasterizer::read(Framebuffer& fb) {
  impl_->require("read");
  readInto(fb);
}

void TriangleRasterizer::readInto(Framebuffer& fb) {
  Impl& r = *impl_;
  gl::api().Finish();
  gl::check("drawing the z-buffer");
  Stopwatch readback;
  r.target->read(r.depthScratch, r.idScratch);
  if (fb.width != r.width || fb.height != r.height) fb.resize(r.width, r.height);
  // GL rows go bottom-up; depth back to view depth by the exact inverse of the storage scale.
  const float unscale = 1.0f / r.depthScale;
  const int w = r.width, h = r.height;
  const std::vector<float>& depth = r.depthScratch;
  const std::vector<uint32_t>& ids = r.idScratch;
#pragma omp parallel for schedule(static)
  for (int y = 0; y < h; ++y) {
    const size_t src = size_t(h - 1 - y) * size_t(w);
    for (int x = 0; x < w; ++x) {
      const size_t i = fb.index(x, y), j = src + size_t(x);
      const uint64_t id = uint64_t(ids[2 * j]) | uint64_t(ids[2 * j + 1]) << 32;
      fb.id[i] = id;
      fb.depth[i] = id == kNoId ? kEmptyDepth : depth[j] * unscale;
    }
  }
  counts_.readbackSeconds += readback.seconds();
}

}  // namespace lzb
