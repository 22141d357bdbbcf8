#pragma once
// Deterministic random numbers for the generators. std::mt19937_64 is specified bit-exactly by
// the standard but the <random> distributions are not, so values come from its raw output here.
#include <cstdint>
#include <random>

namespace lzb {

class Rng {
 public:
  explicit Rng(uint64_t seed) : engine_(seed) {}
  // Uniform in [0, 1) from the top 53 bits.
  double uniform() { return double(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [lo, hi] (modulo bias below 2^-40 for the small ranges used here).
  int64_t integer(int64_t lo, int64_t hi) {
    return lo + int64_t(engine_() % uint64_t(hi - lo + 1));
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace lzb
