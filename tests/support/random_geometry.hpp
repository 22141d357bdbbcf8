#pragma once
// Random geometry for the octree and sample-tree tests (inline: over those folders' own types,
// linked by the tests that use them).
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <random>
#include <vector>

#include "src/core/scene.hpp"
#include "src/octree/octree.hpp"
#include "src/sampletree/tree_input.hpp"

namespace lzb::test {

// n triangles in [-1, 1]^3: most small, in a few dense blobs (so the tree gets deep), and a
// fraction `large` spanning a good part of the region (so triangles cross many leaves).
inline Mesh randomMesh(size_t n, uint64_t seed, double large = 0.02) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<glm::dvec3> blobs(6);
  for (glm::dvec3& b : blobs) b = 0.6 * glm::dvec3{u(rng), u(rng), u(rng)};
  Mesh mesh;
  while (mesh.size() < n) {
    glm::dvec3 at;
    double size;
    if (unit(rng) < large) {
      at = 0.5 * glm::dvec3{u(rng), u(rng), u(rng)};
      size = 0.3 + 0.4 * unit(rng);
    } else if (unit(rng) < 0.7) {
      at = blobs[rng() % blobs.size()] + 0.08 * glm::dvec3{gauss(rng), gauss(rng), gauss(rng)};
      size = 0.004 + 0.01 * unit(rng);
    } else {
      at = 0.9 * glm::dvec3{u(rng), u(rng), u(rng)};
      size = 0.01 + 0.05 * unit(rng);
    }
    const auto corner = [&] {
      return glm::vec3(glm::clamp(at + size * glm::dvec3{u(rng), u(rng), u(rng)}, -1.0, 1.0));
    };
    const glm::vec3 a = corner(), b = corner(), c = corner();
    mesh.add(a, b, c, packRgba8(200, 200, 200));
  }
  return mesh;
}

// Corner k of triangle t in double.
inline glm::dvec3 vertex(const Mesh& m, uint32_t t, int k) {
  return glm::dvec3(m.vertex(t, k));
}

// Non-empty leaves of an octree, by node index.
inline std::vector<uint32_t> nonEmptyLeaves(const Octree& tree) {
  std::vector<uint32_t> out;
  for (uint32_t i = 0; i < tree.nodeCount(); ++i)
    if (tree.node(i).leaf() && tree.node(i).count) out.push_back(i);
  return out;
}

// A random rigid motion with uniform scale, optionally mirrored.
inline glm::dmat4 randomRigidMotion(std::mt19937_64& rng, bool mirror) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  glm::dvec3 axis{u(rng), u(rng), u(rng)};
  axis = glm::normalize(axis + glm::dvec3(1e-3));
  const double angle = 3.0 * u(rng), s = 0.5 + 2.0 * std::abs(u(rng));
  const double c = std::cos(angle), sn = std::sin(angle), t = 1.0 - c;
  const glm::dvec3 a = axis;
  glm::dmat3 r{t * a.x * a.x + c,        t * a.x * a.y + sn * a.z, t * a.x * a.z - sn * a.y,
               t * a.x * a.y - sn * a.z, t * a.y * a.y + c,        t * a.y * a.z + sn * a.x,
               t * a.x * a.z + sn * a.y, t * a.y * a.z - sn * a.x, t * a.z * a.z + c};
  glm::dmat4 m(r * s);
  if (mirror) m[0] = -m[0];
  m[3] = glm::dvec4(5.0 * u(rng), 5.0 * u(rng), 5.0 * u(rng), 1.0);
  return m;
}

// n triangles scattered in the unit cube, sides up to `maxSide`, colours and IDs in order.
inline sampletree::TriangleInput scatteredTriangles(size_t n, float maxSide, uint32_t seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), offset(-maxSide, maxSide);
  sampletree::TriangleInput in;
  for (size_t t = 0; t < n; ++t) {
    const glm::vec3 a(unit(rng), unit(rng), unit(rng));
    const glm::vec3 b = a + glm::vec3(offset(rng), offset(rng), offset(rng));
    const glm::vec3 c = a + glm::vec3(offset(rng), offset(rng), offset(rng));
    in.add(a, b, c, t, Rgba8(rng()) | 0xff000000u);
  }
  return in;
}

}  // namespace lzb::test
