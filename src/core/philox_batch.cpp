// Philox-4x32-10 over a batch of consecutive counters: 16 (AVX-512) or 8 (AVX2) counters per
// vector, the 32 x 32 -> 64 bit products of even and odd lanes formed with vpmuludq and their
// halves blended back; a scalar loop elsewhere. The variant is chosen once, by CPU. Bit-identical
// to Random123's Philox4x32 (tested).
#include <immintrin.h>

#include <cstdint>

#include "src/core/philox_stream.hpp"

namespace lzb {

namespace {

constexpr uint32_t kM0 = 0xD2511F53u, kM1 = 0xCD9E8D57u;
constexpr uint32_t kW0 = 0x9E3779B9u, kW1 = 0xBB67AE85u;

using BatchFn = void (*)(uint32_t, uint32_t, uint32_t, uint32_t, uint64_t, uint32_t, uint32_t*,
                         uint32_t*, uint32_t*, uint32_t*);

void scalarBatch(uint32_t k0, uint32_t k1, uint32_t c0, uint32_t c1, uint64_t first, uint32_t n,
                 uint32_t* w0, uint32_t* w1, uint32_t* w2, uint32_t* w3) {
  for (uint32_t i = 0; i < n; ++i) {
    const uint64_t index = first + i;
    uint32_t x0 = c0, x1 = c1, x2 = uint32_t(index), x3 = uint32_t(index >> 32 & 0xffff);
    uint32_t a = k0, b = k1;
    for (int r = 0; r < 10; ++r) {
      const uint64_t p0 = uint64_t(kM0) * x0, p1 = uint64_t(kM1) * x2;
      const uint32_t y0 = uint32_t(p1 >> 32) ^ x1 ^ a, y2 = uint32_t(p0 >> 32) ^ x3 ^ b;
      x1 = uint32_t(p1);
      x3 = uint32_t(p0);
      x0 = y0;
      x2 = y2;
      a += kW0;
      b += kW1;
    }
    w0[i] = x0;
    w1[i] = x1;
    w2[i] = x2;
    w3[i] = x3;
  }
}

#if defined(__x86_64__)
// GCC 12 warns about the undefined source operand inside avx512fintrin.h's shift intrinsics.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
__attribute__((target("avx512f"))) void avx512Batch(uint32_t k0, uint32_t k1, uint32_t c0,
                                                    uint32_t c1, uint64_t first, uint32_t n,
                                                    uint32_t* w0, uint32_t* w1, uint32_t* w2,
                                                    uint32_t* w3) {
  const __m512i m0 = _mm512_set1_epi64(kM0), m1 = _mm512_set1_epi64(kM1);
  const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
// (hi, lo) of x * m per 32-bit lane: even and odd lanes' 64-bit products, halves blended back.
#define LZB_MULHILO512(x, m, hi, lo)                                                        \
  do {                                                                                      \
    const __m512i even_ = _mm512_mul_epu32(x, m);                                           \
    const __m512i odd_ = _mm512_mul_epu32(_mm512_srli_epi64(x, 32), m);                     \
    lo = _mm512_mask_blend_epi32(0xAAAA, even_, _mm512_slli_epi64(odd_, 32));               \
    hi = _mm512_mask_blend_epi32(0xAAAA, _mm512_srli_epi64(even_, 32), odd_);               \
  } while (0)
  uint32_t i = 0;
  for (; i + 16 <= n; i += 16) {
    const uint64_t index = first + i;
    const __m512i lo32 = _mm512_set1_epi32(int(uint32_t(index)));
    __m512i x2 = _mm512_add_epi32(lo32, lane);
    // Lanes whose low word wrapped carry into word 3 (kept to 16 bits).
    const __mmask16 wrapped = _mm512_cmplt_epu32_mask(x2, lo32);
    __m512i x3 = _mm512_set1_epi32(int(uint32_t(index >> 32 & 0xffff)));
    x3 = _mm512_and_si512(_mm512_mask_add_epi32(x3, wrapped, x3, _mm512_set1_epi32(1)),
                          _mm512_set1_epi32(0xffff));
    __m512i x0 = _mm512_set1_epi32(int(c0)), x1 = _mm512_set1_epi32(int(c1));
    uint32_t a = k0, b = k1;
    for (int r = 0; r < 10; ++r) {
      __m512i hi0, lo0, hi1, lo1;
      LZB_MULHILO512(x0, m0, hi0, lo0);
      LZB_MULHILO512(x2, m1, hi1, lo1);
      x0 = _mm512_xor_si512(_mm512_xor_si512(hi1, x1), _mm512_set1_epi32(int(a)));
      x1 = lo1;
      x2 = _mm512_xor_si512(_mm512_xor_si512(hi0, x3), _mm512_set1_epi32(int(b)));
      x3 = lo0;
      a += kW0;
      b += kW1;
    }
    _mm512_storeu_si512(w0 + i, x0);
    _mm512_storeu_si512(w1 + i, x1);
    _mm512_storeu_si512(w2 + i, x2);
    _mm512_storeu_si512(w3 + i, x3);
  }
  if (i < n) scalarBatch(k0, k1, c0, c1, first + i, n - i, w0 + i, w1 + i, w2 + i, w3 + i);
}

__attribute__((target("avx2"))) void avx2Batch(uint32_t k0, uint32_t k1, uint32_t c0, uint32_t c1,
                                               uint64_t first, uint32_t n, uint32_t* w0,
                                               uint32_t* w1, uint32_t* w2, uint32_t* w3) {
  const __m256i m0 = _mm256_set1_epi64x(kM0), m1 = _mm256_set1_epi64x(kM1);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i sign = _mm256_set1_epi32(int(0x80000000u));
#define LZB_MULHILO256(x, m, hi, lo)                                                        \
  do {                                                                                      \
    const __m256i even_ = _mm256_mul_epu32(x, m);                                           \
    const __m256i odd_ = _mm256_mul_epu32(_mm256_srli_epi64(x, 32), m);                     \
    lo = _mm256_blend_epi32(even_, _mm256_slli_epi64(odd_, 32), 0xAA);                      \
    hi = _mm256_blend_epi32(_mm256_srli_epi64(even_, 32), odd_, 0xAA);                      \
  } while (0)
  uint32_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const uint64_t index = first + i;
    const __m256i lo32 = _mm256_set1_epi32(int(uint32_t(index)));
    __m256i x2 = _mm256_add_epi32(lo32, lane);
    // Unsigned x2 < lo32 (wrapped) as a signed compare of sign-flipped values; -1 where true.
    const __m256i wrapped =
        _mm256_cmpgt_epi32(_mm256_xor_si256(lo32, sign), _mm256_xor_si256(x2, sign));
    __m256i x3 = _mm256_set1_epi32(int(uint32_t(index >> 32 & 0xffff)));
    x3 = _mm256_and_si256(_mm256_sub_epi32(x3, wrapped), _mm256_set1_epi32(0xffff));
    __m256i x0 = _mm256_set1_epi32(int(c0)), x1 = _mm256_set1_epi32(int(c1));
    uint32_t a = k0, b = k1;
    for (int r = 0; r < 10; ++r) {
      __m256i hi0, lo0, hi1, lo1;
      LZB_MULHILO256(x0, m0, hi0, lo0);
      LZB_MULHILO256(x2, m1, hi1, lo1);
      x0 = _mm256_xor_si256(_mm256_xor_si256(hi1, x1), _mm256_set1_epi32(int(a)));
      x1 = lo1;
      x2 = _mm256_xor_si256(_mm256_xor_si256(hi0, x3), _mm256_set1_epi32(int(b)));
      x3 = lo0;
      a += kW0;
      b += kW1;
    }
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(w0 + i), x0);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(w1 + i), x1);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(w2 + i), x2);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(w3 + i), x3);
  }
  if (i < n) scalarBatch(k0, k1, c0, c1, first + i, n - i, w0 + i, w1 + i, w2 + i, w3 + i);
}
#undef LZB_MULHILO512
#undef LZB_MULHILO256
#pragma GCC diagnostic pop
#endif

BatchFn chooseBatch() {
#if defined(__x86_64__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return avx512Batch;
  if (__builtin_cpu_supports("avx2")) return avx2Batch;
#endif
  return scalarBatch;
}

}  // namespace

void philoxBatch(const SampleStream& stream, uint64_t box, uint64_t first, uint32_t n, uint32_t* w0,
                 uint32_t* w1, uint32_t* w2, uint32_t* w3) {
  static const BatchFn batch = chooseBatch();
  batch(stream.key0(), stream.key1(), uint32_t(box), uint32_t(box >> 32), first, n, w0, w1, w2, w3);
}

}  // namespace lzb
