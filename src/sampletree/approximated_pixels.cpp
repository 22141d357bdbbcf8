#include "src/sampletree/approximated_pixels.hpp"

#include <algorithm>
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

// The screen rectangle of the cube around the node's bounding sphere; the whole image when a
// corner is not in front of the near plane.
void markSphere(const SampleTree& tree, const TreeNode& node, const CubeProjector& cubes,
                PixelMask& m) {
  const double r = 0.5 * std::sqrt(3.0) * tree.cellSize(node);
  const ScreenRect rect = cubes.rect(tree.cellBounds(node).center() - glm::dvec3(r), 2.0 * r);
  if (rect.behind)
    m.mark(0, 0, m.width, m.height);
  else
    m.mark(rect.x0, rect.y0, rect.x1, rect.y1);
}

// The splat's d x d pixels: those whose centres are nearest its projection (splatter.hpp).
void markSplat(const TreeNode& node, const Camera& camera, int splat, PixelMask& m) {
  if (node.representativeId == kNoId || splat == 0) return;
  const glm::dvec3 p = camera.project(glm::dvec3(node.representativePoint[0],
                                                 node.representativePoint[1],
                                                 node.representativePoint[2]));
  if (!(p.z > 0.0)) return;
  const double off = 0.5 - 0.5 * splat;
  const double fx = std::floor(p.x + off), fy = std::floor(p.y + off);
  m.mark(fx, fy, fx + splat, fy + splat);
}

}  // namespace

uint64_t approximatedPixels(const SampleTree& tree, const std::vector<uint32_t>& stops,
                            const Camera& camera, int splat) {
  PixelMask m{camera.width(), camera.height(),
              std::vector<uint8_t>(size_t(camera.width()) * size_t(camera.height()), 0)};
  const CubeProjector cubes(camera);
  for (uint32_t i : stops) {
    markSphere(tree, tree.nodes[i], cubes, m);
    markSplat(tree.nodes[i], camera, splat, m);
  }
  return uint64_t(std::count(m.bits.begin(), m.bits.end(), uint8_t(1)));
}

}  // namespace lzb::sampletree
