#include "tests/support/brute_force.hpp"

#include <algorithm>

namespace lzb::test {

std::vector<WorldTriangle> worldTriangles(const Scene& scene) {
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

BruteHit mollerTrumbore(const WorldTriangle& tri, const glm::dvec3& o, const glm::dvec3& d) {
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

BruteHit bruteForce(const std::vector<WorldTriangle>& tris, const glm::dvec3& o,
                    const glm::dvec3& d, double tnear, double tfar) {
  BruteHit best;
  for (const WorldTriangle& tri : tris) {
    const BruteHit h = mollerTrumbore(tri, o, d);
    if (h.margin >= 0.0 && h.t >= tnear && h.t <= tfar && h.t < best.t) best = h;
  }
  return best;
}

const WorldTriangle* findTriangle(const std::vector<WorldTriangle>& tris, uint64_t id) {
  for (const WorldTriangle& tri : tris)
    if (tri.id == id) return &tri;
  return nullptr;
}

}  // namespace lzb::test
