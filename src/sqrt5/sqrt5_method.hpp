#pragma once
// --method sqrt5 (the method contract of src/core/method.hpp): sqrt(5) sampling of procedural
// objects and Halton sampling of meshes (Stamminger & Drettakis); options --amin, --sqrt5-levels,
// --horizon and --sqrt5-cache-mb.
#include <memory>

#include "src/core/method.hpp"

namespace lzb {

std::unique_ptr<Method> makeSqrt5Method();

}  // namespace lzb
