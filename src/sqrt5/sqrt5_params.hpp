#pragma once
// --method sqrt5's parameters: the sample size A'min (pixels) and the refinement depth bound.
#include <nlohmann/json.hpp>
#include <string>

#include "src/sqrt5/lattice.hpp"

namespace lzb::sqrt5 {

struct Sqrt5Params {
  double amin = 0.5;    // --amin: the largest projected sample area, pixels (the paper's A'min)
  int levels = 12;      // --sqrt5-levels: refinement levels below the initial grid at most
  bool horizon = true;  // --horizon on|off: the terrain's horizon culling (section 3.4)
  uint64_t cacheMb = 256;  // --sqrt5-cache-mb: the forest cache's budget per rank (0: none)

  // Splat side d = max(1, ceil(sqrt(2 A'min))): refinement keeps the projected spawning vectors
  // below sqrt(A'min) pixels, so every disc of radius sqrt(A'min / 2) holds a sample, and a
  // d x d splat's inscribed disc (radius d / 2) is at least that: no pixel centre is left
  // between the samples of a surface.
  int splat() const;
  void validate() const;  // throws InputError naming the option
  nlohmann::json toJson() const;
};

struct Sqrt5OptionText {
  std::string amin = "0.5", horizon = "on";
  int levels = 12;
  double cacheMb = 256;
};

// Parses and validates; throws InputError naming the option.
Sqrt5Params parseSqrt5Options(const Sqrt5OptionText& text);

}  // namespace lzb::sqrt5
