#pragma once
// All randomness of the sampling methods: Philox-4x32-10 (Random123), a counter-based generator,
// keyed by (seed, frame) with the counter (node key, sample index, purpose). A sample's random
// numbers therefore depend only on what it is, never on the thread or rank that draws it.
#include <Random123/philox.h>

#include <cstdint>

namespace lzb {

// splitmix64's finalizer: a bijective 64-bit mixer.
inline uint64_t mix64(uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

inline uint64_t hashCombine(uint64_t h, uint64_t v) { return mix64(h ^ mix64(v + 0x9e3779b97f4a7c15ull)); }

// A uniform double in [0, 1) from 53 of the 64 bits.
inline double unit53(uint32_t lo, uint32_t hi) {
  return double(((uint64_t(hi) << 32) | lo) >> 11) * 0x1p-53;
}
// A uniform float in [0, 1) from 24 bits.
inline float unit24(uint32_t w) { return float(w >> 8) * 0x1p-24f; }

// The frame number of sample sets that do not change with the frame (the sample cache).
constexpr uint64_t kTimelessFrame = ~uint64_t(0);

// Purposes (the top 16 bits of the counter's last word): a sample's first draw, fresh numbers for
// deep instance descents, and per-box decisions.
enum Purpose : uint32_t { kSampleDraw = 0, kRefreshDraw = 1, kBoxRounding = 0x100 };

class SampleStream {
 public:
  SampleStream(uint64_t seed, uint64_t frame) {
    const uint64_t k = hashCombine(mix64(seed), frame);
    key_ = {{uint32_t(k), uint32_t(k >> 32)}};
  }
  // Four 32-bit words for (box, index, purpose); index < 2^48.
  __attribute__((always_inline)) r123::Philox4x32::ctr_type draw(
      uint64_t box, uint64_t index, uint32_t purpose = kSampleDraw) const {
    const r123::Philox4x32::ctr_type c = {
        {uint32_t(box), uint32_t(box >> 32), uint32_t(index),
         uint32_t(index >> 32 & 0xffff) | (purpose << 16)}};
    return r123::Philox4x32()(c, key_);
  }
  uint32_t key0() const { return key_.v[0]; }
  uint32_t key1() const { return key_.v[1]; }

 private:
  r123::Philox4x32::key_type key_;
};

// The first draws (purpose kSampleDraw) of samples [first, first + n) of a box, the same words
// as draw(box, first + k): w[0..3][k]. Vectorized over samples (AVX-512 / AVX2 when present).
void philoxBatch(const SampleStream& stream, uint64_t box, uint64_t first, uint32_t n,
                 uint32_t* w0, uint32_t* w1, uint32_t* w2, uint32_t* w3);

}  // namespace lzb
