#include "src/sampletree/approximated_pixels.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "src/core/scene.hpp"
#include "src/sampletree/cube_projection.hpp"

namespace lzb::sampletree {

namespace {

struct PixelMask {
  int width, height;
  std::vector<uint8_t> bits;
  // Marks pixels whose area meets [x0, x1) x [y0, y1) (pixel coordinates, y down).
  void mark(double x0, double y0, double x1, double y1) {
    const int i0 = std::max(0, int(std::floor(x0))), i1 = std::min(width, int(std::ceil(x1)));
    const int j0 = std::max(0, int(std::floor(y0))), j1 = std::min(height, int(std::ceil(y1)));
    for (int j = j0; j < j1; ++j)
      std::fill(bits.begin() + long(j) * width + i0, bits.begin() + long(j) * width + std::max(i0, i1), 1);
  }
};

using Rect = std::array<double, 4>;  // x0, y0, x1, y1; empty when x1 <= x0

// The screen rectangle of the cube around the node's bounding sphere; the whole image when a
// corner is not in front of the near plane.
Rect sphereRect(const SampleTree& tree, const TreeNode& node, const CubeProjector& cubes,
                const Camera& camera) {
  const double r = 0.5 * std::sqrt(3.0) * tree.cellSize(node);
  const ScreenRect rect = cubes.rect(tree.cellBounds(node).center() - glm::dvec3(r), 2.0 * r);
  if (rect.behind) return {0.0, 0.0, double(camera.width()), double(camera.height())};
  return {rect.x0, rect.y0, rect.x1, rect.y1};
}

// The splat's d x d pixels: those whose centres are nearest its projection (splatter.hpp).
Rect splatRect(const TreeNode& node, const Camera& camera, int splat) {
  if (node.representativeId == kNoId || splat == 0) return {};
  const glm::dvec3 p = camera.project(glm::dvec3(node.representativePoint[0],
                                                 node.representativePoint[1],
                                                 node.representativePoint[2]));
  if (!(p.z > 0.0)) return {};
  const double off = 0.5 - 0.5 * splat;
  const double fx = std::floor(p.x + off), fy = std::floor(p.y + off);
  return {fx, fy, fx + splat, fy + splat};
}

}  // namespace

uint64_t approximatedPixels(const SampleTree& tree, const std::vector<uint32_t>& stops,
                            const Camera& camera, int splat, int threads) {
  // The rectangles on the threads (projection is the cost), the marking in one pass.
  std::vector<std::array<Rect, 2>> rects(stops.size());
  const CubeProjector cubes(camera);
  const int64_t n = int64_t(stops.size());
#pragma omp parallel for schedule(static) num_threads(std::max(threads, 1))
  for (int64_t k = 0; k < n; ++k) {
    const TreeNode& node = tree.nodes[stops[size_t(k)]];
    rects[size_t(k)] = {sphereRect(tree, node, cubes, camera), splatRect(node, camera, splat)};
  }
  PixelMask m{camera.width(), camera.height(),
              std::vector<uint8_t>(size_t(camera.width()) * size_t(camera.height()), 0)};
  for (const auto& pair : rects)
    for (const Rect& r : pair) m.mark(r[0], r[1], r[2], r[3]);
  return uint64_t(std::count(m.bits.begin(), m.bits.end(), uint8_t(1)));
}

}  // namespace lzb::sampletree
