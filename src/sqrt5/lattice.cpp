#include "src/sqrt5/lattice.hpp"

namespace lzb::sqrt5 {

Sqrt5Lattice::Sqrt5Lattice(int n) : n_(n) {
  u_[0] = {1.0 / n, 0.0};
  v_[0] = {0.0, 1.0 / n};
  for (size_t i = 0; i + 1 < u_.size(); ++i) {
    u_[i + 1] = (2.0 * u_[i] + v_[i]) / 5.0;
    v_[i + 1] = (-u_[i] + 2.0 * v_[i]) / 5.0;
  }
}

std::array<glm::dvec2, 4> Sqrt5Lattice::offsets(const glm::dvec2& p, int level) const {
  const glm::dvec2 &a = u(level), &b = v(level);
  return {p + a, p - a, p + b, p - b};
}

void Sqrt5Lattice::children(const glm::dvec2& p, int level, std::vector<glm::dvec2>& out) const {
  for (const glm::dvec2& c : offsets(p, level + 1))
    if (inside(c)) out.push_back(c);
  for (const glm::dvec2& q : offsets(p, level)) {
    if (inside(q)) continue;
    for (const glm::dvec2& c : offsets(q, level + 1)) {
      if (!inside(c)) continue;
      // The inside neighbour of q nearest to c (the first in offsets() order on a tie) owns it.
      double best = 1e300;
      glm::dvec2 owner(0.0);
      for (const glm::dvec2& r : offsets(q, level)) {
        if (!inside(r)) continue;
        const glm::dvec2 d = r - c;
        const double d2 = glm::dot(d, d);
        if (d2 < best * (1.0 - 1e-9)) best = d2, owner = r;
      }
      const glm::dvec2 d = owner - p;
      if (glm::dot(d, d) <= 1e-18 * glm::dot(u(level), u(level))) out.push_back(c);
    }
  }
}

}  // namespace lzb::sqrt5
