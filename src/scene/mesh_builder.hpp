#pragma once
// Appends triangles given in double precision to a Mesh and counts what it drops, so generators
// and loaders share one path into the scene model. A corner equal to the last bit (after rounding
// to float) to one met recently is stored once and shared, whatever the input's own indexing:
// every method sees the same floats as if stored three a triangle, in a fraction of the memory.
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "src/core/bounds.hpp"
#include "src/core/color.hpp"
#include "src/core/scene.hpp"

namespace lzb {

class MeshBuilder {
 public:
  // `mesh` may be emptied between triangles (a streamed chunk handed out): the builder then starts
  // sharing afresh.
  MeshBuilder(Mesh& mesh, LoadStats& stats) : mesh_(mesh), stats_(stats) {}

  // Returns false (and counts the reason) when the triangle is not finite or is degenerate after
  // rounding to float.
  bool triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, Rgba8 color);
  // Two triangles (a, b, c) and (a, c, d), wound so their normal points along `outward`.
  void quad(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d,
            const glm::dvec3& outward, Rgba8 color);
  // The faces of an axis-aligned box with outward normals: 12 triangles, or 10 without the
  // bottom face (for boxes standing on something).
  void box(const Bounds& b, Rgba8 color, bool bottom = true);
  // A closed unit sphere about the z axis, `slices` around it and `stacks` pole to pole:
  // 2 * slices * (stacks - 1) triangles (one fan triangle per slice at each pole), normals outward.
  void sphere(int slices, int stacks, Rgba8 color);

 private:
  using Bits = std::array<uint32_t, 3>;
  struct Slot {
    Bits bits{};
    uint32_t vertex = ~uint32_t(0);  // none
  };
  // Recent corners by a hash of their bits, one per slot: a direct-mapped cache, not a map of
  // every vertex, so a 10^7-triangle load stays within cache (a corner evicted before it recurs
  // is stored twice, which costs memory, never correctness). 2^16 slots cover a grid's next row.
  static constexpr uint32_t kSlotBits = 16;
  uint32_t shared(const glm::vec3& p);

  Mesh& mesh_;
  LoadStats& stats_;
  std::vector<Slot> recent_;
};

}  // namespace lzb
