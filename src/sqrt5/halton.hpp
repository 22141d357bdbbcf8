#pragma once
// Halton sample vectors for mesh objects (Stamminger & Drettakis, section 4): per unique mesh, a
// vector of surface samples built from the first two Halton sequences (radical inverses in bases
// 2 and 3), extended on demand and kept, so that any prefix of it is evenly spread over the
// surface and a placement draws its first n_s.
//
// Sample k: x = halton2(k + 1) picks the triangle along the prefix sums of the triangle areas (the
// triangle whose share of the total area holds x), the position of x inside that share is the
// first uniform coordinate r, y = halton3(k + 1) the second s; the point is
// v0 + (1 - sqrt r)(v1 - v0) + s sqrt(r) (v2 - v0), uniform by area and continuous in (r, s), so
// the prefix's even spread carries over (folding the square onto the triangle would overlay two
// halves of it).
#include <cstdint>
#include <vector>

#include "src/core/scene.hpp"

namespace lzb::sqrt5 {

// The radical inverse of k in base b (k's digits mirrored about the point), in [0, 1).
double radicalInverse(uint64_t k, uint32_t base);

struct SurfaceSample {
  uint32_t triangle;
  float a, c;  // the point v0 + a (v1 - v0) + c (v2 - v0)
};

class HaltonSurface {
 public:
  HaltonSurface() = default;
  explicit HaltonSurface(const Mesh& mesh);
  // Extends the vector to at least n samples (not thread-safe: call before drawing).
  void reserve(uint64_t n);
  uint64_t size() const { return samples_.size(); }
  const SurfaceSample& operator[](uint64_t k) const { return samples_[k]; }
  double area() const { return cdf_.empty() ? 0.0 : cdf_.back(); }
  uint64_t bytes() const {
    return samples_.capacity() * sizeof(SurfaceSample) + cdf_.capacity() * sizeof(double);
  }

 private:
  std::vector<double> cdf_;  // inclusive prefix sums of the triangle areas
  std::vector<SurfaceSample> samples_;
};

}  // namespace lzb::sqrt5
