#include "src/sqrt5/halton.hpp"

#include <algorithm>

#include <cmath>

namespace lzb::sqrt5 {

double radicalInverse(uint64_t k, uint32_t base) {
  const double inv = 1.0 / base;
  double scale = inv, x = 0.0;
  while (k > 0) {
    x += double(k % base) * scale;
    k /= base;
    scale *= inv;
  }
  return x;
}

HaltonSurface::HaltonSurface(const Mesh& mesh) {
  cdf_.resize(mesh.size());
  double sum = 0.0;
  for (size_t t = 0; t < mesh.size(); ++t) {
    const glm::dvec3 a(mesh.vertex(t, 0)), b(mesh.vertex(t, 1)), c(mesh.vertex(t, 2));
    sum += 0.5 * glm::length(glm::cross(b - a, c - a));
    cdf_[t] = sum;
  }
}

void HaltonSurface::reserve(uint64_t n) {
  if (n <= samples_.size() || cdf_.empty()) return;
  const double total = cdf_.back();
  samples_.reserve(n);
  for (uint64_t k = samples_.size(); k < n; ++k) {
    const double x = radicalInverse(k + 1, 2) * total;
    const size_t t = size_t(std::upper_bound(cdf_.begin(), cdf_.end(), x) - cdf_.begin());
    const size_t tri = std::min(t, cdf_.size() - 1);
    const double lo = tri == 0 ? 0.0 : cdf_[tri - 1], share = cdf_[tri] - lo;
    // The square mapped onto the triangle continuously (a = 1 - sqrt(r), c = s sqrt(r)): uniform
    // by area and keeping the low-discrepancy spread, which folding the square would overlay.
    const double r = std::clamp(share > 0.0 ? (x - lo) / share : 0.0, 0.0, 1.0);
    const double q = std::sqrt(r), s = radicalInverse(k + 1, 3);
    samples_.push_back({uint32_t(tri), float(1.0 - q), float(s * q)});
  }
}

}  // namespace lzb::sqrt5
