#pragma once
// An OBJ mesh streamed (mesh_stream.hpp) where the loader (assimp 5.2's OBJ reader) is certain to
// give one mesh of the file's faces in file order: lines of `v` (3 values, or 6 with a colour,
// the same on every line), `vn`, `vt`, `f`, `s` and comments, with `o` and `g` only before the
// first face, every keyword at the start of its line; each number one whole token
// (text_tokens.hpp); face corners v, v/t, v/t/n or v//n with indices written plainly (no sign but
// a minus, no leading zero: assimp steps over the digits it counts), a vertex index naming a `v`
// (a negative one counted back from the `v` lines before it). Materials (`mtllib`, `usemtl`),
// lines and points, line continuations and other statements are left to the loader.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

#include "src/scene/mesh_stream.hpp"
#include "src/scene/text_tokens.hpp"

namespace lzb {

class ObjMeshStream : public MeshStream {
 public:
  static std::unique_ptr<ObjMeshStream> open(const std::filesystem::path& path, std::string& why);

 private:
  explicit ObjMeshStream(const std::filesystem::path& path) : MeshStream(path) {}
  // Every line checked; the vertices kept; where the faces start.
  void scan();
  void readVertex(std::string_view values, Bounds& bounds);
  void readFaces(FaceChunks& faces) const override;

  uint64_t faceData_ = 0;        // file offset of the first face line
  uint64_t verticesBefore_ = 0;  // `v` lines before it
};

}  // namespace lzb
