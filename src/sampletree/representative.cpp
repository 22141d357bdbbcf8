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
  std::vector<uint32_t> order(tris.begin(), tris.end());
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    const float la = luminance(in.colours[a]), lb = luminance(in.colours[b]);
    return la != lb ? la < lb : in.ids[a] < in.ids[b];
  });
  double total = 0.0;
  for (uint32_t t : order) total += areas[t];
  double sum = 0.0;
  for (uint32_t t : order) {
    sum += areas[t];
    if (sum >= 0.5 * total) return t;
  }
  return order.back();
}

}  // namespace lzb::sampletree
