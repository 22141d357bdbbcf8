#include "src/zbuffer/mesh_buffers.hpp"

#include <algorithm>

#include "src/zbuffer/gl_api.hpp"

namespace lzb::gl {

MeshBuffers::~MeshBuffers() {
  if (!buffers_.empty()) api().DeleteBuffers(GLsizei(buffers_.size()), buffers_.data());
}

void MeshBuffers::upload(const Mesh& mesh) {
  const Api& g = api();
  triangles_ = mesh.size();
  const uint64_t chunks = (triangles_ + kChunkTriangles - 1) / kChunkTriangles;
  buffers_.assign(chunks, 0);
  if (chunks) g.GenBuffers(GLsizei(chunks), buffers_.data());
  for (uint64_t c = 0; c < chunks; ++c) {
    const uint64_t first = c * kChunkTriangles;
    const uint64_t count = std::min(kChunkTriangles, triangles_ - first);
    g.BindBuffer(GL_ARRAY_BUFFER, buffers_[c]);
    g.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(count * 3 * sizeof(glm::vec3)),
                 mesh.positions.data() + 3 * first, GL_STATIC_DRAW);
  }
  check("uploading a mesh (out of memory?)");
  uploaded_ = true;
}

int MeshBuffers::draw(const IdProgram& program, uint64_t first, uint64_t count,
                      uint64_t firstId) const {
  const Api& g = api();
  int calls = 0;
  const uint64_t end = std::min(first + count, triangles_);
  while (first < end) {
    const uint64_t chunk = first / kChunkTriangles, offset = first % kChunkTriangles;
    const uint64_t n = std::min(end - first, kChunkTriangles - offset);
    g.BindBuffer(GL_ARRAY_BUFFER, buffers_[chunk]);
    g.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    // gl_PrimitiveID restarts at 0 in each draw call, so the base names this call's first one.
    program.setIdBase(firstId);
    g.DrawArrays(GL_TRIANGLES, GLint(3 * offset), GLsizei(3 * n));
    first += n;
    firstId += n;
    ++calls;
  }
  return calls;
}

}  // namespace lzb::gl
