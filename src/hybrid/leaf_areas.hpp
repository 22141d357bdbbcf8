#pragma once
// What the hybrid's point pass needs of every leaf of the local z-buffering octrees
// (raycast/lzb/lzb_accel.hpp), and of every node as a whole: its triangles listed along a Morton
// curve of their centroids, with the inclusive prefix sums of their areas (node frame, double),
// and its largest triangle's area; and the same sums over a node's instances, for the point pass
// to take a whole instanced subtree as one unit. Stratified samples along a spatially coherent
// list spread evenly over the surface (as rzb's distribution list in octree order does), so a pixel
// is less often left without a sample. Built once per scene node: instanced content costs its
// unique triangles only. The largest areas, which decide what the point pass takes, are built at
// once; the lists and sums (~35 bytes a triangle), which only sampling reads, when a frame first
// samples (prepareSampling): a scene whose frames never sample does not pay for them.
#include <cstdint>
#include <span>
#include <vector>

#include "raycast/lzb/lzb_accel.hpp"
#include "src/core/affine.hpp"

namespace lzb::hybrid {

class LeafAreas {
 public:
  explicit LeafAreas(const localz::LzbAccel& accel);
  // Builds the lists and sums below on the first call (not thread-safe: the point pass's caller
  // calls it before its threads read them); the accel must outlive this object.
  void prepareSampling() const;
  bool samplingPrepared() const { return prepared_; }
  double samplingSeconds() const { return samplingSeconds_; }  // prepareSampling's
  // The triangles of leaf `leaf` of scene node `node` (those of leafTriangles, along the curve)
  // and the inclusive prefix sums of their areas. (After prepareSampling, as every accessor of
  // lists and sums below.)
  std::span<const uint32_t> order(uint32_t node, uint32_t leaf) const {
    const Sampling& n = sampling_[node];
    return {n.order.data() + n.begin[leaf], n.begin[leaf + 1] - n.begin[leaf]};
  }
  std::span<const double> prefix(uint32_t node, uint32_t leaf) const {
    const Sampling& n = sampling_[node];
    return {n.prefix.data() + n.begin[leaf], n.begin[leaf + 1] - n.begin[leaf]};
  }
  double total(uint32_t node, uint32_t leaf) const {
    const std::span<const double> p = prefix(node, leaf);
    return p.empty() ? 0.0 : p.back();
  }
  double maxArea(uint32_t node, uint32_t leaf) const { return nodes_[node].maxArea[leaf]; }
  // The same for all triangles of the node.
  std::span<const uint32_t> nodeOrder(uint32_t node) const { return sampling_[node].wholeOrder; }
  std::span<const double> nodePrefix(uint32_t node) const { return sampling_[node].wholePrefix; }
  // A position of nodePrefix at or before the first one above `area` (a guide table: one entry
  // per triangle's share of the total), so a search from it takes a step or two.
  uint64_t nodeGuide(uint32_t node, double area) const {
    const Sampling& n = sampling_[node];
    const double b = area * double(n.guide.size()) / n.wholePrefix.back();
    return b >= 1.0 ? n.guide[std::min(size_t(b) - 1, n.guide.size() - 1)] : 0;
  }
  double nodeMaxArea(uint32_t node) const { return nodes_[node].wholeMax; }
  // The smallest maxArea over the node's leaves with triangles (infinite without any).
  double leastLeafMaxArea(uint32_t node) const { return nodes_[node].leastLeafMax; }
  // The node with everything it instances, for the point pass to sample a whole instanced
  // subtree. Its instances flattened: chains of nodes with instances only are replaced by their
  // instances, composed, level by level while a node keeps at most kFlatBudget entries (nested
  // 2 x 2 instancing then costs one entry per 6 levels when a sample descends).
  struct FlatInstance {
    uint32_t node;
    Affine transform, inverse;  // entry node frame -> this node's frame, and back
    uint64_t idOffset;          // the entry's expanded ID 0 relative to this node's
  };
  static constexpr size_t kFlatBudget = 4096;
  static constexpr size_t kFlatTotal = size_t(1) << 18;  // entries over all nodes (~56 MB)
  std::span<const FlatInstance> flat(uint32_t node) const { return nodes_[node].flat; }
  // Inclusive prefix sums of [its own triangles' area, flat entry 0's subtree area, ...] (node
  // frame; an entry's area scaled by its transform's largest area factor, maxAreaScale, so an
  // upper bound past similarity transforms), and the largest triangle area under the node.
  std::span<const double> flatPrefix(uint32_t node) const { return sampling_[node].flatPrefix; }
  double subtreeArea(uint32_t node) const { return sampling_[node].flatPrefix.back(); }
  double subtreeMaxArea(uint32_t node) const { return nodes_[node].subtreeMax; }
  // Bytes held: the largest areas, and the lists and sums once prepared.
  uint64_t memoryBytes() const;

 private:
  struct PerNode {                // built at once
    std::vector<double> maxArea;  // per octree node
    double wholeMax = 0.0, leastLeafMax = 0.0;
    std::vector<FlatInstance> flat;
    double subtreeMax = 0.0;
  };
  struct Sampling {                // built by prepareSampling
    std::vector<uint32_t> begin;   // per octree node (+1): start in order and prefix
    std::vector<uint32_t> order;   // per listed triangle
    std::vector<double> prefix;    // per listed triangle
    std::vector<uint32_t> wholeOrder;  // all of the node's triangles, along the curve
    std::vector<double> wholePrefix;   // per position of wholeOrder
    std::vector<uint32_t> guide;       // [b]: the first position whose prefix passes b / size of it
    std::vector<double> flatPrefix;    // 1 + flat entries
  };
  void listAlongCurve(uint32_t node, Sampling& out) const;
  std::vector<FlatInstance> flatten(const localz::LzbAccel& accel, uint32_t node) const;
  const localz::LzbAccel& accel_;
  std::vector<PerNode> nodes_;
  mutable std::vector<Sampling> sampling_;
  mutable bool prepared_ = false;
  mutable double samplingSeconds_ = 0.0;
  size_t flatTotal_ = 0;
};

}  // namespace lzb::hybrid
