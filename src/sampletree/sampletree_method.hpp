#pragma once
// --method sampletree on `lzb render` (the method contract of src/core/method.hpp): --tree,
// --c, --splat (shared with rzb and the hybrid), --cache-mb (shared with rzb), --cache-levels,
// --leaf-triangles, --stop-draw.
#include <memory>

#include "src/core/method.hpp"

namespace lzb {

std::unique_ptr<Method> makeSampleTreeMethod();

}  // namespace lzb
