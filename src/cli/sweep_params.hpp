#pragma once
// `lzb sweep`'s --param NAME=V1,V2,...: the swept options, their combinations, and a combination
// applied to the render options exactly as `lzb render --NAME V` would parse and validate it.
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "src/cli/render_command.hpp"
#include "src/core/method.hpp"

namespace lzb {

inline constexpr uint64_t kMaxCombinations = 10000;  // more is a typo, not a study

struct SweptParam {
  std::string name;                 // a render option without its dashes: splat, eps, ...
  std::vector<std::string> values;  // as typed
};

struct SweepGrid {
  std::vector<SweptParam> params;
  uint64_t count() const;  // combinations
  // Combination k (0-based): one value per param, the last param varying fastest.
  std::vector<std::string> values(uint64_t k) const;
  std::string label(uint64_t k) const;  // "splat=2 eps=1.5"
};

// Parses each --param text NAME=V1,V2,... (values separated by ';' instead when one holds commas,
// as --surfel-grids lists do); refuses a missing name, an empty list or value, a repeated value
// or name, and more than kMaxCombinations combinations. Throws InputError naming the --param.
SweepGrid parseSweepGrid(const std::vector<std::string>& texts);

// The names --param may sweep with `method`: its own options and the render options that leave
// the frames and their reference alone (threads, seed, composite).
std::vector<std::string> sweepableNames(Method& method);

// Refuses a name `method` does not read, or one `command` (the sweep's own command line) also
// got as a plain option. Throws InputError naming the --param.
void checkSweepNames(const SweepGrid& grid, Method& method, const CLI::App& command);

// `base` with combination k applied (--NAME=VALUE parsed by the render command's own options, so
// method options land in the registered method as for `lzb render`), then validated like
// `lzb render` (the method's validate() included). Throws InputError naming the combination.
RenderArgs applyCombination(const RenderArgs& base, const SweepGrid& grid, uint64_t k);

}  // namespace lzb
