#pragma once
// Accuracy of a rendered frame against a reference (normally the exact ray caster).
//
// Correct pixel (the papers' definition: the pixel shows a triangle visible in that pixel).
// The reference samples only pixel centres, so a triangle visible somewhere in a pixel may be
// missing from the reference at that pixel but shows at a neighbouring centre. Hence:
//   a pixel is correct when its ID equals the reference ID at the same pixel or at one of its
//   8 neighbours (only existing neighbours at the image border); an empty test pixel is
//   correct when the reference pixel or one of its neighbours is empty.
// Both cases read "the test ID (kNoId included) occurs in the reference's 3x3 window".
// exactIdRate is the strict per-pixel version (both empty counts as equal).
// RMSE is over R, G, B in [0, 255] units, all pixels, alpha ignored; PSNR = 20 log10(255/RMSE),
// +inf for identical colours.
#include <cstddef>
#include <nlohmann/json.hpp>

#include "src/core/framebuffer.hpp"

namespace lzb {

struct Accuracy {
  double correctPixelRate = 0.0;  // correctPixels / pixels
  double exactIdRate = 0.0;       // exactPixels / pixels
  double psnr = 0.0;              // dB; +inf when rmse == 0
  double rmse = 0.0;              // RGB, [0, 255] units
  size_t pixels = 0;
  size_t correctPixels = 0;    // neighbour rule above
  size_t exactPixels = 0;      // same ID as the reference pixel
  size_t missingPixels = 0;    // test empty where the reference pixel is covered (holes)
  size_t extraPixels = 0;      // test covered where the reference pixel is empty
  size_t coveredMismatch = 0;  // both covered, not correct under the neighbour rule
};

// Compares `test` with `reference`. Throws InputError when their sizes differ or are empty.
Accuracy compare(const Framebuffer& test, const Framebuffer& reference);

// JSON object with snake_case keys (correct_pixel_rate, exact_id_rate, psnr, rmse, pixels,
// correct_pixels, exact_pixels, missing_pixels, extra_pixels, covered_mismatch).
// JSON has no infinity: an infinite PSNR (identical colours) is written as null, never as a
// sentinel number that a plot or an average could mistake for a measurement.
nlohmann::json toJson(const Accuracy& a);

}  // namespace lzb
