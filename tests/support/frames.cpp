#include "tests/support/frames.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace lzb::test {

bool sameKeys(const Framebuffer& a, const Framebuffer& b) {
  return a.id == b.id && a.depth.size() == b.depth.size() &&
         std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)) == 0;
}

bool sameImage(const Framebuffer& a, const Framebuffer& b) {
  return a.width == b.width && a.height == b.height && a.id == b.id && a.color == b.color &&
         std::equal(a.depth.begin(), a.depth.end(), b.depth.begin(), [](float x, float y) {
           return std::bit_cast<uint32_t>(x) == std::bit_cast<uint32_t>(y);
         });
}

bool sameIdsAndDepths(const Framebuffer& a, const Framebuffer& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a.id[i] != b.id[i] ||
        !(a.depth[i] == b.depth[i] || (std::isinf(a.depth[i]) && std::isinf(b.depth[i]))))
      return false;
  return true;
}

size_t holes(const Framebuffer& image, const Framebuffer& exact) {
  size_t n = 0;
  for (size_t i = 0; i < image.size(); ++i) n += exact.covered(i) && !image.covered(i);
  return n;
}

size_t covered(const Framebuffer& f) {
  size_t n = 0;
  for (size_t i = 0; i < f.size(); ++i) n += f.covered(i);
  return n;
}

}  // namespace lzb::test
