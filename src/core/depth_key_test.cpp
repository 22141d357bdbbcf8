#include "src/core/depth_key.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "src/core/framebuffer.hpp"

namespace lzb {
namespace {

struct Sample {
  float depth;
  uint64_t id;
};

// Depths with many exact ties, +inf (empty) and extremes; IDs with ties, kNoId and wide values.
std::vector<Sample> awkwardSamples(bool wideIds, size_t n) {
  std::mt19937_64 rng(7);
  const float depths[] = {1e-6f, 0.5f, 0.5f, 1.0f, 1.0f, 3.25f, 1e30f,
                          std::numeric_limits<float>::max(), kEmptyDepth};
  std::vector<Sample> out;
  for (size_t k = 0; k < n; ++k) {
    const float d = rng() % 3 ? depths[rng() % std::size(depths)]
                              : std::uniform_real_distribution<float>(0.1f, 100.0f)(rng);
    uint64_t id = rng() % 5;
    if (rng() % 4 == 0) id = wideIds ? (rng() >> 1) : uint32_t(rng());
    if (d == kEmptyDepth) id = kNoId;
    out.push_back({d, id});
  }
  return out;
}

// The framebuffer's rule: whether keepNearer(b) replaces a pixel holding a.
bool framebufferKeeps(const Sample& a, const Sample& b) {
  Framebuffer fb(1, 1);
  fb.depth[0] = a.depth;
  fb.id[0] = a.id;
  fb.keepNearer(0, b.depth, 0, b.id);
  return fb.id[0] != a.id || fb.depth[0] != a.depth;
}

// The plain float statement of the rule, for positive depths and +inf.
bool floatNearer(const Sample& b, const Sample& a) {
  return b.depth < a.depth || (b.depth == a.depth && b.id < a.id);
}

TEST(DepthKey, NarrowKeyOrderIsTheFramebuffersNearerRule) {
  const std::vector<Sample> s = awkwardSamples(false, 400);
  for (const Sample& a : s)
    for (const Sample& b : s) {
      const uint64_t ka = a.id == kNoId ? kEmptyKey : narrowKey(a.depth, a.id);
      const uint64_t kb = b.id == kNoId ? kEmptyKey : narrowKey(b.depth, b.id);
      ASSERT_EQ(kb < ka, framebufferKeeps(a, b)) << a.depth << "/" << a.id << " vs " << b.depth << "/" << b.id;
      ASSERT_EQ(framebufferKeeps(a, b), floatNearer(b, a));
    }
}

TEST(DepthKey, WideKeyOrderIsTheFramebuffersNearerRule) {
  const std::vector<Sample> s = awkwardSamples(true, 400);
  for (const Sample& a : s)
    for (const Sample& b : s) {
      const WideKey ka = a.id == kNoId ? kEmptyWideKey : wideKey(a.depth, a.id);
      const WideKey kb = b.id == kNoId ? kEmptyWideKey : wideKey(b.depth, b.id);
      ASSERT_EQ(kb < ka, framebufferKeeps(a, b)) << a.depth << "/" << a.id << " vs " << b.depth << "/" << b.id;
      ASSERT_EQ(nearer(b.depth, b.id, a.depth, a.id), floatNearer(b, a));
    }
}

TEST(DepthKey, EmptyKeysLoseToEverySample) {
  EXPECT_LT(narrowKey(kEmptyDepth, 0xfffffffeu), kEmptyKey);
  EXPECT_LT(wideKey(kEmptyDepth, kNoId - 1), kEmptyWideKey);
  EXPECT_TRUE(nearer(std::numeric_limits<float>::max(), kNoId - 1, kEmptyDepth, kNoId));
}

// Many threads putting the same samples in different orders leave the sequential minimum.
TEST(DepthKey, KeyBufferGivesTheSequentialMinimumForAnyThreadOrder) {
  for (bool wide : {false, true}) {
    if (wide && !wideKeysSupported()) continue;
    const int w = 16, h = 8;
    const std::vector<Sample> s = awkwardSamples(wide, 20000);
    Framebuffer expected(w, h);
    for (size_t k = 0; k < s.size(); ++k)
      if (s[k].id != kNoId) expected.keepNearer(k % expected.size(), s[k].depth, 0, s[k].id);
    for (int threads : {1, 2, 4}) {
      KeyBuffer keys;
      keys.reset(w, h, wide, threads);
      const long n = long(s.size());
#pragma omp parallel for schedule(dynamic, 7) num_threads(threads)
      for (long k = n - 1; k >= 0; --k)
        if (s[size_t(k)].id != kNoId) keys.put(size_t(k) % size_t(w * h), s[size_t(k)].depth, s[size_t(k)].id);
      Framebuffer got(w, h);
      keys.resolve(got, threads);
      EXPECT_EQ(got.id, expected.id) << "wide " << wide << ", threads " << threads;
      EXPECT_EQ(got.depth, expected.depth) << "wide " << wide << ", threads " << threads;
    }
  }
}

TEST(DepthKey, ResolveLeavesUntouchedPixelsEmpty) {
  KeyBuffer keys;
  keys.reset(3, 2, false, 1);
  keys.put(4, 2.5f, 17);
  Framebuffer fb(3, 2);
  keys.resolve(fb, 1);
  EXPECT_EQ(fb.id[4], 17u);
  EXPECT_EQ(fb.depth[4], 2.5f);
  EXPECT_EQ(fb.coveredCount(), 1u);
  EXPECT_EQ(fb.depth[0], kEmptyDepth);
}

}  // namespace
}  // namespace lzb
