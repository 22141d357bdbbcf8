#pragma once
// Parameters of --method rzb (src/rzb/README.md documents them and their defaults).
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace lzb::rzb {

enum class Reconstruct { kPixel, kSplat, kGauss };
// Which exact z-buffer draws the fallback's triangles: the native one (multithreaded) or OSMesa.
enum class FallbackRender { kNative, kGl };

// The largest --cache-mb (1 EiB): its byte count fits an integer exactly.
constexpr double kMaxCacheMb = 1099511627776.0;

struct RzbParams {
  double eps = 1.5;            // depth accuracy: select a box when (zmax / zmin)^2 <= eps
  bool autoEps = false;        // search eps per frame for the least modelled cost (section 8.2)
  double oversample = 1.0;     // scales the ln v oversampling
  int splat = 1;               // d: samples are d x d splats, and d^2 fewer are drawn
  Reconstruct reconstruct = Reconstruct::kPixel;
  bool fallback = true;        // z-buffer fallback for boxes of large triangles (section 7.1)
  double fallbackPx = 0.0;     // projected triangle area (pixels) above which; 0: d^2 / ln v
  FallbackRender fallbackRender = FallbackRender::kNative;  // faster than OSMesa (README)
  double areaRatio = 4.0;      // area class width (2..64)
  double cacheMb = 0.0;        // sample cache budget (MiB); 0: no cache
  bool dropBackfaces = true;   // drop samples on triangles facing away from the eye
  double gaussFactor = 10.0;   // gauss reconstruction draws this many times more samples

  // Throws InputError naming the option for out-of-range values.
  void validate() const;
  // Samples per pixel of projected area for an image of `pixels` pixels.
  double samplesPerPixel(double pixels) const;
  // The fallback threshold in pixels of projected triangle area (+inf when off).
  double fallbackThreshold(double pixels) const;
  // The cache budget in bytes (validated: no overflow).
  uint64_t cacheBytes() const;
  // The smallest cache budget that holds one box covering the image once (bytes).
  static uint64_t minCacheBytes(int width, int height, int splat);
  nlohmann::json toJson() const;
};

std::string reconstructName(Reconstruct r);
std::string fallbackRenderName(FallbackRender r);

}  // namespace lzb::rzb
