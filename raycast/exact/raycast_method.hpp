#pragma once
// --method raycast: exact Embree primary rays (raycast_renderer.hpp); no options of its own.
#include <memory>

#include "src/core/method.hpp"

namespace lzb {

std::unique_ptr<Method> makeRaycastMethod();

}  // namespace lzb
