#include "src/zbuffer/draw_walk.hpp"

#include <algorithm>

namespace lzb {

namespace {

constexpr uint64_t kMax = ~uint64_t(0);
uint64_t addSat(uint64_t a, uint64_t b) {
  return a > kMax - b ? kMax : a + b;
}

}  // namespace

DrawWalk::DrawWalk(const Scene& scene) : scene_(scene) {
  const size_t n = scene.nodes.size();
  meshBounds_.resize(n);
  for (size_t i = 0; i < n; ++i)
    for (const glm::vec3& p : scene.nodes[i].mesh.positions) meshBounds_[i].extend(glm::dvec3(p));
  // Memoised post-order count; finalize() has already rejected cycles.
  itemCount_.assign(n, kMax);
  std::function<uint64_t(uint32_t)> count = [&](uint32_t i) {
    if (itemCount_[i] != kMax) return itemCount_[i];
    uint64_t c = scene.nodes[i].mesh.empty() ? 0 : 1;
    for (const Instance& inst : scene.nodes[i].instances) c = addSat(c, count(inst.node));
    return itemCount_[i] = c;
  };
  count(scene.root);
}

struct DrawWalk::Pass {
  const DrawWalk& w;
  const Frustum& frustum;
  const IdRange& range;
  const std::function<void(const DrawCall&)>& draw;
  WalkCounts counts;

  // Draw items of node's subtree (expanded IDs from base) with triangles in the range.
  uint64_t itemsInRange(uint32_t node, uint64_t base) const {
    const Scene& s = w.scene_;
    const uint64_t end = addSat(base, s.expandedCount[node]);
    if (!range.overlaps(base, end)) return 0;
    if (range.contains(base, end)) return w.itemCount_[node];
    const Node& n = s.nodes[node];
    uint64_t c = !n.mesh.empty() && range.overlaps(base, base + n.mesh.size()) ? 1 : 0;
    uint64_t offset = base + n.mesh.size();
    for (const Instance& inst : n.instances) {
      c = addSat(c, itemsInRange(inst.node, offset));
      offset = addSat(offset, s.expandedCount[inst.node]);
    }
    return c;
  }

  void visit(uint32_t node, const glm::dmat4& world, uint64_t base, bool inside) {
    const Scene& s = w.scene_;
    const uint64_t end = addSat(base, s.expandedCount[node]);
    if (!range.overlaps(base, end)) return;
    const Node& n = s.nodes[node];
    if (!inside) {
      const Cull c = frustum.classify(s.nodeBounds[node].transformed(world));
      if (c == Cull::kOutside) {
        const uint64_t items = itemsInRange(node, base);
        counts.items = addSat(counts.items, items);
        counts.culled = addSat(counts.culled, items);
        return;
      }
      inside = c == Cull::kInside;
    }
    const uint64_t meshEnd = base + n.mesh.size();
    if (!n.mesh.empty() && range.overlaps(base, meshEnd)) {
      ++counts.items;
      // A node with instances has looser subtree bounds than its own triangles: test those too.
      const bool visible =
          inside || n.instances.empty() ||
          frustum.classify(w.meshBounds_[node].transformed(world)) != Cull::kOutside;
      if (visible) {
        const uint64_t first = std::max(base, range.begin) - base;
        const uint64_t last = std::min(meshEnd, range.end) - base;
        draw(DrawCall{node, world, first, last - first, base + first});
        counts.triangles += last - first;
      } else {
        ++counts.culled;
      }
    }
    uint64_t offset = meshEnd;
    for (const Instance& inst : n.instances) {
      if (offset >= range.end) break;
      visit(inst.node, world * inst.transform, offset, inside);
      offset = addSat(offset, s.expandedCount[inst.node]);
    }
  }
};

WalkCounts DrawWalk::walk(const Frustum& frustum, const IdRange& range,
                          const std::function<void(const DrawCall&)>& draw) const {
  Pass pass{*this, frustum, range, draw, {}};
  if (!scene_.nodes.empty()) pass.visit(scene_.root, glm::dmat4(1.0), 0, false);
  return pass.counts;
}

}  // namespace lzb
