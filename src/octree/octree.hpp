#pragma once
// Octree over ONE scene node's content, in that node's frame (LZB paper, sections II.A and III):
// the node's triangles and its instances (each as the AABB of the child node's bounds under the
// instance transform). Instanced content gets its own octree per node; callers walk the DAG.
//
// A node is split while it holds more than maxLeafEntries entries and is above maxDepth. A
// triangle is listed in EVERY leaf it overlaps (triBoxOverlap, closed boxes), an instance in every
// leaf its AABB overlaps, so the leaves a ray crosses list every triangle the ray can hit there.
// A split whose children would hold more than maxSplitGrowth times the parent's entries is
// refused (the node stays a larger leaf): many large overlapping triangles would otherwise
// multiply the leaves by 4 per level down to maxDepth without separating anything.
//
// Layout: nodes in one flat vector, the 8 children of an inner node contiguous (octant bit 0: x
// upper half, bit 1: y, bit 2: z, as Bounds::corner), boxes and depths in parallel vectors, leaf
// entries in one flat array (offset + count per leaf). Node 0 is the root. Leaves are named by
// their node index everywhere. The result does not depend on the thread count.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <span>
#include <utility>
#include <vector>

#include "src/core/bounds.hpp"
#include "src/core/camera.hpp"
#include "src/core/scene.hpp"

namespace lzb {

struct OctreeParams {
  int maxDepth = 16;              // the root has depth 0
  uint32_t maxLeafEntries = 150;  // the LZB paper uses at most 150 triangles per leaf
  double maxSplitGrowth = 3.0;    // see the top of this file; must be >= 1
  bool progress = false;          // show a progress line for large builds
};

struct OctreeStats {
  uint64_t nodes = 0, leaves = 0, nonEmptyLeaves = 0;
  int maxDepth = 0;              // deepest leaf
  uint64_t entries = 0;          // stored in leaves, duplicates included
  double meanLeafEntries = 0.0;  // over non-empty leaves
  uint64_t maxLeafEntries = 0;
  uint64_t growthStoppedLeaves = 0;  // leaves whose split was refused by maxSplitGrowth
  uint64_t skippedTriangles = 0;     // non-finite triangles left out
  uint64_t memoryBytes = 0;          // nodes, boxes, depths and entries
  double buildSeconds = 0.0;
  nlohmann::json toJson() const;
};

// The world-space frustum's planes in a node's frame: planes are covectors, so they transform
// with the transpose of nodeToWorld (the inverse transpose of worldToNode); normals renormalised.
Frustum frustumToNodeSpace(const Frustum& world, const glm::dmat4& nodeToWorld);

class Octree {
 public:
  // An entry is a triangle index of the mesh, or an instance index with kInstanceBit set.
  static constexpr uint32_t kInstanceBit = 0x80000000u;
  static constexpr uint32_t kNoChild = ~uint32_t(0);
  static bool isInstance(uint32_t entry) { return (entry & kInstanceBit) != 0; }
  static uint32_t entryIndex(uint32_t entry) { return entry & ~kInstanceBit; }

  struct Node {
    uint64_t offset = 0;             // leaves: first entry in entries()
    uint32_t count = 0;              // leaves: number of entries; inner nodes: 0
    uint32_t firstChild = kNoChild;  // inner nodes: index of child octant 0
    bool leaf() const { return firstChild == kNoChild; }
  };

  Octree() = default;
  // Builds over a mesh and instance AABBs (both in the same frame). Empty boxes are left out.
  Octree(const Mesh& mesh, std::span<const Bounds> instanceBoxes, const OctreeParams& params = {});
  // Builds over scene.nodes[node]; scene.finalize() must have run (it fills nodeBounds).
  Octree(const Scene& scene, uint32_t node, const OctreeParams& params = {});
  // The AABB of each instance of scene.nodes[node], in that node's frame.
  static std::vector<Bounds> instanceBoxes(const Scene& scene, uint32_t node);

  bool empty() const { return nodes_.empty() || boxes_[0].empty(); }
  // The root box: a cube around the content (empty for an empty tree).
  const Bounds& bounds() const { return nodes_.empty() ? kNoBounds : boxes_[0]; }
  uint32_t nodeCount() const { return uint32_t(nodes_.size()); }
  const Node& node(uint32_t i) const { return nodes_[i]; }
  const Bounds& nodeBox(uint32_t i) const { return boxes_[i]; }
  int nodeDepth(uint32_t i) const { return depths_[i]; }
  std::span<const uint32_t> leafEntries(uint32_t i) const {
    return {entries_.data() + nodes_[i].offset, nodes_[i].count};
  }
  const std::vector<uint32_t>& entries() const { return entries_; }
  const OctreeParams& params() const { return params_; }
  const OctreeStats& stats() const { return stats_; }

  // Hierarchical view-frustum culling. Calls emit(uint32_t leaf, Cull) for every non-empty leaf
  // not outside the frustum (kInside or kIntersects); a node fully inside emits its leaves with
  // no further plane tests. The frustum is in world space; nodeToWorld places this node.
  template <class Emit>
  void cullFrustum(const Frustum& world, const glm::dmat4& nodeToWorld, Emit&& emit) const;

  // Visits the non-empty leaves whose closed boxes the segment origin + t * dir, t in
  // [tMin, tMax], touches, in increasing entry t (ties by node index), as
  // visitor(uint32_t leaf, double tEnter, double tExit) -> bool with tMin <= tEnter <= tExit <=
  // tMax; visitor returning false stops the walk. Node frame: a ray transformed by an affine
  // worldToNode keeps its t. Returns false when the visitor stopped it. Zero direction components
  // (and subnormal ones) are handled without NaN; a non-finite ray visits nothing.
  template <class Visitor>
  bool traverseRay(const glm::dvec3& origin, const glm::dvec3& dir, double tMin, double tMax,
                   Visitor&& visitor) const;

