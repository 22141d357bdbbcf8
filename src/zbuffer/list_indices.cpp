#include "src/zbuffer/list_indices.hpp"

#include <cassert>

#include "src/zbuffer/gl_api.hpp"

namespace lzb::gl {

ListIndices::~ListIndices() {
  if (buffer_) api().DeleteBuffers(1, &buffer_);
}

void ListIndices::upload(std::span<const uint32_t> triangles) {
  assert(triangles.size() <= kBatchTriangles);
  const Api& g = api();
  if (!buffer_) g.GenBuffers(1, &buffer_);
  scratch_.resize(3 * triangles.size());
  uint32_t* out = scratch_.data();
  for (const uint32_t t : triangles) {
    out[0] = 3 * t;
    out[1] = 3 * t + 1;
    out[2] = 3 * t + 2;
    out += 3;
  }
  // The element-array binding belongs to the vertex array bound now.
  g.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffer_);
  // New storage each time: GL keeps the previous batch's indices for draws still queued.
  g.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(scratch_.size() * sizeof(uint32_t)),
               scratch_.data(), GL_STREAM_DRAW);
}

}  // namespace lzb::gl
