#include "src/core/affine.hpp"

#include <algorithm>
#include <numbers>

namespace lzb {

namespace {

// Largest eigenvalue of a symmetric positive semi-definite 3x3 matrix (closed form).
double largestEigenvalue(const glm::dmat3& m) {
  const double p1 = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
  const double tr = m[0][0] + m[1][1] + m[2][2];
  if (p1 <= 1e-30 * tr * tr) return std::max({m[0][0], m[1][1], m[2][2]});
  const double q = tr / 3.0;
  const double p2 = (m[0][0] - q) * (m[0][0] - q) + (m[1][1] - q) * (m[1][1] - q) +
                    (m[2][2] - q) * (m[2][2] - q) + 2.0 * p1;
  const double p = std::sqrt(p2 / 6.0);
  const glm::dmat3 b = (1.0 / p) * (m - q * glm::dmat3(1.0));
  const double r = std::clamp(glm::determinant(b) / 2.0, -1.0, 1.0);
  const double phi = std::acos(r) / 3.0;
  return q + 2.0 * p * std::cos(phi);
}

glm::dmat3 cofactor(const glm::dmat3& a) {
  // Columns of cof(a) are the cross products of a's columns (cof(a) = det(a) a^-T when invertible).
  return glm::dmat3(glm::cross(a[1], a[2]), glm::cross(a[2], a[0]), glm::cross(a[0], a[1]));
}

}  // namespace

double maxStretch(const glm::dmat3& a) {
  return std::sqrt(std::max(largestEigenvalue(glm::transpose(a) * a), 0.0));
}

double maxAreaScale(const glm::dmat3& a) { return maxStretch(cofactor(a)); }

}  // namespace lzb
