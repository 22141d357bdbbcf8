#pragma once
// --method hybrid (the method contract of src/core/method.hpp): options, validation, report
// parameters and factory. It shares --splat, --oversample, --fallback and --backfaces with rzb
// and --plane with lzb.
#include <memory>

#include "src/core/method.hpp"

namespace lzb {

std::unique_ptr<Method> makeHybridMethod();

}  // namespace lzb
