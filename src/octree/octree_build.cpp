// Octree construction: recursive split with OpenMP tasks, then a serial flatten into the
// cache-friendly layout. The tree's shape depends only on the input, and the flatten order is
// fixed, so the result is identical for every thread count.
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <string>

#include "src/core/error.hpp"
#include "src/core/progress.hpp"
#include "src/core/timer.hpp"
#include "src/octree/octree.hpp"
#include "src/octree/tri_box_overlap.hpp"

namespace lzb {

namespace {

// Nodes with this many entries classify them in parallel, in chunks of kClassifyChunk.
constexpr size_t kParallelClassify = size_t(1) << 15;
constexpr size_t kClassifyChunk = size_t(1) << 13;
// Children with this many entries are built as their own task.
constexpr size_t kChildTask = size_t(1) << 12;
// Builds with fewer entries show no progress line.
constexpr uint64_t kProgressEntries = uint64_t(1) << 17;
constexpr int kMaxDepthLimit = 30;

struct PendingNode {
  Bounds box;
  int depth = 0;
  std::vector<uint32_t> entries;          // leaves
  std::unique_ptr<PendingNode[]> children;  // 8, or null for a leaf
};

std::array<Bounds, 8> childBoxes(const Bounds& b) {
  const glm::dvec3 mid = 0.5 * (b.lo + b.hi);
  std::array<Bounds, 8> kids;
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < 3; ++k) {
      kids[c].lo[k] = (c >> k) & 1 ? mid[k] : b.lo[k];
      kids[c].hi[k] = (c >> k) & 1 ? b.hi[k] : mid[k];
    }
  return kids;
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

class OctreeBuilder {
 public:
  OctreeBuilder(const Mesh& mesh, std::span<const Bounds> instances, const OctreeParams& params,
                Progress& progress)
      : mesh_(mesh), instances_(instances), params_(params), progress_(progress) {}

  // Splits `node` holding `entries` (all overlap node.box); `budget` is its share of progress.
  void build(PendingNode& node, std::vector<uint32_t> entries, double budget) {
    const size_t n = entries.size();
    if (n <= params_.maxLeafEntries || node.depth >= params_.maxDepth)
      return makeLeaf(node, std::move(entries), budget);
    const std::array<Bounds, 8> kids = childBoxes(node.box);
    const glm::dvec3 mid = kids[0].hi;
    // One byte per entry: the children it overlaps.
    std::vector<uint8_t> masks(n);
    const auto classify = [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) {
        // Deeper nodes touch scattered triangles: fetch ahead to hide the memory latency.
        if (i + kPrefetch < end) prefetch(entries[i + kPrefetch]);
        masks[i] = childMask(entries[i], node.box, mid, kids);
      }
    };
    if (n >= kParallelClassify) {
      const size_t chunks = (n + kClassifyChunk - 1) / kClassifyChunk;
#pragma omp taskloop grainsize(1) shared(classify)
      for (size_t ch = 0; ch < chunks; ++ch)
        classify(ch * kClassifyChunk, std::min(n, (ch + 1) * kClassifyChunk));
    } else {
      classify(0, n);
    }
    std::array<size_t, 8> counts{};
    for (uint8_t m : masks)
      for (int c = 0; c < 8; ++c) counts[c] += (m >> c) & 1;
    size_t total = 0;
    for (size_t k : counts) total += k;
    if (double(total) > params_.maxSplitGrowth * double(n)) {
      growthStopped_.fetch_add(1, std::memory_order_relaxed);
      return makeLeaf(node, std::move(entries), budget);
    }
    // Child lists keep the parent's (ascending) order.
    std::array<std::vector<uint32_t>, 8> lists;
    for (int c = 0; c < 8; ++c) lists[c].reserve(counts[c]);
    for (size_t i = 0; i < n; ++i)
      for (unsigned m = masks[i]; m; m &= m - 1) lists[__builtin_ctz(m)].push_back(entries[i]);
    std::vector<uint32_t>().swap(entries);
    std::vector<uint8_t>().swap(masks);
    node.children = std::make_unique<PendingNode[]>(8);
    for (int c = 0; c < 8; ++c) {
      node.children[c].box = kids[c];
      node.children[c].depth = node.depth + 1;
    }
    // Entries lost to rounding (overlapping the parent only within tolerance) still count.
    if (total == 0) progress_.add(uint64_t(budget));
    for (int c = 0; c < 8; ++c) {
      const double share = total ? budget * double(counts[c]) / double(total) : 0.0;
      if (lists[c].size() >= kChildTask) {
#pragma omp task shared(node, lists) firstprivate(c, share)
        build(node.children[c], std::move(lists[c]), share);
      } else {
        build(node.children[c], std::move(lists[c]), share);
      }
    }
#pragma omp taskwait
  }

