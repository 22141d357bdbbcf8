#include "src/zbuffer/id_depth_target.hpp"

#include <stdexcept>

#include "src/zbuffer/gl_api.hpp"

namespace lzb::gl {

IdDepthTarget::~IdDepthTarget() {
  release();
}

void IdDepthTarget::release() {
  const Api& g = api();
  if (fbo_) g.DeleteFramebuffers(1, &fbo_);
  if (idBuffer_) g.DeleteRenderbuffers(1, &idBuffer_);
  if (depthBuffer_) g.DeleteRenderbuffers(1, &depthBuffer_);
  fbo_ = idBuffer_ = depthBuffer_ = 0;
  width_ = height_ = 0;
}

void IdDepthTarget::bind(int width, int height) {
  const Api& g = api();
  if (width != width_ || height != height_) {
    release();
    g.GenFramebuffers(1, &fbo_);
    g.GenRenderbuffers(1, &idBuffer_);
    g.GenRenderbuffers(1, &depthBuffer_);
    g.BindRenderbuffer(GL_RENDERBUFFER, idBuffer_);
    g.RenderbufferStorage(GL_RENDERBUFFER, GL_RG32UI, width, height);
    g.BindRenderbuffer(GL_RENDERBUFFER, depthBuffer_);
    g.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, width, height);
    g.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
    g.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, idBuffer_);
    g.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthBuffer_);
    const GLenum status = g.CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("z-buffer framebuffer incomplete (" + std::to_string(width) + "x" +
                               std::to_string(height) + ", status " + std::to_string(status) + ")");
    check("allocating the z-buffer framebuffer");
    width_ = width;
    height_ = height;
  }
  g.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  const GLenum drawBuffer = GL_COLOR_ATTACHMENT0;
  g.DrawBuffers(1, &drawBuffer);
  g.ReadBuffer(GL_COLOR_ATTACHMENT0);
  g.Viewport(0, 0, width, height);
}

void IdDepthTarget::clear() {
  const Api& g = api();
  const GLuint noId[4] = {~0u, ~0u, 0u, 0u};
  const GLfloat far = 1.0f;
  g.DepthMask(GL_TRUE);
  g.ClearBufferuiv(GL_COLOR, 0, noId);
  g.ClearBufferfv(GL_DEPTH, 0, &far);
}

void IdDepthTarget::read(std::vector<float>& depth, std::vector<uint32_t>& ids) {
  const Api& g = api();
  const size_t n = size_t(width_) * size_t(height_);
  depth.resize(n);
  ids.resize(2 * n);
  g.PixelStorei(GL_PACK_ALIGNMENT, 4);
  g.ReadPixels(0, 0, width_, height_, GL_RG_INTEGER, GL_UNSIGNED_INT, ids.data());
  g.ReadPixels(0, 0, width_, height_, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  check("reading back the z-buffer");
}

}  // namespace lzb::gl
