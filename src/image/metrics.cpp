#include "src/image/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "src/core/error.hpp"

namespace lzb {
namespace {

std::string sizeText(const Framebuffer& fb) {
  return std::to_string(fb.width) + "x" + std::to_string(fb.height);
}

// True when `id` occurs in the reference's 3x3 window around (x, y), clipped to the image.
bool inNeighbourhood(const Framebuffer& ref, int x, int y, uint64_t id) {
  const int x0 = std::max(x - 1, 0), x1 = std::min(x + 1, ref.width - 1);
  const int y0 = std::max(y - 1, 0), y1 = std::min(y + 1, ref.height - 1);
  for (int v = y0; v <= y1; ++v)
    for (int u = x0; u <= x1; ++u)
      if (ref.id[ref.index(u, v)] == id) return true;
  return false;
}

}  // namespace

Accuracy compare(const Framebuffer& test, const Framebuffer& reference) {
  if (test.width != reference.width || test.height != reference.height)
    throw InputError("compare: image sizes differ (" + sizeText(test) + " vs reference " +
                     sizeText(reference) + ")");
  if (test.size() == 0) throw InputError("compare: empty images");

  Accuracy a;
  a.pixels = test.size();
  size_t correct = 0, exact = 0, missing = 0, extra = 0, mismatch = 0;
  double squared = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : correct, exact, missing, extra, mismatch, squared)
  for (int y = 0; y < test.height; ++y) {
    for (int x = 0; x < test.width; ++x) {
      const size_t i = test.index(x, y);
      const uint64_t id = test.id[i], refId = reference.id[i];
      const bool ok = id == refId || inNeighbourhood(reference, x, y, id);
      correct += ok;
      exact += id == refId;
      missing += id == kNoId && refId != kNoId;
      extra += id != kNoId && refId == kNoId;
      mismatch += !ok && id != kNoId && refId != kNoId;
      for (int k = 0; k < 3; ++k) {
        const double d = double(channel(test.color[i], k)) - double(channel(reference.color[i], k));
        squared += d * d;
      }
    }
  }
  a.correctPixels = correct;
  a.exactPixels = exact;
  a.missingPixels = missing;
  a.extraPixels = extra;
  a.coveredMismatch = mismatch;
  a.correctPixelRate = double(correct) / double(a.pixels);
  a.exactIdRate = double(exact) / double(a.pixels);
  a.rmse = std::sqrt(squared / (3.0 * double(a.pixels)));
  a.psnr =
      a.rmse > 0.0 ? 20.0 * std::log10(255.0 / a.rmse) : std::numeric_limits<double>::infinity();
  return a;
}

nlohmann::json toJson(const Accuracy& a) {
  nlohmann::json j;
  j["correct_pixel_rate"] = a.correctPixelRate;
  j["exact_id_rate"] = a.exactIdRate;
  j["psnr"] = std::isfinite(a.psnr) ? nlohmann::json(a.psnr) : nlohmann::json(nullptr);
  j["rmse"] = a.rmse;
  j["pixels"] = a.pixels;
  j["correct_pixels"] = a.correctPixels;
  j["exact_pixels"] = a.exactPixels;
  j["missing_pixels"] = a.missingPixels;
  j["extra_pixels"] = a.extraPixels;
  j["covered_mismatch"] = a.coveredMismatch;
  return j;
}

}  // namespace lzb
