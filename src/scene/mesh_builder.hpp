#pragma once
// Appends triangles given in double precision to a Mesh and counts what it drops, so generators
// and loaders share one path into the scene model.
#include <glm/glm.hpp>

#include "src/core/bounds.hpp"
#include "src/core/color.hpp"
#include "src/core/scene.hpp"

namespace lzb {

class MeshBuilder {
 public:
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
  Mesh& mesh_;
  LoadStats& stats_;
};

}  // namespace lzb
