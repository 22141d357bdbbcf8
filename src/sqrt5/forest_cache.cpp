#include "src/sqrt5/forest_cache.hpp"

namespace lzb::sqrt5 {

void ForestCache::endFrame(uint64_t budgetBytes) {
  for (auto it = lines_.begin(); it != lines_.end();) {
    if (!it->second.used) {
      it = lines_.erase(it);
      continue;
    }
    it->second.used = false;
    ++it;
  }
  if (bytes() > budgetBytes) lines_.clear();
}

uint64_t ForestCache::bytes() const {
  uint64_t b = 0;
  for (const auto& [key, line] : lines_) b += line.bytes() + sizeof(key) + 64;  // + map node
  return b;
}

}  // namespace lzb::sqrt5
