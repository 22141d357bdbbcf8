#pragma once
// --method zbuffer: the exact OSMesa z-buffer (zbuffer_renderer.hpp); no options of its own.
#include <memory>

#include "src/core/method.hpp"

namespace lzb {

std::unique_ptr<Method> makeZBufferMethod();

}  // namespace lzb
