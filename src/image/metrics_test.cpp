#include "src/image/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "src/core/error.hpp"

namespace lzb {
namespace {

// Left half triangle 1 (red), right half triangle 2 (green) from column `edge` on; the bottom
// row is empty.
Framebuffer edgeImage(int edge) {
  Framebuffer fb(16, 12);
  for (int y = 0; y < fb.height - 1; ++y)
    for (int x = 0; x < fb.width; ++x) {
      const size_t i = fb.index(x, y);
      const bool right = x >= edge;
      fb.id[i] = right ? 2 : 1;
      fb.depth[i] = right ? 2.0f : 1.0f;
      fb.color[i] = right ? packRgba8(0, 200, 0) : packRgba8(200, 0, 0);
    }
  return fb;
}

TEST(Metrics, IdenticalImagesArePerfect) {
  const Framebuffer fb = edgeImage(8);
  const Accuracy a = compare(fb, fb);
  EXPECT_EQ(a.pixels, fb.size());
  EXPECT_EQ(a.correctPixelRate, 1.0);
  EXPECT_EQ(a.exactIdRate, 1.0);
  EXPECT_EQ(a.rmse, 0.0);
  EXPECT_TRUE(std::isinf(a.psnr) && a.psnr > 0);
  EXPECT_EQ(a.missingPixels + a.extraPixels + a.coveredMismatch, 0u);
  const nlohmann::json j = toJson(a);
  EXPECT_TRUE(j.at("psnr").is_null());
  EXPECT_EQ(j.at("correct_pixel_rate"), 1.0);
  EXPECT_EQ(j.at("pixels"), fb.size());
  // Round-trips through text: no inf or nan reaches the JSON.
  EXPECT_EQ(nlohmann::json::parse(j.dump()), j);
}

TEST(Metrics, OnePixelShiftStaysCorrectButNotExact) {
  const Framebuffer ref = edgeImage(8);
  const Framebuffer shifted = edgeImage(9);    // one column of pixels changes ID
  const Framebuffer shifted2 = edgeImage(10);  // two columns: one is beyond the neighbours
  const Accuracy a = compare(shifted, ref);
  EXPECT_EQ(a.correctPixelRate, 1.0);
  EXPECT_EQ(a.exactPixels, ref.size() - 11);  // column 8 of the 11 covered rows
  EXPECT_LT(a.exactIdRate, 1.0);
  EXPECT_GT(a.rmse, 0.0);
  const Accuracy b = compare(shifted2, ref);
  EXPECT_EQ(b.correctPixels, ref.size() - 11);  // column 9 shows 1; ref has 2 at 8..10
  EXPECT_EQ(b.coveredMismatch, 11u);
  EXPECT_EQ(b.exactPixels, ref.size() - 22);
}

TEST(Metrics, EmptyPixelsFollowTheNeighbourRule) {
  const Framebuffer ref = edgeImage(8);
  Framebuffer test = ref;
  test.id[test.index(3, 10)] = kNoId;  // next to the empty bottom row: correct
  test.id[test.index(3, 5)] = kNoId;   // a hole inside triangle 1: wrong
  Framebuffer covered = ref;
  covered.id[covered.index(4, 11)] = 1;   // covers an empty pixel next to triangle 1: correct
  covered.id[covered.index(15, 11)] = 7;  // unknown ID: wrong
  const Accuracy a = compare(test, ref);
  EXPECT_EQ(a.correctPixels, ref.size() - 1);
  EXPECT_EQ(a.missingPixels, 2u);
  EXPECT_EQ(a.coveredMismatch, 0u);
  const Accuracy b = compare(covered, ref);
  EXPECT_EQ(b.correctPixels, ref.size() - 1);
  EXPECT_EQ(b.extraPixels, 2u);
}

TEST(Metrics, BorderPixelsUseOnlyExistingNeighbours) {
  Framebuffer ref(3, 1), test(3, 1);
  ref.id = {5, 6, 7};
  test.id = {6, 7, 5};  // 6 and 7 are neighbours of 0 and 1; 5 is two pixels from pixel 2
  const Accuracy a = compare(test, ref);
  EXPECT_EQ(a.correctPixels, 2u);
  EXPECT_EQ(a.exactPixels, 0u);
}

TEST(Metrics, RandomIdsAreMostlyWrong) {
  const Framebuffer ref = edgeImage(8);
  Framebuffer test = ref;
  std::mt19937_64 rng(7);
  for (auto& id : test.id) id = 1000 + rng() % 100000;
  const Accuracy a = compare(test, ref);
  EXPECT_LT(a.correctPixelRate, 0.05);
  EXPECT_LT(a.exactIdRate, 0.05);
  EXPECT_GT(a.coveredMismatch, ref.size() / 2);
}

TEST(Metrics, RmseAndPsnrMatchAHandComputedExample) {
  Framebuffer ref(2, 1), test(2, 1);
  ref.color = {packRgba8(10, 20, 30, 255), packRgba8(0, 0, 0, 0)};
  test.color = {packRgba8(13, 16, 30, 0), packRgba8(0, 0, 12, 255)};  // alpha is ignored
  // Differences 3, -4, 0, 0, 0, 12: sum of squares 169 over 6 values.
  const Accuracy a = compare(test, ref);
  const double rmse = std::sqrt(169.0 / 6.0);
  EXPECT_DOUBLE_EQ(a.rmse, rmse);
  EXPECT_DOUBLE_EQ(a.psnr, 20.0 * std::log10(255.0 / rmse));
  EXPECT_NEAR(a.psnr, 33.6334, 1e-3);
  EXPECT_DOUBLE_EQ(toJson(a).at("psnr").get<double>(), a.psnr);
}

TEST(Metrics, SizeMismatchThrows) {
  EXPECT_THROW(compare(Framebuffer(4, 4), Framebuffer(4, 5)), InputError);
  EXPECT_THROW(compare(Framebuffer(), Framebuffer()), InputError);
}

}  // namespace
}  // namespace lzb
