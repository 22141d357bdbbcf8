#pragma once
// --method lzb: the local z-buffering method's options, validation, report parameters and
// factory (the method contract of src/core/method.hpp).
#include <memory>

#include "src/core/method.hpp"

namespace lzb {

std::unique_ptr<Method> makeLzbMethod();

}  // namespace lzb