  uint64_t growthStopped() const {
    return growthStopped_.load();
  }

 private:
  static constexpr size_t kPrefetch = 16;
  void prefetch(uint32_t entry) const {
    if (Octree::isInstance(entry)) return;
    __builtin_prefetch(&mesh_.indices[3 * size_t(entry)]);
  }

  void makeLeaf(PendingNode& node, std::vector<uint32_t> entries, double budget) {
    node.entries = std::move(entries);
    progress_.add(uint64_t(budget));
  }

  // Bit c set when the entry overlaps child c (its box kids[c]) of `parent`.
  uint8_t childMask(uint32_t entry, const Bounds& parent, const glm::dvec3& mid,
                    const std::array<Bounds, 8>& kids) const {
    uint8_t mask = 0;
    if (Octree::isInstance(entry)) {
      const Bounds& b = instances_[Octree::entryIndex(entry)];
      for (int c = 0; c < 8; ++c)
        if (b.overlaps(kids[c])) mask |= uint8_t(1u << c);
      return mask;
    }
    const glm::dvec3 a(mesh_.vertex(entry, 0)), b(mesh_.vertex(entry, 1)),
        c(mesh_.vertex(entry, 2));
    const glm::dvec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    // Per axis, bit 0: reaches the lower half, bit 1: reaches the upper half.
    unsigned sides[3];
    bool single = true;
    for (int k = 0; k < 3; ++k) {
      sides[k] = (lo[k] <= mid[k] ? 1u : 0u) | (hi[k] >= mid[k] ? 2u : 0u);
      single = single && sides[k] != 3u;
    }
    const bool inside = glm::all(glm::greaterThanEqual(lo, parent.lo)) &&
                        glm::all(glm::lessThanEqual(hi, parent.hi));
    for (int k = 0; k < 8; ++k) {
      if (!(sides[0] & (1u << (k & 1))) || !(sides[1] & (1u << ((k >> 1) & 1))) ||
          !(sides[2] & (1u << ((k >> 2) & 1))))
        continue;
      // A triangle whose bounding box lies inside one child, or with a vertex in the child,
      // overlaps it: no full test needed.
      if ((inside && single) || kids[k].contains(a) || kids[k].contains(b) || kids[k].contains(c) ||
          triBoxOverlap(kids[k], a, b, c))
        mask |= uint8_t(1u << k);
    }
    return mask;
  }

