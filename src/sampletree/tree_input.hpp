#pragma once
// The triangles a sample tree is built from: the scene's expanded triangles in world space, with
// instances flattened (this milestone builds in memory; a scene above kMaxInCoreTriangles is
// refused rather than swapping).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "src/core/bounds.hpp"
#include "src/core/color.hpp"
#include "src/core/scene.hpp"
#include "src/sampletree/triangle_stream.hpp"

namespace lzb::sampletree {

// 2^24 expanded triangles: 48 bytes each in the input, as much again in the tree, and the octree's
// index lists stay under ~2 GB.
constexpr uint64_t kMaxInCoreTriangles = uint64_t(1) << 24;

// A triangle's area from its float vertices, in double: the one the build samples by.
double triangleArea(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

struct TriangleInput {
  std::vector<glm::vec3> positions;  // world, 3 per triangle
  std::vector<uint64_t> ids;         // expanded IDs
  std::vector<Rgba8> colours;

  size_t size() const { return ids.size(); }
  const glm::vec3& vertex(size_t t, int k) const { return positions[3 * t + size_t(k)]; }
  double area(size_t t) const;
  void add(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, uint64_t id, Rgba8 colour);
  void add(const StreamTriangle& t) { add(t.v[0], t.v[1], t.v[2], t.id, t.colour); }
  // Appends triangle t of `from`.
  void addFrom(const TriangleInput& from, size_t t) {
    add(from.vertex(t, 0), from.vertex(t, 1), from.vertex(t, 2), from.ids[t], from.colours[t]);
  }
};

// The tree stores world coordinates as floats: a scene whose float rounding exceeds this fraction
// of its size (e.g. a small scene 1e8 from the origin) is refused with exit status 2.
constexpr double kMaxFloatRounding = 1e-4;
void requireFloatResolves(const Scene& scene);
// The same for a scene known by its bounds (a stream's); `where` names it.
void requireFloatResolves(const Bounds& bounds, const std::string& where);

// Every expanded triangle of the scene in expanded-ID order; throws InputError naming the scene
// when it has more than `limit` of them.
TriangleInput gatherTriangles(const Scene& scene, uint64_t limit = kMaxInCoreTriangles);

}  // namespace lzb::sampletree
