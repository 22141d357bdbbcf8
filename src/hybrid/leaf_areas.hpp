#pragma once
// What the hybrid's point pass needs of every leaf of the local z-buffering octrees
// (raycast/lzb_accel.hpp), and of every node as a whole: its triangles listed along a Morton
// curve of their centroids, with the inclusive prefix sums of their areas (node frame, double),
// and its largest triangle's area. Stratified samples along a spatially coherent list spread
// evenly over the surface (as rzb's distribution list in octree order does), so a pixel is less
// often left without a sample. Built once per scene node: instanced content costs its unique
// triangles only.
#include <cstdint>
#include <span>
#include <vector>

#include "raycast/lzb_accel.hpp"

namespace lzb::hybrid {

class LeafAreas {
 public:
  explicit LeafAreas(const LzbAccel& accel);
  // The triangles of leaf `leaf` of scene node `node` (those of leafTriangles, along the curve)
  // and the inclusive prefix sums of their areas.
  std::span<const uint32_t> order(uint32_t node, uint32_t leaf) const {
    const PerNode& n = nodes_[node];
    return {n.order.data() + n.begin[leaf], n.begin[leaf + 1] - n.begin[leaf]};
  }
  std::span<const double> prefix(uint32_t node, uint32_t leaf) const {
    const PerNode& n = nodes_[node];
    return {n.prefix.data() + n.begin[leaf], n.begin[leaf + 1] - n.begin[leaf]};
  }
  double total(uint32_t node, uint32_t leaf) const {
    const std::span<const double> p = prefix(node, leaf);
    return p.empty() ? 0.0 : p.back();
  }
  double maxArea(uint32_t node, uint32_t leaf) const { return nodes_[node].maxArea[leaf]; }
  // The same for all triangles of the node.
  std::span<const uint32_t> nodeOrder(uint32_t node) const { return nodes_[node].wholeOrder; }
  std::span<const double> nodePrefix(uint32_t node) const { return nodes_[node].wholePrefix; }
  double nodeMaxArea(uint32_t node) const { return nodes_[node].wholeMax; }
  uint64_t memoryBytes() const;

 private:
  struct PerNode {
    std::vector<uint32_t> begin;   // per octree node (+1): start in order and prefix
    std::vector<uint32_t> order;   // per listed triangle
    std::vector<double> prefix;    // per listed triangle
    std::vector<double> maxArea;   // per octree node
    std::vector<uint32_t> wholeOrder;  // all of the node's triangles, along the curve
    std::vector<double> wholePrefix;   // per position of wholeOrder
    double wholeMax = 0.0;
  };
  std::vector<PerNode> nodes_;
};

}  // namespace lzb::hybrid
