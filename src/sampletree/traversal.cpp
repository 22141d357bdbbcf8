#include "src/sampletree/traversal.hpp"

#include <cmath>
#include <limits>

#include "src/core/scene.hpp"

namespace lzb::sampletree {

namespace {

// Every triangle of a node lies in its cell's bounding sphere (cell_octree.hpp): cull that.
bool sphereOutside(const Frustum& f, const glm::dvec3& centre, double radius) {
  for (const Plane& p : f.planes)
    if (p.distance(centre) < -radius * glm::length(p.n)) return true;
  return false;
}

}  // namespace

double projectedCellPixels(const SampleTree& tree, const TreeNode& node, const Camera& camera) {
  const Bounds b = tree.cellBounds(node);
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 p = camera.project(b.corner(k));
    if (!(p.z >= camera.nearPlane())) return std::numeric_limits<double>::infinity();
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  return (x1 - x0) * (y1 - y0);
}

Traversal traverse(const SampleTree& tree, const Camera& camera, int splat, StopDraw stopDraw) {
  Traversal out;
  const Frustum frustum = camera.frustum();
  const double stopPixels = double(splat) * double(splat);
  const size_t n = tree.nodes.size();
  // Preorder: the node after u is u's first child, or, when u has none, the next subtree.
  for (size_t i = 0; i < n;) {
    const TreeNode& node = tree.nodes[i];
    const double side = tree.cellSize(node);
    if (sphereOutside(frustum, tree.cellBounds(node).center(), 0.5 * std::sqrt(3.0) * side)) {
      ++out.culled;
      i = node.subtreeEnd;
      continue;
    }
    ++out.visited;
    if (projectedCellPixels(tree, node, camera) <= stopPixels) {
      out.stops.push_back(uint32_t(i));
      if (stopDraw == StopDraw::kTriangles) {
        if (node.triangleCount > 0) out.visits.push_back({uint32_t(i), false});
      } else if (node.representativeId != kNoId) {
        out.visits.push_back({uint32_t(i), true});
      }
      i = node.subtreeEnd;
      continue;
    }
    if (node.triangleCount > 0) out.visits.push_back({uint32_t(i), false});
    ++i;
  }
  return out;
}

std::vector<uint32_t> belowStops(const SampleTree& tree, const std::vector<uint32_t>& stops,
                                 int levels) {
  std::vector<uint32_t> out;
  for (uint32_t s : stops) {
    const TreeNode& stop = tree.nodes[s];
    const int deepest = int(stop.level) + levels;
    for (uint32_t i = s; i < stop.subtreeEnd;) {
      const TreeNode& n = tree.nodes[i];
      if (n.triangleCount > 0) out.push_back(i);
      i = int(n.level) >= deepest ? n.subtreeEnd : i + 1;  // skip what lies deeper
    }
  }
  return out;
}

}  // namespace lzb::sampletree
