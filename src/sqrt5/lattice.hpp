#pragma once
// The sqrt(5) sampling lattice of Stamminger & Drettakis, section 3.1, over the unit square of a
// procedural object's (u, v) parameters.
//
// Level 0 is a uniform grid of step h = 1 / n: the (n + 1)^2 points (i h, j h), spanned by
// u_0 = (h, 0), v_0 = (0, h). Refining a point p of level i inserts p + u_{i+1}, p - u_{i+1},
// p + v_{i+1}, p - v_{i+1} (and keeps p itself, the "self copy"), with
//   u_{i+1} = (2 u_i + v_i) / 5,   v_{i+1} = (-u_i + 2 v_i) / 5.
// (The paper's text extraction reads "2u_i/sqrt5 + v_i/sqrt5", which keeps |u| = h and never
// refines; dividing by 5 gives the step h / sqrt(5)^i and the rotation by atan(1/2) per level
// that the paper states, and makes level i a sublattice of index 5 of level i + 1:
// u_i = 2 u_{i+1} - v_{i+1}, v_i = u_{i+1} + 2 v_{i+1}.) So every point of level i + 1 has exactly
// one parent at level i, and the points refined to level i are the level-i lattice.
//
// Boundary children (section 3.1, Fig. 3e): the descendants of the lattice points outside the
// square form fractals reaching into it, which no inside point would ever generate. When p of
// level i is refined, each neighbour q = p +- u_i, p +- v_i outside the square contributes those
// of its four children inside the square, attached to the one inside neighbour of q (among
// q +- u_i, q +- v_i) nearest to the child, so that each is attached once.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace lzb::sqrt5 {

// The deepest refinement level (spacing h / sqrt(5)^16 = h / 390625); --sqrt5-levels is at most
// this.
constexpr int kMaxLevels = 16;

class Sqrt5Lattice {
 public:
  // Spawning vectors of every level for the initial step h = 1 / n.
  explicit Sqrt5Lattice(int n);
  int initialSide() const { return n_; }
  const glm::dvec2& u(int level) const { return u_[size_t(level)]; }
  const glm::dvec2& v(int level) const { return v_[size_t(level)]; }
  // Level 0's point (i, j), i, j in [0, n].
  glm::dvec2 root(int i, int j) const { return {double(i) / n_, double(j) / n_}; }
  // p + u_level, p - u_level, p + v_level, p - v_level.
  std::array<glm::dvec2, 4> offsets(const glm::dvec2& p, int level) const;
  // Appends the children of p (refined from `level` to level + 1) inside the square: its four
  // offsets, then the boundary children attached to it.
  void children(const glm::dvec2& p, int level, std::vector<glm::dvec2>& out) const;

  static bool inside(const glm::dvec2& p) {
    constexpr double e = 1e-12;
    return p.x >= -e && p.x <= 1.0 + e && p.y >= -e && p.y <= 1.0 + e;
  }

 private:
  int n_;
  std::array<glm::dvec2, kMaxLevels + 2> u_, v_;
};

}  // namespace lzb::sqrt5
