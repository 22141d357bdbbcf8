#include "src/zbuffer/zbuffer_method.hpp"

#include "src/zbuffer/zbuffer_renderer.hpp"

namespace lzb {

std::unique_ptr<Method> makeZBufferMethod() {
  return std::make_unique<PlainMethod<ZBufferRenderer>>(
      "zbuffer", "exact: conventional z-buffer through OSMesa", /*exact=*/true);
}

}  // namespace lzb
