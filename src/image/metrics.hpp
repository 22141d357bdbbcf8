#pragma once
// Accuracy of a rendered frame against an exact reference (reference.hpp), as the papers define it:
// a pixel is correct when it shows a triangle visible somewhere in that pixel. The reference
// knows a pixel's visible triangles from 17 samples: its centre and a 4 x 4 grid of sub-samples;
// a visibility witness (witness.hpp), when given, settles the covered pixels those miss.
//
//   correct   the test ID (kNoId included) is one of the pixel's 17 reference IDs; an empty
//             test pixel is correct when at least one reference sample of the pixel is empty;
//             or (with a witness) the test shows a triangle the witness proves visible inside
//             the pixel ("witnessed"). Holes cannot be witnessed: they show nothing.
//   covered   the test pixel or any reference sample of the pixel shows geometry.
//   missing   test empty where every reference sample shows geometry (a hole);
//   extra     test shows geometry where no reference sample does, not witnessed;
//   wrong     both covered, the test ID not among the 17, not witnessed;
//             missing + extra + wrong = covered - correct covered.
//   exact     the test ID equals the reference centre ID (counted over covered pixels).
// A pixel counted correct is correct by the definition. Without a witness, pixels showing
// triangles much smaller than the samples' quarter-pixel spacing are mostly scored wrong and the
// rates are lower bounds (README.md); the ray witness proves most of them.
// Rates over covered pixels are 1 when no pixel is covered (nothing could be wrong; the count
// coveredPixels = 0 says so). RMSE is over R, G, B in [0, 255] units, all pixels, alpha ignored,
// of the test colour against the box-filtered reference colour (antialiased: "aa");
// PSNR = 20 log10(255 / RMSE), +inf for identical colours.
#include <cstddef>
#include <string>
#include <nlohmann/json.hpp>

#include "src/core/framebuffer.hpp"
#include "src/image/reference.hpp"
#include "src/image/witness.hpp"

namespace lzb {

struct Accuracy {
  double correctRateCovered = 0.0;  // correctCoveredPixels / coveredPixels
  double correctRateAll = 0.0;      // correctPixels / pixels
  double exactIdRateCovered = 0.0;  // exactCoveredPixels / coveredPixels
  double psnrAa = 0.0;              // dB; +inf when rmseAa == 0
  double rmseAa = 0.0;              // RGB, [0, 255] units, against the box-filtered colour
  size_t pixels = 0;
  size_t coveredPixels = 0;
  size_t correctPixels = 0;         // over all pixels
  size_t correctCoveredPixels = 0;
  size_t exactCoveredPixels = 0;
  size_t missingPixels = 0;
  size_t extraPixels = 0;
  size_t wrongPixels = 0;
  size_t witnessedPixels = 0;       // correct covered pixels proven by the witness, not the 17
  std::string witness = "none";     // the witness's rule (VisibilityWitness::name()), or "none"
  int referenceSamplesPerPixel = kReferenceSamplesPerPixel;
};

// Compares `test` with `reference`; `witness` (made for this frame's camera) settles covered test
// pixels whose triangle is not among the 17. Throws InputError when the sizes differ or are empty.
Accuracy compare(const Framebuffer& test, const ReferenceFrame& reference,
                 const VisibilityWitness* witness = nullptr);

// JSON object with snake_case keys: correct_rate_covered, correct_rate_all,
// exact_id_rate_covered, psnr_aa, rmse_aa, pixels, covered_pixels, correct_pixels,
// correct_covered_pixels, exact_covered_pixels, missing_pixels, extra_pixels, wrong_pixels,
// witnessed_pixels, witness, reference_samples_per_pixel.
// JSON has no infinity: an infinite PSNR (identical colours) is written as null, never as a
// sentinel number that a plot or an average could mistake for a measurement.
nlohmann::json toJson(const Accuracy& a);

}  // namespace lzb
