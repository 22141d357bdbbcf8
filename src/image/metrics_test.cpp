#include "src/image/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "src/core/error.hpp"

namespace lzb {
namespace {

// A reference whose 17 samples all show `id` with colour `c` (kNoId: empty, kBackground).
ReferenceFrame uniformReference(int w, int h, uint64_t id, Rgba8 c) {
  ReferenceFrame ref(w, h);
  for (size_t i = 0; i < ref.size(); ++i) {
    ref.centreId[i] = id;
    for (int k = 0; k < kSubsamples; ++k) ref.subsampleId[i * kSubsamples + size_t(k)] = id;
    for (int ch = 0; ch < 3; ++ch) ref.boxColor[i][size_t(ch)] = float(channel(c, ch));
  }
  return ref;
}

// A frame showing `id` with colour `c` everywhere.
Framebuffer uniformFrame(int w, int h, uint64_t id, Rgba8 c) {
  Framebuffer fb(w, h);
  for (size_t i = 0; i < fb.size(); ++i) {
    fb.id[i] = id;
    fb.color[i] = c;
    fb.depth[i] = id == kNoId ? kEmptyDepth : 1.0f;
  }
  return fb;
}

void setSubsample(ReferenceFrame& ref, size_t pixel, int k, uint64_t id) {
  ref.subsampleId[pixel * kSubsamples + size_t(k)] = id;
}

constexpr Rgba8 kGrey = packRgba8(100, 100, 100);

void expectCountsAddUp(const Accuracy& a) {
  EXPECT_EQ(a.missingPixels + a.extraPixels + a.wrongPixels,
            a.coveredPixels - a.correctCoveredPixels);
  EXPECT_EQ(a.correctPixels - a.correctCoveredPixels, a.pixels - a.coveredPixels);
  EXPECT_EQ(a.referenceSamplesPerPixel, 17);
}

TEST(Metrics, TheReferenceItselfIsPerfect) {
  const ReferenceFrame ref = uniformReference(6, 4, 3, kGrey);
  const Accuracy a = compare(uniformFrame(6, 4, 3, kGrey), ref);
  EXPECT_EQ(a.pixels, 24u);
  EXPECT_EQ(a.coveredPixels, 24u);
  EXPECT_EQ(a.correctRateCovered, 1.0);
  EXPECT_EQ(a.correctRateAll, 1.0);
  EXPECT_EQ(a.exactIdRateCovered, 1.0);
  EXPECT_EQ(a.rmseAa, 0.0);
  EXPECT_TRUE(std::isinf(a.psnrAa) && a.psnrAa > 0);
  expectCountsAddUp(a);
  const nlohmann::json j = toJson(a);
  EXPECT_TRUE(j.at("psnr_aa").is_null());
  EXPECT_EQ(j.at("correct_rate_covered"), 1.0);
  EXPECT_EQ(j.at("reference_samples_per_pixel"), 17);
  EXPECT_EQ(j.size(), 14u);
  // Round-trips through text: no inf or nan reaches the JSON.
  EXPECT_EQ(nlohmann::json::parse(j.dump()), j);
}

TEST(Metrics, AnIdSeenByOneSubsampleIsCorrectButNotExact) {
  ReferenceFrame ref = uniformReference(3, 2, 5, kGrey);
  setSubsample(ref, 4, 13, 9);  // a sub-pixel triangle seen once, in pixel 4
  Framebuffer test = uniformFrame(3, 2, 5, kGrey);
  test.id[4] = 9;
  test.id[1] = 9;  // not seen in pixel 1
  const Accuracy a = compare(test, ref);
  EXPECT_EQ(a.correctCoveredPixels, 5u);
  EXPECT_EQ(a.wrongPixels, 1u);
  EXPECT_EQ(a.exactCoveredPixels, 4u);
  EXPECT_DOUBLE_EQ(a.correctRateCovered, 5.0 / 6.0);
  EXPECT_DOUBLE_EQ(a.exactIdRateCovered, 4.0 / 6.0);
  expectCountsAddUp(a);
}

TEST(Metrics, TheCentreIdCountsAsOneOfTheSeventeen) {
  ReferenceFrame ref = uniformReference(1, 1, 5, kGrey);
  ref.centreId[0] = 8;  // seen at the centre only
  const Accuracy a = compare(uniformFrame(1, 1, 8, kGrey), ref);
  EXPECT_EQ(a.correctCoveredPixels, 1u);
  EXPECT_EQ(a.exactCoveredPixels, 1u);
}

TEST(Metrics, SkyOnlyFramesHaveNoCoveredPixelsAndRatesOfOne) {
  const ReferenceFrame ref = uniformReference(4, 3, kNoId, kBackground);
  const Accuracy a = compare(uniformFrame(4, 3, kNoId, kBackground), ref);
  EXPECT_EQ(a.coveredPixels, 0u);
  EXPECT_EQ(a.correctPixels, 12u);
  EXPECT_EQ(a.correctRateCovered, 1.0);
  EXPECT_EQ(a.exactIdRateCovered, 1.0);
  EXPECT_EQ(a.correctRateAll, 1.0);
  EXPECT_EQ(toJson(a).at("correct_rate_covered"), 1.0);
  expectCountsAddUp(a);
}

TEST(Metrics, HolesAreEmptyPixelsWhereEverySampleIsCovered) {
  ReferenceFrame ref = uniformReference(4, 1, 5, kGrey);
  setSubsample(ref, 1, 0, kNoId);  // pixel 1: an edge, one sub-sample sees the sky
  ref.centreId[2] = kNoId;         // pixel 2: the centre sees the sky
  Framebuffer test = uniformFrame(4, 1, kNoId, kBackground);
  test.id[3] = 5;
  const Accuracy a = compare(test, ref);
  EXPECT_EQ(a.coveredPixels, 4u);
  EXPECT_EQ(a.missingPixels, 1u);  // pixel 0 only: 1 and 2 may show the sky
  EXPECT_EQ(a.correctCoveredPixels, 3u);
  EXPECT_EQ(a.exactCoveredPixels, 2u);  // pixels 2 (both empty) and 3
  EXPECT_EQ(a.wrongPixels + a.extraPixels, 0u);
  expectCountsAddUp(a);
}

TEST(Metrics, ExtrasShowGeometryWhereNoSampleDoes) {
  ReferenceFrame ref = uniformReference(3, 1, kNoId, kBackground);
  setSubsample(ref, 2, 7, 4);  // pixel 2 sees triangle 4 once
  Framebuffer test = uniformFrame(3, 1, 4, kGrey);
  test.id[1] = kNoId;
  const Accuracy a = compare(test, ref);
  EXPECT_EQ(a.coveredPixels, 2u);   // pixel 0 (test) and pixel 2 (both)
  EXPECT_EQ(a.extraPixels, 1u);     // pixel 0
  EXPECT_EQ(a.correctCoveredPixels, 1u);
  EXPECT_EQ(a.correctPixels, 2u);   // pixel 1 is empty in both
  EXPECT_DOUBLE_EQ(a.correctRateAll, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(a.correctRateCovered, 0.5);
  expectCountsAddUp(a);
}

TEST(Metrics, WrongPixelsShowATriangleNoSampleSees) {
  ReferenceFrame ref = uniformReference(2, 2, 5, kGrey);
  setSubsample(ref, 3, 2, kNoId);
  Framebuffer test = uniformFrame(2, 2, 6, kGrey);
  test.id[0] = 5;
  const Accuracy a = compare(test, ref);
  EXPECT_EQ(a.wrongPixels, 3u);
  EXPECT_EQ(a.missingPixels + a.extraPixels, 0u);
  expectCountsAddUp(a);
}

TEST(Metrics, RandomIdsAreMostlyWrong) {
  const ReferenceFrame ref = uniformReference(16, 12, 5, kGrey);
  Framebuffer test = uniformFrame(16, 12, 5, kGrey);
  std::mt19937_64 rng(7);
  for (auto& id : test.id) id = 1000 + rng() % 100000;
  const Accuracy a = compare(test, ref);
  EXPECT_LT(a.correctRateCovered, 0.05);
  EXPECT_LT(a.exactIdRateCovered, 0.05);
  EXPECT_GT(a.wrongPixels, ref.size() / 2);
}

TEST(Metrics, RmseIsAgainstTheBoxFilteredColour) {
  ReferenceFrame ref(2, 1);
  ref.boxColor = {{10.5f, 20.0f, 30.0f}, {0.0f, 0.0f, 0.0625f}};
  Framebuffer test(2, 1);
  test.color = {packRgba8(13, 16, 30, 0), packRgba8(0, 0, 12, 255)};  // alpha is ignored
  // Differences 2.5, -4, 0, 0, 0, 11.9375 over 6 values.
  const double squares = 2.5 * 2.5 + 16.0 + 11.9375 * 11.9375;
  const Accuracy a = compare(test, ref);
  const double rmse = std::sqrt(squares / 6.0);
  EXPECT_DOUBLE_EQ(a.rmseAa, rmse);
  EXPECT_DOUBLE_EQ(a.psnrAa, 20.0 * std::log10(255.0 / rmse));
  EXPECT_DOUBLE_EQ(toJson(a).at("psnr_aa").get<double>(), a.psnrAa);
  EXPECT_DOUBLE_EQ(toJson(a).at("rmse_aa").get<double>(), a.rmseAa);
}

TEST(Metrics, SizeMismatchThrows) {
  EXPECT_THROW(compare(Framebuffer(4, 4), ReferenceFrame(4, 5)), InputError);
  EXPECT_THROW(compare(Framebuffer(), ReferenceFrame()), InputError);
}

}  // namespace
}  // namespace lzb
