#include "src/rzb/rzb_params.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "src/core/error.hpp"
#include "src/rzb/sample_cache.hpp"
#include "src/splat/splatter.hpp"

namespace lzb::rzb {

namespace {

// 1e+300, not 300 digits.
std::string shortNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

void RzbParams::validate() const {
  require(autoEps || (std::isfinite(eps) && eps > 1.0 && eps <= 1000.0), "--eps",
          "must be > 1 (and at most 1000) or 'auto', got " + shortNumber(eps));
  require(std::isfinite(oversample) && oversample > 0.0 && oversample <= 1000.0, "--oversample",
          "must be in (0, 1000], got " + shortNumber(oversample));
  validateSplat(splat);
  require(!(reconstruct == Reconstruct::kPixel && splat > 1), "--reconstruct",
          "'pixel' draws single pixels; use --reconstruct splat with --splat " +
              std::to_string(splat));
  require(!fallback || (std::isfinite(fallbackPx) && fallbackPx >= 0.0), "--fallback",
          "must be 'auto', 'off' or a projected triangle area in pixels > 0");
  require(areaRatio >= 2.0 && areaRatio <= 64.0, "--area-ratio",
          "must be in [2, 64], got " + shortNumber(areaRatio));
  require(std::isfinite(cacheMb) && cacheMb >= 0.0 && cacheMb <= kMaxCacheMb, "--cache-mb",
          "must be 0 (no cache) or a budget in MiB up to 2^40, got " + shortNumber(cacheMb));
  require(std::isfinite(gaussFactor) && gaussFactor >= 1.0, "gauss factor", "must be >= 1");
}

double RzbParams::samplesPerPixel(double pixels) const {
  const double factor = reconstruct == Reconstruct::kGauss ? gaussFactor : 1.0;
  return oversample * std::log(pixels) * factor / (double(splat) * double(splat));
}

double RzbParams::fallbackThreshold(double pixels) const {
  if (!fallback) return std::numeric_limits<double>::infinity();
  if (fallbackPx > 0.0) return fallbackPx;
  return double(splat) * double(splat) / std::log(pixels);
}

uint64_t RzbParams::cacheBytes() const { return uint64_t(cacheMb * 1024.0 * 1024.0); }

uint64_t RzbParams::minCacheBytes(int width, int height, int splat) {
  // A box covering the image holds at least one quantized sample per splat.
  const uint64_t splats = (uint64_t(width) + uint64_t(splat) - 1) / uint64_t(splat) *
                          ((uint64_t(height) + uint64_t(splat) - 1) / uint64_t(splat));
  return splats * sizeof(CachedSample);
}

std::string reconstructName(Reconstruct r) {
  switch (r) {
    case Reconstruct::kPixel:
      return "pixel";
    case Reconstruct::kSplat:
      return "splat";
    case Reconstruct::kGauss:
      return "gauss";
  }
  return "?";
}

std::string fallbackRenderName(FallbackRender r) {
  return r == FallbackRender::kNative ? "native" : "gl";
}

nlohmann::json RzbParams::toJson() const {
  return {{"eps", autoEps ? nlohmann::json("auto") : nlohmann::json(eps)},
          {"oversample", oversample},
          {"splat", splat},
          {"reconstruct", reconstructName(reconstruct)},
          {"fallback", !fallback ? nlohmann::json("off")
                                 : fallbackPx > 0.0 ? nlohmann::json(fallbackPx)
                                                    : nlohmann::json("auto")},
          {"fallback_render", fallbackRenderName(fallbackRender)},
          {"area_ratio", areaRatio},
          {"cache_mb", cacheMb},
          {"backfaces", dropBackfaces ? "drop" : "keep"},
          {"gauss_factor", gaussFactor}};
}

}  // namespace lzb::rzb
