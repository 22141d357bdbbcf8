#pragma once
// One node's triangle positions in GL vertex buffers (unindexed, 3 vertices per triangle), split
// into chunks so no buffer or draw call exceeds GL's 32-bit counts. Needs a current context and
// a vertex array with attribute 0 enabled.
#include <cstdint>
#include <span>
#include <vector>

#include "src/core/scene.hpp"
#include "src/zbuffer/id_program.hpp"
#include "src/zbuffer/list_indices.hpp"

namespace lzb::gl {

class MeshBuffers {
 public:
  static constexpr uint64_t kChunkTriangles = uint64_t(1) << 22;  // 48 MiB of positions

  MeshBuffers() = default;
  ~MeshBuffers();
  MeshBuffers(const MeshBuffers&) = delete;
  MeshBuffers& operator=(const MeshBuffers&) = delete;

  bool uploaded() const { return uploaded_; }
  uint64_t triangles() const { return triangles_; }
  void upload(const Mesh& mesh);
  // Draws triangles [first, first + count) (clamped to the mesh); triangle `first` gets ID
  // firstId. Returns the number of draw calls made.
  int draw(const IdProgram& program, uint64_t first, uint64_t count, uint64_t firstId) const;
  // Draws the listed triangles (each < triangles(); else std::out_of_range before drawing);
  // triangle t gets ID idBase + t. Draw order: chunk by chunk, list order within a chunk (so an
  // ascending list is drawn in its order). Returns the number of draw calls made.
  int drawList(const IdProgram& program, std::span<const uint32_t> list, uint64_t idBase,
               ListIndices& indices) const;

 private:
  // Binds chunk c's vertices to attribute 0.
  void bindChunk(uint64_t c) const;
  // Draws a list of triangles of chunk c given as indices within the chunk.
  int drawChunkList(const IdProgram& program, uint64_t c, std::span<const uint32_t> local,
                    uint64_t idBase, ListIndices& indices) const;

  std::vector<unsigned> buffers_;  // chunk c holds triangles [c * kChunkTriangles, ...)
  uint64_t triangles_ = 0;
  bool uploaded_ = false;
};

}  // namespace lzb::gl
