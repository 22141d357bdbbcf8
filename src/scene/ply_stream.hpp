#pragma once
// A PLY mesh read for streaming, never whole: the vertex element is held (12 bytes a vertex, 24
// with colours), the faces are read from the file in chunks on every pass. Binary files, and
// ASCII ones where every value reads as the loader reads it (ply_text_reader.hpp). The
// triangles, their order, colours and dropped ones are those `loadScene` makes of the file (the
// same face rules, mesh_faces.hpp); so are the stored frame and its placement (recentred far
// geometry). For the sample tree's external construction (src/sampletree/external_build.hpp).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "src/core/scene.hpp"
#include "src/scene/ply_header.hpp"

namespace lzb {

class PlyMeshStream {
 public:
  // Opens `path` and reads it once: the header, the vertices, every face checked and split (the
  // count of kept and dropped triangles), the elements after the faces checked for length.
  // Returns nullptr with `why` set for a file that the loader (assimp) reads otherwise than this
  // reader would, or that it does not stream (triangle strips, no faces, an ASCII value it cannot
  // be sure to read as the loader does...): the caller
  // then loads it. Throws InputError naming the file for a missing, unreadable, truncated or
  // malformed one (an index out of range, a face without vertices, no valid triangle). An ASCII
  // file is read whole once here, so a file left to the loader costs one more reading.
  static std::unique_ptr<PlyMeshStream> open(const std::filesystem::path& path, std::string& why);

  const std::string& where() const { return where_; }
  uint64_t triangles() const { return stats_.loaded; }
  const LoadStats& stats() const { return stats_; }
  // What the stream holds while open: the vertex element (positions, colours).
  uint64_t heldBytes() const {
    return (positions_.capacity() + colours_.capacity()) * sizeof(glm::vec3);
  }
  // Stored frame -> world, as the loaded scene places the file's triangles (flattenScene).
  const glm::dmat4& placement() const { return placement_; }
  // Hands out the triangles in file order (the loaded scene's ID order) in meshes of about
  // `chunk` triangles, in the stored frame. Throws InputError if the file changed under it.
  void forEachChunk(const std::function<void(const Mesh&)>& out, size_t chunk = 1 << 16) const;

  struct Layout;  // where the properties lie (ply_stream.cpp)
  ~PlyMeshStream();

 private:
  PlyMeshStream() = default;
  bool binary() const { return header_.format != "ascii"; }
  template <class Reader>
  void scan();
  template <class Reader>
  void readVertices(Reader& in, const PlyElement& element);
  // Reads, checks and splits every face, handing out chunks; returns what was kept and dropped.
  template <class Reader>
  LoadStats readFaces(Reader& in, const std::function<void(const Mesh&)>& out, size_t chunk) const;
  template <class Reader>
  Reader reader(uint64_t offset) const;

  std::filesystem::path path_;
  std::string where_;
  PlyHeader header_;
  std::unique_ptr<Layout> layout_;
  std::vector<glm::vec3> positions_, colours_;
  glm::dvec3 origin_{0.0};
  glm::dmat4 placement_{1.0};
  uint64_t faceData_ = 0;  // file offset of the face element's data
  LoadStats stats_;
};

}  // namespace lzb
