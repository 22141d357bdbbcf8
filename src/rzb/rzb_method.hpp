#pragma once
// --method rzb on `lzb render`: its options (--eps, --oversample, --splat, --fallback,
// --reconstruct, --area-ratio, --cache-mb, --backfaces), their validation and report record.
#include "src/cli/method_plugin.hpp"
#include "src/rzb/rzb_params.hpp"

namespace lzb {

MethodPlugin rzbMethod();

namespace rzb {
// Parses the option strings as the CLI gives them (tests use this too); throws InputError.
RzbParams parseRzbOptions(const std::string& eps, double oversample, int splat,
                          const std::string& fallback, const std::string& reconstruct,
                          double areaRatio, double cacheMb, const std::string& backfaces);
}  // namespace rzb

}  // namespace lzb
