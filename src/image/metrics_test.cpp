#include "src/image/metrics.hpp"

#include <gtest/gtest.h>

#include <omp.h>

#include <atomic>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <tuple>

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
  EXPECT_EQ(j.at("witness"), "none");
  EXPECT_EQ(j.at("witnessed_pixels"), 0);
  EXPECT_EQ(j.size(), 16u);
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

// A witness that proves exactly the (x, y, ID) triples it holds and counts the questions.
class ListWitness : public VisibilityWitness {
 public:
  std::set<std::tuple<int, int, uint64_t>> proven;
  mutable std::atomic<int> asked{0};
  std::string name() const override { return "list"; }
  bool visibleInPixel(int x, int y, uint64_t id) const override {
    ++asked;
    return proven.count({x, y, id}) > 0;
  }
};

TEST(Metrics, AWitnessSettlesOnlyCoveredPixelsTheSeventeenMiss) {
  const ReferenceFrame ref = uniformReference(3, 2, 5, kGrey);
  Framebuffer test = uniformFrame(3, 2, 5, kGrey);
  test.id[1] = 9;      // (1, 0): proven below
  test.id[2] = 9;      // (2, 0): not proven
  test.id[3] = kNoId;  // (0, 1): a hole, never asked even if "proven"
  ListWitness witness;
  witness.proven = {{1, 0, 9}, {0, 1, kNoId}, {0, 0, 5}};
  const Accuracy a = compare(test, ref, &witness);
  EXPECT_EQ(witness.asked, 2);  // pixels 1 and 2: pixel 0's ID is among the 17
  EXPECT_EQ(a.witness, "list");
  EXPECT_EQ(a.witnessedPixels, 1u);
  EXPECT_EQ(a.coveredPixels, 6u);
  EXPECT_EQ(a.correctCoveredPixels, 4u);
  EXPECT_EQ(a.wrongPixels, 1u);
  EXPECT_EQ(a.missingPixels, 1u);
  EXPECT_EQ(a.extraPixels, 0u);
  EXPECT_EQ(a.exactCoveredPixels, 3u);  // a witness proves visibility, not the centre's ID
  EXPECT_DOUBLE_EQ(a.correctRateCovered, 4.0 / 6.0);
  expectCountsAddUp(a);
  const nlohmann::json j = toJson(a);
  EXPECT_EQ(j.at("witness"), "list");
  EXPECT_EQ(j.at("witnessed_pixels"), 1);
  // Without the witness the same frame loses exactly the witnessed pixel.
  const Accuracy plain = compare(test, ref);
  EXPECT_EQ(plain.witness, "none");
  EXPECT_EQ(plain.correctCoveredPixels + a.witnessedPixels, a.correctCoveredPixels);
}

TEST(Metrics, AWitnessedTriangleAgainstTheSkyIsCorrectNotExtra) {
  const ReferenceFrame ref = uniformReference(3, 1, kNoId, kBackground);
  Framebuffer test = uniformFrame(3, 1, 4, kGrey);  // a sub-pixel triangle no sample hit
  test.id[2] = kNoId;
  ListWitness witness;
  witness.proven = {{0, 0, 4}};
  const Accuracy a = compare(test, ref, &witness);
  EXPECT_EQ(a.coveredPixels, 2u);
  EXPECT_EQ(a.witnessedPixels, 1u);
  EXPECT_EQ(a.extraPixels, 1u);  // pixel 1
  EXPECT_EQ(a.correctCoveredPixels, 1u);
  EXPECT_EQ(a.correctPixels, 2u);  // pixel 0 (witnessed) and pixel 2 (sky in both)
  expectCountsAddUp(a);
}

// Proves about a third of (pixel, ID) pairs, by a hash: the same answer on every call.
class HashWitness : public VisibilityWitness {
 public:
  std::string name() const override { return "hash"; }
  bool visibleInPixel(int x, int y, uint64_t id) const override {
    return (uint64_t(x) * 0x9e3779b97f4a7c15ull ^ uint64_t(y) * 0xc2b2ae3d27d4eb4full ^ id) % 3 == 0;
  }
};

TEST(Metrics, WitnessedCountsDoNotDependOnTheThreads) {
  const ReferenceFrame ref = uniformReference(97, 61, 5, kGrey);
  Framebuffer test = uniformFrame(97, 61, 5, kGrey);
  std::mt19937_64 rng(11);
  for (auto& id : test.id) id = rng() % 4 == 0 ? kNoId : 1000 + rng() % 1000;
  const HashWitness witness;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const nlohmann::json one = toJson(compare(test, ref, &witness));
  omp_set_num_threads(4);
  const nlohmann::json four = toJson(compare(test, ref, &witness));
  omp_set_num_threads(threads);
  EXPECT_EQ(one, four);
  EXPECT_GT(one.at("witnessed_pixels").get<size_t>(), test.size() / 5);
}

}  // namespace
}  // namespace lzb
