#pragma once
// Hand-built scenes and a brute-force double-precision ray caster for the raycast tests.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "src/core/camera.hpp"
#include "src/core/scene.hpp"

namespace lzb::testing {

inline Rgba8 grey(uint8_t v) {
  return packRgba8(v, v, v, 255);
}

// The quad [-1, 1]^2 at z = 0 as triangle 0 (below the diagonal y = x) and 1 (above).
inline void addQuad(Mesh& mesh) {
  mesh.add({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, grey(200));
  mesh.add({-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, grey(100));
}

inline Scene quadScene() {
  Scene s;
  s.source = "quad";
  s.addNode("quad");
  addQuad(s.nodes[0].mesh);
  s.finalize();
  return s;
}

// Random triangles of about `size` inside [-1, 1]^3.
inline void addRandomTriangles(Mesh& mesh, size_t count, double size, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  while (mesh.size() < count) {
    const glm::dvec3 c(u(rng), u(rng), u(rng));
    auto corner = [&] { return glm::vec3(c + size * glm::dvec3(u(rng), u(rng), u(rng))); };
    mesh.add(corner(), corner(), corner(), packRgba8(uint8_t(rng()), uint8_t(rng()), 128, 255));
  }
}

// Rotation about a random axis, non-uniform scale in [lo, hi], translation in [-1, 1]^3.
inline glm::dmat4 randomTransform(std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), s(lo, hi), a(0.0, 6.283185307179586);
  glm::dvec3 axis(u(rng), u(rng), u(rng));
  if (glm::length(axis) < 1e-3) axis = {0, 0, 1};
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(u(rng), u(rng), u(rng)));
  m = glm::rotate(m, a(rng), glm::normalize(axis));
  return glm::scale(m, glm::dvec3(s(rng), s(rng), s(rng)));
}

// Instances three levels deep: root -> B -> A -> leaf, every node with triangles of its own.
inline Scene nestedScene(uint64_t seed = 7) {
  std::mt19937_64 rng(seed);
  Scene s;
  s.source = "nested";
  const uint32_t root = s.addNode("root"), b = s.addNode("B"), a = s.addNode("A"),
                 leaf = s.addNode("leaf");
  s.root = root;
  addRandomTriangles(s.nodes[leaf].mesh, 200, 0.6, rng);
  addRandomTriangles(s.nodes[a].mesh, 20, 0.5, rng);
  for (int i = 0; i < 3; ++i)
    s.nodes[a].instances.push_back({leaf, randomTransform(rng, 0.5, 0.9)});
  addRandomTriangles(s.nodes[b].mesh, 10, 0.3, rng);
  for (int i = 0; i < 2; ++i) s.nodes[b].instances.push_back({a, randomTransform(rng, 0.6, 0.9)});
  s.nodes[b].instances.push_back({leaf, randomTransform(rng, 0.3, 0.5)});
  addRandomTriangles(s.nodes[root].mesh, 10, 0.3, rng);
  for (int i = 0; i < 2; ++i)
    s.nodes[root].instances.push_back({b, randomTransform(rng, 0.7, 1.0)});
  s.nodes[root].instances.push_back({a, randomTransform(rng, 0.6, 0.9)});
  s.nodes[root].instances.push_back({leaf, randomTransform(rng, 0.3, 0.5)});
  s.finalize();
  return s;
}

// `inner` placed under a new root by one translation: the same expanded IDs (offset 0).
inline Scene translated(const Scene& inner, const glm::dvec3& t) {
  Scene s = inner;
  const uint32_t world = s.addNode("world");
  s.nodes[world].instances.push_back({inner.root, glm::translate(glm::dmat4(1.0), t)});
  s.root = world;
  s.finalize();
  return s;
}

// Closer than frameBounds: the bounds of rotated nested boxes are loose, the triangles compact.
inline CameraSpec closeSpec(const Scene& scene) {
  CameraSpec spec = frameBounds(scene.bounds());
  spec.position = spec.lookAt + 0.4 * (spec.position - spec.lookAt);
  spec.nearPlane = 0.05 * glm::length(spec.position - spec.lookAt);
  return spec;
}
inline Camera camera(const Scene& scene, int w, int h) {
  return Camera(closeSpec(scene), w, h);
}

struct WorldTriangle {
  glm::dvec3 a, b, c;
  uint64_t id;
};

inline std::vector<WorldTriangle> worldTriangles(const Scene& scene) {
  std::vector<WorldTriangle> out;
  for (const DrawItem& item : flattenScene(scene)) {
    const Mesh& mesh = scene.nodes[item.node].mesh;
    auto place = [&](size_t t, int k) {
      return glm::dvec3(item.transform * glm::dvec4(glm::dvec3(mesh.vertex(t, k)), 1.0));
    };
    for (size_t t = 0; t < mesh.size(); ++t)
      out.push_back({place(t, 0), place(t, 1), place(t, 2), item.idBase + t});
  }
  return out;
}

struct BruteHit {
  double t = std::numeric_limits<double>::infinity();
  double margin = 0.0;  // smallest barycentric coordinate: how far inside the triangle
  uint64_t id = kNoId;
};

// Möller–Trumbore in double; margin < 0 means the ray passes outside by that much.
inline BruteHit mollerTrumbore(const WorldTriangle& tri, const glm::dvec3& o, const glm::dvec3& d) {
  const glm::dvec3 e1 = tri.b - tri.a, e2 = tri.c - tri.a;
  const glm::dvec3 p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (det == 0.0) return {};
  const glm::dvec3 s = o - tri.a;
  const double u = glm::dot(s, p) / det;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) / det;
  return {glm::dot(e2, q) / det, std::min({u, v, 1.0 - u - v}), tri.id};
}

// The nearest triangle hit with t in [tnear, tfar].
inline BruteHit bruteForce(const std::vector<WorldTriangle>& tris, const glm::dvec3& o,
                           const glm::dvec3& d, double tnear, double tfar) {
  BruteHit best;
  for (const WorldTriangle& tri : tris) {
    const BruteHit h = mollerTrumbore(tri, o, d);
    if (h.margin >= 0.0 && h.t >= tnear && h.t <= tfar && h.t < best.t) best = h;
  }
  return best;
}

inline const WorldTriangle* findTriangle(const std::vector<WorldTriangle>& tris, uint64_t id) {
  for (const WorldTriangle& tri : tris)
    if (tri.id == id) return &tri;
  return nullptr;
}

}  // namespace lzb::testing
