#pragma once
// An OFF mesh streamed (mesh_stream.hpp) where the loader (assimp 5.2's OFF reader) is certain to
// read the same: the keyword OFF, COFF, NOFF or CNOFF on a line of its own (comments and blank
// lines before it and before the counts), the three counts on one line, each vertex on a line of
// its own (x y z, then nx ny nz with N, then r g b a with C; anything after is never read), each
// face a line "k i1 .. ik" with 1 <= k <= 9 and every index a vertex (face colours after it are
// never read), blank lines between them, every number one whole token (text_tokens.hpp). Anything
// else is left to the loader, which refuses what its file check refuses.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "src/scene/mesh_stream.hpp"
#include "src/scene/text_tokens.hpp"

namespace lzb {

class OffMeshStream : public MeshStream {
 public:
  static std::unique_ptr<OffMeshStream> open(const std::filesystem::path& path, std::string& why);

 private:
  explicit OffMeshStream(const std::filesystem::path& path) : MeshStream(path) {}
  // The header: the keyword's letters and the counts; leaves `lines` at the first vertex line.
  void readHeader(TextLines& lines);
  void readVertices(TextLines& lines);
  void readFaces(FaceChunks& faces) const override;

  bool colours_ = false, normals_ = false;
  uint64_t vertices_ = 0, faces_ = 0;
  uint64_t faceData_ = 0;  // file offset of the first face line
};

}  // namespace lzb
