#pragma once
// The tests' hand-built scenes: a quad, random triangles, instances nested three levels deep, a
// translated copy, spheres.
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <vector>

#include "src/core/scene.hpp"
#include "src/surfels/surfel_renderer.hpp"

namespace lzb::test {

Rgba8 grey(uint8_t v);

// The quad [-1, 1]^2 at z = 0 as triangle 0 (below the diagonal y = x) and 1 (above).
void addQuad(Mesh& mesh);
Scene quadScene();

// Random triangles of about `size` inside [-1, 1]^3 until the mesh holds `count`.
void addRandomTriangles(Mesh& mesh, size_t count, double size, std::mt19937_64& rng);

// One node "soup" of `triangles` random triangles of about `size` (addRandomTriangles), finalized.
Scene soupScene(size_t triangles, double size, uint64_t seed);

// Rotation about a random axis, non-uniform scale in [lo, hi], translation in [-1, 1]^3.
glm::dmat4 randomTransform(std::mt19937_64& rng, double lo, double hi);

// Instances three levels deep: root -> B -> A -> leaf, every node with triangles of its own.
Scene nestedScene(uint64_t seed = 7);

// `inner` placed under a new root by one translation: the same expanded IDs (offset 0).
Scene translated(const Scene& inner, const glm::dvec3& t);

// One closed sphere node placed at each of `centres` with radius `radius` (inline: the sphere
// mesh is the surfel method's, linked by the tests that use it).
inline Scene spheres(const std::vector<glm::dvec3>& centres, double radius = 1.0) {
  Scene s;
  s.source = "test spheres";
  s.root = s.addNode("root");
  const uint32_t ball = s.addNode("ball");
  s.nodes[ball].mesh = surfels::uvSphere(48, 24);
  for (const glm::dvec3& c : centres)
    s.nodes[s.root].instances.push_back(
        {ball, glm::scale(glm::translate(glm::dmat4(1.0), c), glm::dvec3(radius))});
  s.finalize();
  return s;
}

}  // namespace lzb::test
