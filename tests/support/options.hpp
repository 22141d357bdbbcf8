#pragma once
// The tests' render options: one builder for every method, quiet (no progress lines).
#include <cstdint>
#include <string>

#include "raycast/lzb/lzb_options.hpp"
#include "src/core/renderer.hpp"

namespace lzb::test {

inline RenderOptions renderOptions(const std::string& method, int threads,
                                   uint64_t seed = RenderOptions{}.seed) {
  RenderOptions o;
  o.method = method;
  o.threads = threads;
  o.seed = seed;
  o.quiet = true;
  return o;
}

// Local z-buffering's options at one stage, the rest at their defaults.
inline localz::LzbOptions lzbStageOptions(localz::LzbStage stage) {
  localz::LzbOptions o;
  o.stage = stage;
  return o;
}

}  // namespace lzb::test