 private:
  friend class OctreeBuilder;
  template <class Emit>
  void cullNode(const Frustum& f, uint32_t i, unsigned planeMask, Emit& emit) const;
  template <class Emit>
  void emitSubtree(uint32_t i, Emit& emit) const;
  void computeStats();
  static inline const Bounds kNoBounds{};

  OctreeParams params_;
  std::vector<Node> nodes_;
  std::vector<Bounds> boxes_;
  std::vector<uint8_t> depths_;
  std::vector<uint32_t> entries_;
  OctreeStats stats_;
};

namespace detail {

struct RayItem {
  double tEnter, tExit;
  uint32_t node;
};

// Min-heap on (tEnter, node) with inline storage: no allocation for ordinary rays, and
// re-entrant, so a visitor may walk another octree (an instance's) from inside a visit.
class RayQueue {
 public:
  RayQueue() = default;
  RayQueue(const RayQueue&) = delete;
  RayQueue& operator=(const RayQueue&) = delete;
  bool empty() const { return size_ == 0; }
  void push(const RayItem& item) {
    if (size_ == cap_) grow();
    data_[size_++] = item;
    std::push_heap(data_, data_ + size_, later);
  }
  RayItem pop() {
    std::pop_heap(data_, data_ + size_, later);
    return data_[--size_];
  }

 private:
  static bool later(const RayItem& a, const RayItem& b) {
    return a.tEnter > b.tEnter || (a.tEnter == b.tEnter && a.node > b.node);
  }
  void grow() {
    std::vector<RayItem> bigger(data_, data_ + size_);
    bigger.resize(2 * cap_);
    spill_.swap(bigger);
    data_ = spill_.data();
    cap_ = spill_.size();
  }
  static constexpr size_t kInline = 64;
  RayItem inline_[kInline];
  std::vector<RayItem> spill_;
  RayItem* data_ = inline_;
  size_t size_ = 0, cap_ = kInline;
};

}  // namespace detail

template <class Emit>
void Octree::cullFrustum(const Frustum& world, const glm::dmat4& nodeToWorld, Emit&& emit) const {
  if (empty()) return;
  const Frustum f = frustumToNodeSpace(world, nodeToWorld);
  cullNode(f, 0, 0x3fu, emit);
}

template <class Emit>
void Octree::cullNode(const Frustum& f, uint32_t i, unsigned planeMask, Emit& emit) const {
  const Bounds& b = boxes_[i];
  for (int p = 0; p < 6; ++p) {
    if (!(planeMask & (1u << p))) continue;  // the parent is inside this plane already
    const Plane& pl = f.planes[p];
    const glm::dvec3 pv{pl.n.x >= 0 ? b.hi.x : b.lo.x, pl.n.y >= 0 ? b.hi.y : b.lo.y,
                        pl.n.z >= 0 ? b.hi.z : b.lo.z};
    if (pl.distance(pv) < 0.0) return;  // even the farthest corner is outside
    const glm::dvec3 nv{pl.n.x >= 0 ? b.lo.x : b.hi.x, pl.n.y >= 0 ? b.lo.y : b.hi.y,
                        pl.n.z >= 0 ? b.lo.z : b.hi.z};
    if (pl.distance(nv) >= 0.0) planeMask &= ~(1u << p);
  }
  if (planeMask == 0) return emitSubtree(i, emit);
  const Node& n = nodes_[i];
  if (n.leaf()) {
    if (n.count) emit(i, Cull::kIntersects);
    return;
  }
  for (uint32_t c = 0; c < 8; ++c) cullNode(f, n.firstChild + c, planeMask, emit);
}

template <class Emit>
void Octree::emitSubtree(uint32_t i, Emit& emit) const {
  const Node& n = nodes_[i];
  if (n.leaf()) {
    if (n.count) emit(i, Cull::kInside);
    return;
  }
  for (uint32_t c = 0; c < 8; ++c) emitSubtree(n.firstChild + c, emit);
}

template <class Visitor>
bool Octree::traverseRay(const glm::dvec3& origin, const glm::dvec3& dir, double tMin, double tMax,
                         Visitor&& visitor) const {
  const auto finite = [](const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
  };
  if (empty() || !finite(origin) || !finite(dir) || !(tMin <= tMax)) return true;
  const RaySlabs ray(origin, dir);
  double t0 = tMin, t1 = tMax;
  if (!ray.clip(boxes_[0], t0, t1)) return true;
  // Best-first by entry t: a child never enters before its parent, so leaves pop in entry order
  // even for rays lying in a splitting plane, where depth-first would interleave subtrees.
  detail::RayQueue queue;
  queue.push({t0, t1, 0});
  while (!queue.empty()) {
    const detail::RayItem item = queue.pop();
    const Node& n = nodes_[item.node];
    if (n.leaf()) {
      if (!visitor(item.node, item.tEnter, item.tExit)) return false;
      continue;
    }
    for (uint32_t c = n.firstChild; c < n.firstChild + 8; ++c) {
      const Node& child = nodes_[c];
      if (child.leaf() && child.count == 0) continue;
      double c0 = item.tEnter, c1 = item.tExit;
      if (ray.clip(boxes_[c], c0, c1)) queue.push({c0, c1, c});
    }
  }
  return true;
}

}  // namespace lzb
