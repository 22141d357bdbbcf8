#pragma once
// `lzb render --method lzb`: the local z-buffering method's options, validation, report
// parameters and factory (see src/cli/method_plugin.hpp).
#include "src/cli/method_plugin.hpp"

namespace lzb {

MethodPlugin lzbMethod();

}  // namespace lzb
