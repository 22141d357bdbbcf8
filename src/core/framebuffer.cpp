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
  // On the frame's threads: one thread fills 16 bytes a pixel at ~20 GB/s (1.7 ms at 1080p).
  tilesInUse.clear();
  const long n = long(size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    depth[size_t(i)] = kEmptyDepth;
    color[size_t(i)] = kBackground;
    id[size_t(i)] = kNoId;
  }
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
