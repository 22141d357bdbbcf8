#include "src/core/framebuffer.hpp"

#include <algorithm>
#include <cassert>

namespace lzb {

void Framebuffer::resize(int w, int h) {
  width = w;
  height = h;
  depth.resize(size());
  color.resize(size());
  id.resize(size());
  clear();
}

void Framebuffer::clear() {
  std::fill(depth.begin(), depth.end(), kEmptyDepth);
  std::fill(color.begin(), color.end(), kBackground);
  std::fill(id.begin(), id.end(), kNoId);
}

size_t Framebuffer::coveredCount() const {
  return size_t(std::count_if(id.begin(), id.end(), [](uint64_t v) { return v != kNoId; }));
}

void compositeNearer(Framebuffer& into, const Framebuffer& other) {
  assert(into.width == other.width && into.height == other.height);
  const size_t n = into.size();
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) into.keepNearer(i, other.depth[i], other.color[i], other.id[i]);
}

}  // namespace lzb
