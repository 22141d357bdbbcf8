#pragma once
// How a mesh file's faces become stored triangles: where its geometry is stored around, a face
// split into coloured triangles. Shared by the assimp loader (mesh_file.cpp) and the streaming PLY
// reader (ply_stream.hpp), so that both make the same triangles bit for bit.
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "src/core/bounds.hpp"
#include "src/core/color.hpp"
#include "src/scene/mesh_builder.hpp"
#include "src/scene/triangulate.hpp"

namespace lzb {

// The origin a file's geometry is stored around, from the bounds of its finite vertices (in the
// file's frame): their centre when it lies more than 1000 x their size from the origin, else 0.
glm::dvec3 storageOrigin(const Bounds& finiteVertices);

// A file vertex placed by `transform` (file node -> file frame), relative to the storage origin.
glm::dvec3 storedVertex(const glm::dmat4& transform, float x, float y, float z,
                        const glm::dvec3& origin);

// A triangle's colour from its corners' vertex colours (components in [0, 1]): their mean.
Rgba8 meanColour(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

// Splits one face (its stored vertices in `polygon`) by ear clipping and hands each piece to the
// builder, coloured by colourOf(corner indices into polygon); the builder drops and counts
// degenerate and non-finite pieces. Faces of fewer than 3 vertices count as degenerate.
class FaceSplitter {
 public:
  std::vector<glm::dvec3> polygon;

  template <class ColourOf>
  void split(MeshBuilder& builder, LoadStats& stats, ColourOf&& colourOf) {
    if (polygon.size() < 3) {  // points and lines have no area
      ++stats.degenerate;
      return;
    }
    pieces_.clear();
    triangulatePolygon(polygon, pieces_);
    for (const auto& t : pieces_)
      builder.triangle(polygon[t[0]], polygon[t[1]], polygon[t[2]], colourOf(t));
  }

 private:
  std::vector<std::array<uint32_t, 3>> pieces_;
};

}  // namespace lzb
