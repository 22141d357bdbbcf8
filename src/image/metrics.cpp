#include "src/image/metrics.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "src/core/error.hpp"

namespace lzb {
namespace {

std::string sizeText(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// How one pixel's reference samples relate to a test ID.
struct PixelVerdict {
  bool correct = false;    // the ID is one of the 17
  bool anyCovered = false;  // some reference sample shows geometry
  bool allCovered = true;   // every reference sample shows geometry
};

PixelVerdict judgePixel(const ReferenceFrame& ref, size_t pixel, uint64_t id) {
  PixelVerdict v;
  const uint64_t centre = ref.centreId[pixel];
  v.correct = id == centre;
  v.anyCovered = centre != kNoId;
  v.allCovered = centre != kNoId;
  const uint64_t* sub = ref.subsamples(pixel);
  for (int k = 0; k < kSubsamples; ++k) {
    v.correct |= sub[k] == id;
    v.anyCovered |= sub[k] != kNoId;
    v.allCovered &= sub[k] != kNoId;
  }
  return v;
}

double squaredColourError(Rgba8 test, const std::array<float, 3>& box) {
  double sum = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double d = double(channel(test, c)) - double(box[size_t(c)]);
    sum += d * d;
  }
  return sum;
}

double rateOf(size_t count, size_t total) {
  return total == 0 ? 1.0 : double(count) / double(total);
}

// The counts of one pixel, summed over the frame.
struct PixelCounts {
  size_t covered = 0, correct = 0, correctCovered = 0, exact = 0, missing = 0, extra = 0,
         wrong = 0, witnessed = 0;
};

void countPixel(const ReferenceFrame& ref, const VisibilityWitness* witness, int x, int y,
                size_t i, uint64_t id, PixelCounts& n) {
  const PixelVerdict v = judgePixel(ref, i, id);
  const bool testCovered = id != kNoId;
  // Only a triangle the 17 samples missed needs a witness; a hole shows nothing to witness.
  const bool witnessed =
      witness && testCovered && !v.correct && witness->visibleInPixel(x, y, id);
  const bool correct = v.correct || witnessed;
  const bool isCovered = testCovered || v.anyCovered;
  n.covered += isCovered;
  n.correct += correct;
  n.correctCovered += isCovered && correct;
  n.exact += isCovered && id == ref.centreId[i];
  n.missing += !testCovered && v.allCovered;
  n.extra += testCovered && !v.anyCovered && !witnessed;
  n.wrong += testCovered && v.anyCovered && !correct;
  n.witnessed += witnessed;
}

}  // namespace

Accuracy compare(const Framebuffer& test, const ReferenceFrame& reference,
                 const VisibilityWitness* witness) {
  if (test.width != reference.width || test.height != reference.height)
    throw InputError("compare: image sizes differ (" + sizeText(test.width, test.height) +
                     " vs reference " + sizeText(reference.width, reference.height) + ")");
  if (test.size() == 0) throw InputError("compare: empty images");

  size_t covered = 0, correct = 0, correctCovered = 0, exact = 0, missing = 0, extra = 0,
         wrong = 0, witnessed = 0;
  // Squared errors are multiples of 1/256 (bytes against sixteenths of a byte) and sum to at most
  // 3 * 255^2 * 4096^2 < 2^42: exact in a double, so the threads' order cannot change the sum.
  double squared = 0.0;
  // Rows handed out one by one: witnessed pixels cost rays, and they cluster.
#pragma omp parallel for schedule(dynamic, 1)                                              \
    reduction(+ : covered, correct, correctCovered, exact, missing, extra, wrong, witnessed, \
                  squared)
  for (int y = 0; y < test.height; ++y) {
    PixelCounts n;
    for (int x = 0; x < test.width; ++x) {
      const size_t i = test.index(x, y);
      countPixel(reference, witness, x, y, i, test.id[i], n);
      squared += squaredColourError(test.color[i], reference.boxColor[i]);
    }
    covered += n.covered;
    correct += n.correct;
    correctCovered += n.correctCovered;
    exact += n.exact;
    missing += n.missing;
    extra += n.extra;
    wrong += n.wrong;
    witnessed += n.witnessed;
  }
  Accuracy a;
  a.pixels = test.size();
  a.coveredPixels = covered;
  a.correctPixels = correct;
  a.correctCoveredPixels = correctCovered;
  a.exactCoveredPixels = exact;
  a.missingPixels = missing;
  a.extraPixels = extra;
  a.wrongPixels = wrong;
  a.witnessedPixels = witnessed;
  a.witness = witness ? witness->name() : "none";
  a.correctRateCovered = rateOf(correctCovered, covered);
  a.correctRateAll = rateOf(correct, a.pixels);
  a.exactIdRateCovered = rateOf(exact, covered);
  a.rmseAa = std::sqrt(squared / (3.0 * double(a.pixels)));
  a.psnrAa = a.rmseAa > 0.0 ? 20.0 * std::log10(255.0 / a.rmseAa)
                            : std::numeric_limits<double>::infinity();
  return a;
}

nlohmann::json toJson(const Accuracy& a) {
  nlohmann::json j;
  j["correct_rate_covered"] = a.correctRateCovered;
  j["correct_rate_all"] = a.correctRateAll;
  j["exact_id_rate_covered"] = a.exactIdRateCovered;
  j["psnr_aa"] = std::isfinite(a.psnrAa) ? nlohmann::json(a.psnrAa) : nlohmann::json(nullptr);
  j["rmse_aa"] = a.rmseAa;
  j["pixels"] = a.pixels;
  j["covered_pixels"] = a.coveredPixels;
  j["correct_pixels"] = a.correctPixels;
  j["correct_covered_pixels"] = a.correctCoveredPixels;
  j["exact_covered_pixels"] = a.exactCoveredPixels;
  j["missing_pixels"] = a.missingPixels;
  j["extra_pixels"] = a.extraPixels;
  j["wrong_pixels"] = a.wrongPixels;
  j["witnessed_pixels"] = a.witnessedPixels;
  j["witness"] = a.witness;
  j["reference_samples_per_pixel"] = a.referenceSamplesPerPixel;
  return j;
}

}  // namespace lzb
