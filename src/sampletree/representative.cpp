#include "src/sampletree/representative.hpp"

#include <algorithm>
#include <vector>

namespace lzb::sampletree {

namespace {

float luminance(Rgba8 c) {
  const glm::vec3 rgb = unpackRgb(c);
  return 0.2126f * rgb.r + 0.7152f * rgb.g + 0.0722f * rgb.b;
}

}  // namespace

uint32_t medianTriangle(const TriangleInput& in, const std::vector<double>& areas,
                        std::span<const uint32_t> tris) {
  // Each triangle's luminance once, not per comparison.
  struct Key {
    float luminance;
    uint64_t id;
    uint32_t t;
  };
  std::vector<Key> order;
  order.reserve(tris.size());
  for (uint32_t t : tris) order.push_back({luminance(in.colours[t]), in.ids[t], t});
  std::sort(order.begin(), order.end(), [](const Key& a, const Key& b) {
    return a.luminance != b.luminance ? a.luminance < b.luminance : a.id < b.id;
  });
  double total = 0.0;
  for (const Key& k : order) total += areas[k.t];
  double sum = 0.0;
  for (const Key& k : order) {
    sum += areas[k.t];
    if (sum >= 0.5 * total) return k.t;
  }
  return order.back().t;
}

}  // namespace lzb::sampletree
