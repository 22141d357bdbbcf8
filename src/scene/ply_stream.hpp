#pragma once
// A PLY mesh streamed (mesh_stream.hpp): binary files, and ASCII ones where every value reads as
// the loader reads it (ply_text_reader.hpp). The triangles, their order, colours and dropped ones
// are those `loadScene` makes of the file (the same face rules, mesh_faces.hpp); so are the stored
// frame and its placement (recentred far geometry).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "src/scene/mesh_stream.hpp"
#include "src/scene/ply_binary.hpp"

namespace lzb {

class PlyMeshStream : public MeshStream {
 public:
  // Opens `path` and reads it once: the header, the vertices, every face checked and split (the
  // count of kept and dropped triangles), the elements after the faces checked for length.
  // Returns nullptr with `why` set for a file that the loader (assimp) reads otherwise than this
  // reader would, or that it does not stream (triangle strips, no faces, an ASCII value it cannot
  // be sure to read as the loader does...): the caller then loads it. Throws InputError naming
  // the file for a missing, unreadable, truncated or malformed one (an index out of range, a face
  // without vertices, no valid triangle).
  static std::unique_ptr<PlyMeshStream> open(const std::filesystem::path& path, std::string& why);

  ~PlyMeshStream() override;

 private:
  explicit PlyMeshStream(const std::filesystem::path& path);
  bool binary() const { return header_.format != "ascii"; }
  template <class Reader>
  Reader reader(uint64_t offset) const;
  template <class Reader>
  void scan();
  template <class Reader>
  void readVertices(Reader& in, const PlyElement& element);
  // Reads, checks and splits every face of the face element where `in` stands.
  template <class Reader>
  void readFaceElement(Reader& in, FaceChunks& faces) const;
  void readFaces(FaceChunks& faces) const override;

  PlyHeader header_;
  PlyMeshLayout layout_;
  uint64_t faceData_ = 0;  // file offset of the face element's data
};

}  // namespace lzb
