#pragma once
// The frame's traversal (sections 4.2 and 4.5): depth first over the nodes in view; every visited
// node's triangles are drawn, and the traversal stops below a node whose cell projects to at most
// splat^2 pixels: such a node draws its representative as a splat instead of its triangles (or,
// with StopDraw::kTriangles, its own triangles as in section 4.2, without its subtree's).
#include <cstdint>
#include <vector>

#include "src/core/camera.hpp"
#include "src/sampletree/sample_tree.hpp"

namespace lzb::sampletree {

// One node's part of the frame: its triangles, or its splat.
struct Visit {
  uint32_t node;
  bool splat;
};

struct Traversal {
  std::vector<Visit> visits;  // preorder
  std::vector<uint32_t> stops;  // nodes where the traversal stopped (with or without a splat)
  uint64_t visited = 0;       // nodes reached in view (drawn, splatted or empty)
  uint64_t culled = 0;        // subtrees outside the view frustum
};

// Pixels of the screen rectangle around the projected cell; +inf when a corner is not in front
// of the near plane (the traversal never stops there).
double projectedCellPixels(const SampleTree& tree, const TreeNode& node, const Camera& camera);

// stopDraw: what a stopped node draws (section 4.5's splat of its representative, or section
// 4.2's own triangles).
enum class StopDraw { kSplat, kTriangles };

// Walked by up to `threads` threads; the result does not depend on their number.
Traversal traverse(const SampleTree& tree, const Camera& camera, int splat,
                   StopDraw stopDraw = StopDraw::kSplat, int threads = 1);

// Section 6.2's prefetch: the nodes with triangles among each stop and the `levels` levels below
// it, in preorder: what the next frames draw when the viewer comes closer (a stop that drew a
// splat draws its own triangles first, then its children).
std::vector<uint32_t> belowStops(const SampleTree& tree, const std::vector<uint32_t>& stops,
                                 int levels);

}  // namespace lzb::sampletree
