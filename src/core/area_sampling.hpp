#pragma once
// Sampling surfaces by area, the primitives every point-based method shares: stratified picks
// along inclusive prefix sums of areas (sample i of n takes the stratum [i, i + 1) / n of the
// total, jittered, so consecutive samples move forward along the list and a triangle gets its
// area's share of the samples, the integer part exactly), and uniform points of a triangle from
// two uniform numbers (the unit square folded onto the triangle).
#include <cstdint>

namespace lzb {

// The first j in [from, e) with P[j] > target (e - 1 if none), from >= the list start: a forward
// gallop then a branchless binary search, cheap for the small forward steps of stratified picks.
inline uint64_t searchForward(const double* P, uint64_t e, uint64_t from, double target) {
  // Most steps are a few entries: eight compares counted without a branch first (a gallop's
  // branches mispredict about once a sample).
  if (e - from >= 8) {
    uint64_t n = 0;
    for (uint64_t k = 0; k < 8; ++k) n += P[from + k] <= target ? 1 : 0;
    if (n < 8) return from + n;
    from += 7;  // P[from] <= target
  }
  if (P[from] > target) return from;
  uint64_t lo = from + 1, hi, step = 1;
  for (;;) {
    if (lo >= e) return e - 1;
    hi = e - lo > step ? lo + step : e;
    if (P[hi - 1] > target || hi == e) break;
    lo = hi;
    step <<= 1;
  }
  uint64_t n = hi - lo;
  while (n > 1) {
    const uint64_t h = n >> 1;
    lo = P[lo + h - 1] <= target ? lo + h : lo;
    n -= h;
  }
  return lo;
}

// Folds (a, c), uniform in the unit square, onto the triangle a, c >= 0, a + c <= 1 (uniform there
// too) without a branch, which would mispredict half the time: with m = 1, a + (1 - 2a) = 1 - a
// exactly for 24-bit a.
inline void foldUnitSquare(float& a, float& c) {
  const float m = float(a + c > 1.0f);
  a += m * (1.0f - 2.0f * a);
  c += m * (1.0f - 2.0f * c);
}

}  // namespace lzb
