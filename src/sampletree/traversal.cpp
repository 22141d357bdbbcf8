#include "src/sampletree/traversal.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "src/core/scene.hpp"
#include "src/sampletree/cube_projection.hpp"

namespace lzb::sampletree {

namespace {

// Subtrees rooted at this level are walked in parallel (a flat scene's tree has ~10^2 of them
// in view); their parts of the preorder lists are joined in order, so the result is the
// one-thread walk's whatever the thread count.
constexpr uint8_t kTaskLevel = 4;

class Walk {
 public:
  Walk(const SampleTree& tree, const Camera& camera, int splat, StopDraw stopDraw)
      : tree_(tree),
        frustum_(camera.frustum()),
        cubes_(camera),
        stopPixels_(double(splat) * double(splat)),
        stopDraw_(stopDraw) {
    for (size_t p = 0; p < frustum_.planes.size(); ++p)
      normLength_[p] = glm::length(frustum_.planes[p].n);
  }

  // Walks the preorder nodes [begin, end) into parts.back(). With `tasks`, a node of kTaskLevel
  // is not walked but left as a task: its index goes to `tasks`, and two parts are added (its
  // walk's, then the walk's after it).
  void run(size_t begin, size_t end, std::vector<Traversal>& parts,
           std::vector<uint32_t>* tasks) const {
    for (size_t i = begin; i < end;) {
      const TreeNode& node = tree_.nodes[i];
      if (tasks && node.level == kTaskLevel) {
        tasks->push_back(uint32_t(i));
        parts.resize(parts.size() + 2);
        i = node.subtreeEnd;
        continue;
      }
      i = step(i, parts.back());
    }
  }

 private:
  // Visits node i; returns the next node to visit.
  size_t step(size_t i, Traversal& out) const {
    const TreeNode& node = tree_.nodes[i];
    const double side = tree_.cellSize(node);
    const glm::dvec3 lo =
        tree_.origin + side * glm::dvec3(node.cell[0], node.cell[1], node.cell[2]);
    if (sphereOutside(lo + 0.5 * side, 0.5 * std::sqrt(3.0) * side)) {
      ++out.culled;
      return node.subtreeEnd;
    }
    ++out.visited;
    const ScreenRect rect = cubes_.rect(lo, side);
    if (!rect.behind && rect.area() <= stopPixels_) {
      out.stops.push_back(uint32_t(i));
      if (stopDraw_ == StopDraw::kTriangles) {
        if (node.triangleCount > 0) out.visits.push_back({uint32_t(i), false});
      } else if (node.representativeId != kNoId) {
        out.visits.push_back({uint32_t(i), true});
      }
      return node.subtreeEnd;
    }
    if (node.triangleCount > 0) out.visits.push_back({uint32_t(i), false});
    return i + 1;
  }

  // Every triangle of a node lies in its cell's bounding sphere (cell_octree.hpp): cull that.
  bool sphereOutside(const glm::dvec3& centre, double radius) const {
    for (size_t p = 0; p < frustum_.planes.size(); ++p)
      if (frustum_.planes[p].distance(centre) < -radius * normLength_[p]) return true;
    return false;
  }

  const SampleTree& tree_;
  const Frustum frustum_;
  const CubeProjector cubes_;
  const double stopPixels_;
  const StopDraw stopDraw_;
  std::array<double, 6> normLength_{};
};

void append(Traversal& to, const Traversal& part) {
  to.visits.insert(to.visits.end(), part.visits.begin(), part.visits.end());
  to.stops.insert(to.stops.end(), part.stops.begin(), part.stops.end());
  to.visited += part.visited;
  to.culled += part.culled;
}

}  // namespace

double projectedCellPixels(const SampleTree& tree, const TreeNode& node, const Camera& camera) {
  const Bounds b = tree.cellBounds(node);
  const ScreenRect rect = CubeProjector(camera).rect(b.lo, tree.cellSize(node));
  return rect.behind ? std::numeric_limits<double>::infinity() : rect.area();
}

Traversal traverse(const SampleTree& tree, const Camera& camera, int splat, StopDraw stopDraw,
                   int threads) {
  const Walk walk(tree, camera, splat, stopDraw);
  std::vector<Traversal> parts(1);
  std::vector<uint32_t> tasks;
  walk.run(0, tree.nodes.size(), parts, &tasks);
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::max(threads, 1))
  for (size_t t = 0; t < tasks.size(); ++t) {
    std::vector<Traversal> mine(1);
    walk.run(tasks[t], tree.nodes[tasks[t]].subtreeEnd, mine, nullptr);
    parts[2 * t + 1] = std::move(mine.front());
  }
  Traversal out = std::move(parts.front());
  for (size_t p = 1; p < parts.size(); ++p) append(out, parts[p]);
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
