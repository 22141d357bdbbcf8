#pragma once
// The off-screen render target: a GL_RG32UI colour attachment holding 64-bit triangle IDs as
// (low, high) words and a GL_DEPTH_COMPONENT32F depth attachment. Needs a current context.
#include <cstdint>
#include <vector>

namespace lzb::gl {

class IdDepthTarget {
 public:
  IdDepthTarget() = default;
  ~IdDepthTarget();
  IdDepthTarget(const IdDepthTarget&) = delete;
  IdDepthTarget& operator=(const IdDepthTarget&) = delete;

  // (Re)allocates the attachments when the size changes, binds the FBO and sets the viewport.
  void bind(int width, int height);
  // IDs to all ones (kNoId), depth to 1.
  void clear();
  // Bottom-up rows as GL stores them: depth as written, ids as (low, high) pairs.
  void read(std::vector<float>& depth, std::vector<uint32_t>& ids);

 private:
  void release();
  unsigned fbo_ = 0, idBuffer_ = 0, depthBuffer_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace lzb::gl