  const Mesh& mesh_;
  std::span<const Bounds> instances_;
  const OctreeParams& params_;
  Progress& progress_;
  std::atomic<uint64_t> growthStopped_{0};
};

namespace {

uint64_t countNodes(const PendingNode& b) {
  uint64_t n = 1;
  if (b.children)
    for (int c = 0; c < 8; ++c) n += countNodes(b.children[c]);
  return n;
}

uint64_t countEntries(const PendingNode& b) {
  uint64_t n = b.entries.size();
  if (b.children)
    for (int c = 0; c < 8; ++c) n += countEntries(b.children[c]);
  return n;
}

}  // namespace

Octree::Octree(const Mesh& mesh, std::span<const Bounds> instanceBoxes, const OctreeParams& params)
    : params_(params) {
  require(params.maxDepth >= 0 && params.maxDepth <= kMaxDepthLimit, "octree.max_depth",
          "must be in [0, " + std::to_string(kMaxDepthLimit) + "], got " +
              std::to_string(params.maxDepth));
  require(params.maxLeafEntries >= 1, "octree.max_leaf_entries", "must be >= 1");
  require(params.maxSplitGrowth >= 1.0, "octree.max_split_growth",
          "must be >= 1, got " + std::to_string(params.maxSplitGrowth));
  require(mesh.size() < kInstanceBit && instanceBoxes.size() < kInstanceBit, "octree",
          "a node with 2^31 or more triangles or instances is not supported");
  Stopwatch clock;
  // Root entries in ascending order: finite triangles, then instances with non-empty boxes.
  std::vector<uint32_t> rootEntries;
  rootEntries.reserve(mesh.size() + instanceBoxes.size());
  Bounds content;
  for (uint32_t t = 0; t < mesh.size(); ++t) {
    const glm::vec3 &a = mesh.vertex(t, 0), &b = mesh.vertex(t, 1), &c = mesh.vertex(t, 2);
    if (!finite(a) || !finite(b) || !finite(c)) {
      ++stats_.skippedTriangles;
      continue;
    }
    content.extend(glm::dvec3(a));
    content.extend(glm::dvec3(b));
    content.extend(glm::dvec3(c));
    rootEntries.push_back(t);
  }
  for (uint32_t i = 0; i < instanceBoxes.size(); ++i) {
    if (instanceBoxes[i].empty()) continue;
    content.extend(instanceBoxes[i]);
    rootEntries.push_back(i | kInstanceBit);
  }
  // A cube keeps cells well shaped; extended by the content so rounding never leaves it out.
  PendingNode root;
  if (!content.empty()) {
    const glm::dvec3 e = content.extent();
    const double half = 0.5 * std::max(e.x, std::max(e.y, e.z));
    const glm::dvec3 centre = content.center();
    root.box = Bounds{glm::min(centre - half, content.lo), glm::max(centre + half, content.hi)};
  }
  const uint64_t total = rootEntries.size();
  Progress progress("octree", total, params.progress && total >= kProgressEntries);
  OctreeBuilder builder(mesh, instanceBoxes, params_, progress);
#pragma omp parallel
#pragma omp single
  builder.build(root, std::move(rootEntries), double(total));
  progress.done();
  stats_.growthStoppedLeaves = builder.growthStopped();

  // Flatten depth first; each inner node's 8 children take the next 8 free slots.
  const uint64_t nodeCount = countNodes(root);
  require(nodeCount < kNoChild, "octree", "more than 2^32 nodes; raise max_leaf_entries");
  nodes_.reserve(nodeCount);
  boxes_.reserve(nodeCount);
  depths_.reserve(nodeCount);
  entries_.reserve(countEntries(root));
  const auto place = [&](auto& self, PendingNode& b, uint32_t index) -> void {
    boxes_[index] = b.box;
    depths_[index] = uint8_t(b.depth);
    if (!b.children) {
      nodes_[index].offset = entries_.size();
      nodes_[index].count = uint32_t(b.entries.size());
      entries_.insert(entries_.end(), b.entries.begin(), b.entries.end());
      std::vector<uint32_t>().swap(b.entries);
      return;
    }
    const uint32_t first = uint32_t(nodes_.size());
    nodes_[index].firstChild = first;
    nodes_.resize(first + 8);
    boxes_.resize(first + 8);
    depths_.resize(first + 8);
    for (uint32_t c = 0; c < 8; ++c) self(self, b.children[c], first + c);
    b.children.reset();
  };
  nodes_.resize(1);
  boxes_.resize(1);
  depths_.resize(1);
  place(place, root, 0);
  stats_.buildSeconds = clock.seconds();
  computeStats();
}

}  // namespace lzb
