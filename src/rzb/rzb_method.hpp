#pragma once
// --method rzb on `lzb render` (the method contract of src/core/method.hpp): its options (--eps, --oversample, --splat, --fallback,
// --fallback-render, --reconstruct, --area-ratio, --cache-mb, --backfaces), their validation and report record.
#include <memory>
#include <string>

#include "src/core/method.hpp"
#include "src/rzb/rzb_params.hpp"

namespace lzb {

std::unique_ptr<Method> makeRzbMethod();

namespace rzb {
// Parses the option strings as the CLI gives them (tests use this too); throws InputError.
RzbParams parseRzbOptions(const std::string& eps, double oversample, int splat,
                          const std::string& fallback, const std::string& reconstruct,
                          double areaRatio, double cacheMb, const std::string& backfaces,
                          const std::string& fallbackRender = "native");
}  // namespace rzb

}  // namespace lzb
