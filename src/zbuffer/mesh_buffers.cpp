#include "src/zbuffer/mesh_buffers.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

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
  std::vector<glm::vec3> corners;  // a chunk's triangles unshared: the shader's ID is vertex / 3
  for (uint64_t c = 0; c < chunks; ++c) {
    const uint64_t first = c * kChunkTriangles;
    const uint64_t count = std::min(kChunkTriangles, triangles_ - first);
    corners.resize(3 * count);
    for (uint64_t t = 0; t < count; ++t)
      for (int k = 0; k < 3; ++k) corners[3 * t + uint64_t(k)] = mesh.vertex(first + t, k);
    g.BindBuffer(GL_ARRAY_BUFFER, buffers_[c]);
    g.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(count * 3 * sizeof(glm::vec3)), corners.data(),
                 GL_STATIC_DRAW);
  }
  check("uploading a mesh (out of memory?)");
  uploaded_ = true;
}

void MeshBuffers::bindChunk(uint64_t c) const {
  const Api& g = api();
  g.BindBuffer(GL_ARRAY_BUFFER, buffers_[c]);
  g.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
}

int MeshBuffers::draw(const IdProgram& program, uint64_t first, uint64_t count,
                      uint64_t firstId) const {
  const Api& g = api();
  int calls = 0;
  const uint64_t end = std::min(first + count, triangles_);
  while (first < end) {
    const uint64_t chunk = first / kChunkTriangles, offset = first % kChunkTriangles;
    const uint64_t n = std::min(end - first, kChunkTriangles - offset);
    bindChunk(chunk);
    // The shader adds the triangle's index within the chunk (offset for the first one).
    program.setIdBase(firstId - offset);
    g.DrawArrays(GL_TRIANGLES, GLint(3 * offset), GLsizei(3 * n));
    first += n;
    firstId += n;
    ++calls;
  }
  return calls;
}

int MeshBuffers::drawChunkList(const IdProgram& program, uint64_t c,
                               std::span<const uint32_t> local, uint64_t idBase,
                               ListIndices& indices) const {
  if (local.empty()) return 0;
  const Api& g = api();
  bindChunk(c);
  program.setIdBase(idBase + c * kChunkTriangles);
  int calls = 0;
  for (size_t at = 0; at < local.size(); at += ListIndices::kBatchTriangles) {
    const size_t n = std::min<size_t>(ListIndices::kBatchTriangles, local.size() - at);
    indices.upload(local.subspan(at, n));
    g.DrawElements(GL_TRIANGLES, GLsizei(3 * n), GL_UNSIGNED_INT, nullptr);
    ++calls;
  }
  return calls;
}

int MeshBuffers::drawList(const IdProgram& program, std::span<const uint32_t> list, uint64_t idBase,
                          ListIndices& indices) const {
  for (const uint32_t t : list)
    if (t >= triangles_)
      throw std::out_of_range("z-buffer triangle list: triangle " + std::to_string(t) +
                              " of a mesh of " + std::to_string(triangles_));
  if (buffers_.size() <= 1) return drawChunkList(program, 0, list, idBase, indices);
  // Stable counting sort by chunk, as indices within the chunk.
  std::vector<size_t> start(buffers_.size() + 1, 0);
  for (const uint32_t t : list) ++start[t / kChunkTriangles + 1];
  for (size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<uint32_t> local(list.size());
  std::vector<size_t> next(start.begin(), start.end() - 1);
  for (const uint32_t t : list) local[next[t / kChunkTriangles]++] = uint32_t(t % kChunkTriangles);
  int calls = 0;
  const std::span<const uint32_t> all(local);
  for (size_t c = 0; c < buffers_.size(); ++c)
    calls +=
        drawChunkList(program, c, all.subspan(start[c], start[c + 1] - start[c]), idBase, indices);
  return calls;
}

}  // namespace lzb::gl
