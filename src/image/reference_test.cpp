#include "src/image/reference.hpp"

#include <gtest/gtest.h>

#include <string>

#include "src/core/error.hpp"
#include "tests/support/cameras.hpp"

namespace lzb {
namespace {

// A 2 x 1 centre image and its 8 x 4 sub-sample image: sub-sample (a, b) of pixel i holds ID
// 100 i + a + 4b and colour bytes (16 i + a + 4b, 3 b, 255); sub-sample (3, 3) of pixel 1 is
// empty (kBackground counts as black in the box filter).
struct CentresAndSubsamples {
  Framebuffer centres{2, 1}, fine{8, 4};
};

CentresAndSubsamples handBuilt() {
  CentresAndSubsamples p;
  p.centres.id = {7, kNoId};
  for (int i = 0; i < 2; ++i)
    for (int b = 0; b < 4; ++b)
      for (int a = 0; a < 4; ++a) {
        const size_t s = p.fine.index(4 * i + a, b);
        p.fine.id[s] = uint64_t(100 * i + a + 4 * b);
        p.fine.color[s] = packRgba8(uint8_t(16 * i + a + 4 * b), uint8_t(3 * b), 255);
      }
  const size_t empty = p.fine.index(7, 3);
  p.fine.id[empty] = kNoId;
  p.fine.color[empty] = kBackground;
  return p;
}

TEST(Reference, SubsamplesAreRowMajorPerPixel) {
  const CentresAndSubsamples p = handBuilt();
  const ReferenceFrame ref = reduceReference(p.centres, p.fine);
  ASSERT_EQ(ref.width, 2);
  ASSERT_EQ(ref.height, 1);
  EXPECT_EQ(ref.centreId, p.centres.id);
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < kSubsamples; ++k) {
      const uint64_t want = i == 1 && k == 15 ? kNoId : uint64_t(100 * i + k);
      EXPECT_EQ(ref.subsamples(size_t(i))[k], want) << "pixel " << i << " sub-sample " << k;
    }
}

TEST(Reference, BoxColourIsTheExactMeanOfTheSixteenSubsamples) {
  const CentresAndSubsamples p = handBuilt();
  const ReferenceFrame ref = reduceReference(p.centres, p.fine);
  // Pixel 0: R = mean of 0..15 = 7.5; G = 3 * mean(b) = 4.5; B = 255.
  EXPECT_EQ(ref.boxColor[0][0], 7.5f);
  EXPECT_EQ(ref.boxColor[0][1], 4.5f);
  EXPECT_EQ(ref.boxColor[0][2], 255.0f);
  // Pixel 1: R = (15 * 16 + 0 + ... + 14) / 16 = (240 + 105) / 16 (the empty one is black).
  EXPECT_EQ(ref.boxColor[1][0], 345.0f / 16.0f);
  EXPECT_EQ(ref.boxColor[1][1], (4.5f * 16.0f - 9.0f) / 16.0f);
  EXPECT_EQ(ref.boxColor[1][2], 255.0f * 15.0f / 16.0f);
}

TEST(Reference, SizesThatAreNotFourTimesThrow) {
  EXPECT_THROW(reduceReference(Framebuffer(2, 1), Framebuffer(8, 3)), InputError);
  EXPECT_THROW(reduceReference(Framebuffer(2, 1), Framebuffer(2, 1)), InputError);
  EXPECT_THROW(reduceReference(Framebuffer(), Framebuffer()), InputError);
}

TEST(Reference, SubsampleSizeLimitNamesTheOption) {
  EXPECT_NO_THROW(checkSubsampleSize(4096, 4096, "--reference"));
  EXPECT_NO_THROW(checkSubsampleSize(0, 0, "--reference"));  // not given yet
  for (auto [w, h] : {std::pair{4097, 10}, std::pair{10, 4097}}) {
    try {
      checkSubsampleSize(w, h, "--reference");
      FAIL() << "expected InputError for " << w << "x" << h;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--reference:", 0), 0u) << e.what();
    }
  }
}

TEST(Reference, FinePixelCentresAreTheStratumCentres) {
  const Camera camera = test::lookAtCamera({1, 2, 3}, {0, 0, 0}, 0.1, 100.0, 40, 30, 60.0);
  const Camera fine = subsampleCamera(camera);
  ASSERT_EQ(fine.width(), 160);
  ASSERT_EQ(fine.height(), 120);
  for (int j : {0, 17, 29})
    for (int i : {0, 13, 39})
      for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a) {
          const glm::dvec3 want = camera.pixelDirection(i + (a + 0.5) / 4.0, j + (b + 0.5) / 4.0);
          const glm::dvec3 got = fine.pixelDirection(4 * i + a + 0.5, 4 * j + b + 0.5);
          EXPECT_LT(glm::length(got - want), 1e-12) << i << " " << j << " " << a << " " << b;
        }
}

}  // namespace
}  // namespace lzb
