#include "src/sampletree/tree_input.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "src/core/error.hpp"

namespace lzb::sampletree {

double TriangleInput::area(size_t t) const {
  const glm::dvec3 a(vertex(t, 0)), b(vertex(t, 1)), c(vertex(t, 2));
  return 0.5 * glm::length(glm::cross(b - a, c - a));
}

void TriangleInput::add(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, uint64_t id,
                        Rgba8 colour) {
  positions.insert(positions.end(), {a, b, c});
  ids.push_back(id);
  colours.push_back(colour);
}

void requireFloatResolves(const Scene& scene) {
  const Bounds& b = scene.bounds();
  if (b.empty()) return;
  const glm::dvec3 far = glm::max(glm::abs(b.lo), glm::abs(b.hi));
  const double reach = std::max({far.x, far.y, far.z}), size = b.diagonal();
  // Float world coordinates round by half an ulp at the scene's farthest coordinate.
  const double rounding = reach * std::ldexp(1.0, -24);
  require(rounding <= kMaxFloatRounding * size, scene.source,
          "the scene lies too far from the origin for the sample tree's float world coordinates "
          "(farthest coordinate " + std::to_string(reach) + ", size " + std::to_string(size) +
              "): recentre it (cell-relative storage is not implemented yet)");
}

TriangleInput gatherTriangles(const Scene& scene, uint64_t limit) {
  const uint64_t n = scene.expandedTriangles();
  require(n <= limit, scene.source,
          std::to_string(n) + " expanded triangles, more than the sample tree builds in memory (" +
              std::to_string(limit) + "; out-of-core construction is not implemented yet)");
  requireFloatResolves(scene);
  TriangleInput in;
  in.positions.reserve(3 * n);
  in.ids.reserve(n);
  in.colours.reserve(n);
  for (const DrawItem& item : flattenScene(scene)) {
    const Mesh& mesh = scene.nodes[item.node].mesh;
    for (size_t t = 0; t < mesh.size(); ++t) {
      glm::vec3 w[3];
      for (int k = 0; k < 3; ++k)
        w[k] = glm::vec3(item.transform * glm::dvec4(glm::dvec3(mesh.vertex(t, k)), 1.0));
      in.add(w[0], w[1], w[2], item.idBase + t, mesh.colors[t]);
    }
  }
  return in;
}

}  // namespace lzb::sampletree
