#pragma once
// The tests' slow, obviously right ray caster: every world-space triangle against a ray in
// double precision (Möller–Trumbore), the witness the fast ray walks are checked against.
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <vector>

#include "src/core/scene.hpp"

namespace lzb::test {

struct WorldTriangle {
  glm::dvec3 a, b, c;
  uint64_t id;
};

// Every triangle of the flattened scene in world space, with its expanded ID.
std::vector<WorldTriangle> worldTriangles(const Scene& scene);

struct BruteHit {
  double t = std::numeric_limits<double>::infinity();
  double margin = 0.0;  // smallest barycentric coordinate: how far inside the triangle
  uint64_t id = kNoId;
};

// Möller–Trumbore in double; margin < 0 means the ray passes outside by that much.
BruteHit mollerTrumbore(const WorldTriangle& tri, const glm::dvec3& o, const glm::dvec3& d);

// The nearest triangle hit with t in [tnear, tfar].
BruteHit bruteForce(const std::vector<WorldTriangle>& tris, const glm::dvec3& o,
                    const glm::dvec3& d, double tnear, double tfar);

const WorldTriangle* findTriangle(const std::vector<WorldTriangle>& tris, uint64_t id);

}  // namespace lzb::test
