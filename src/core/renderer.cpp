#include "src/core/renderer.hpp"

#include <stdexcept>

namespace lzb {

void requireFrameSize(const Framebuffer& fb, const Camera& camera, const std::string& renderer) {
  if (fb.width != camera.width() || fb.height != camera.height())
    throw std::invalid_argument(renderer + ": framebuffer and camera sizes differ");
}

}  // namespace lzb
