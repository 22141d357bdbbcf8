#pragma once
// One node's triangle positions in GL vertex buffers (unindexed, 3 vertices per triangle), split
// into chunks so no buffer or draw call exceeds GL's 32-bit counts. Needs a current context.
#include <cstdint>
#include <vector>

#include "src/core/scene.hpp"
#include "src/zbuffer/id_program.hpp"

namespace lzb::gl {

class MeshBuffers {
 public:
  static constexpr uint64_t kChunkTriangles = uint64_t(1) << 22;  // 48 MiB of positions

  MeshBuffers() = default;
  ~MeshBuffers();
  MeshBuffers(const MeshBuffers&) = delete;
  MeshBuffers& operator=(const MeshBuffers&) = delete;

  bool uploaded() const { return uploaded_; }
  void upload(const Mesh& mesh);
  // Draws triangles [first, first + count) with a vertex array bound; triangle `first` gets ID
  // firstId. Returns the number of draw calls made.
  int draw(const IdProgram& program, uint64_t first, uint64_t count, uint64_t firstId) const;

 private:
  std::vector<unsigned> buffers_;  // chunk c holds triangles [c * kChunkTriangles, ...)
  uint64_t triangles_ = 0;
  bool uploaded_ = false;
};

}  // namespace lzb::gl
