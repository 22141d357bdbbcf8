#include "src/sqrt5/sqrt5_params.hpp"

#include <algorithm>
#include <cmath>

#include "src/core/error.hpp"
#include "src/core/system.hpp"

namespace lzb::sqrt5 {

// Smaller samples than 1/64 pixel only multiply the work; larger than 64 pixels splats of 12 x 12
// pixels and more, beyond any use.
constexpr double kMinAmin = 1.0 / 64.0, kMaxAmin = 64.0;

int Sqrt5Params::splat() const {
  return std::max(1, int(std::ceil(std::sqrt(2.0 * amin) - 1e-9)));
}

void Sqrt5Params::validate() const {
  require(std::isfinite(amin) && amin >= kMinAmin && amin <= kMaxAmin, "--amin",
          "must be a sample area in [1/64, 64] pixels");
  require(levels >= 0 && levels <= kMaxLevels, "--sqrt5-levels",
          "must be in [0, " + std::to_string(kMaxLevels) + "]");
}

nlohmann::json Sqrt5Params::toJson() const {
  return {{"amin", amin}, {"sqrt5_levels", levels}, {"splat", splat()},
          {"horizon", horizon ? "on" : "off"}, {"sqrt5_cache_mb", cacheMb}};
}

Sqrt5Params parseSqrt5Options(const Sqrt5OptionText& t) {
  Sqrt5Params p;
  p.amin = parseNumber(t.amin, "--amin", "a sample area in [1/64, 64] pixels");
  require(t.horizon == "on" || t.horizon == "off", "--horizon",
          "expected on or off, got '" + t.horizon + "'");
  p.horizon = t.horizon == "on";
  p.levels = t.levels;
  require(t.cacheMb >= 0.0 && t.cacheMb <= double(uint64_t(1) << 30) && t.cacheMb == std::floor(t.cacheMb),
          "--sqrt5-cache-mb", "must be 0 (no cache) or a budget in MiB up to 2^30");
  p.cacheMb = uint64_t(t.cacheMb);
  if (p.cacheMb > 0) requireMemory(p.cacheMb << 20, "--sqrt5-cache-mb", "a forest cache");
  p.validate();
  return p;
}

}  // namespace lzb::sqrt5
