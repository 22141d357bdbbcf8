#pragma once
// --method surfels (the method contract of src/core/method.hpp): its options (--surfelize,
// --surfel-quality, --surfel-grids, --sprite-shape, --surfel-cell, --collisions, --budget-ms,
// --budget-rate, --surfel-build; --splat and --backfaces shared with rzb and the hybrid), their
// validation, report parameters and factory.
#include <memory>

#include "src/core/method.hpp"

namespace lzb {

std::unique_ptr<Method> makeSurfelMethod();

}  // namespace lzb
