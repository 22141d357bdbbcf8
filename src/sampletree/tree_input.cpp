#include "src/sampletree/tree_input.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "src/core/error.hpp"

namespace lzb::sampletree {

double triangleArea(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::dvec3 da(a), db(b), dc(c);
  return 0.5 * glm::length(glm::cross(db - da, dc - da));
}

double TriangleInput::area(size_t t) const {
  return triangleArea(vertex(t, 0), vertex(t, 1), vertex(t, 2));
}

void TriangleInput::add(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, uint64_t id,
                        Rgba8 colour) {
  positions.insert(positions.end(), {a, b, c});
  ids.push_back(id);
  colours.push_back(colour);
}

void requireFloatResolves(const Scene& scene) { requireFloatResolves(scene.bounds(), scene.source); }

void requireFloatResolves(const Bounds& b, const std::string& where) {
  if (b.empty()) return;
  const glm::dvec3 far = glm::max(glm::abs(b.lo), glm::abs(b.hi));
  const double reach = std::max({far.x, far.y, far.z}), size = b.diagonal();
  // Float world coordinates round by half an ulp at the scene's farthest coordinate.
  const double rounding = reach * std::ldexp(1.0, -24);
  require(rounding <= kMaxFloatRounding * size, where,
          "the scene lies too far from the origin for the sample tree's float world coordinates "
          "(farthest coordinate " + std::to_string(reach) + ", size " + std::to_string(size) +
              "): recentre it (cell-relative storage is not implemented yet)");
}

TriangleInput gatherTriangles(const Scene& scene, uint64_t limit) {
  const uint64_t n = scene.expandedTriangles();
  require(n <= limit, scene.source,
          std::to_string(n) + " expanded triangles, more than the sample tree builds in memory (" +
              std::to_string(limit) + "; build it out of core: `lzb build-tree --mem-mb M`)");
  requireFloatResolves(scene);
  TriangleInput in;
  in.positions.reserve(3 * n);
  in.ids.reserve(n);
  in.colours.reserve(n);
  SceneStream(scene).forEach([&](std::span<const StreamTriangle> batch) {
    for (const StreamTriangle& t : batch) in.add(t);
  });
  return in;
}

}  // namespace lzb::sampletree
