#pragma once
// Where a frame of the sample tree can differ from the exact image: only around the nodes where
// the traversal stopped. Every other visited node draws all its triangles, and a stopped node's
// triangles (and its subtree's) lie in its cell's bounding sphere, while its splat covers the
// splat x splat pixels around its representative. The union of those pixels bounds the wrong
// pixels of the frame (reported as approximated_pixels; the accuracy test holds frames to it).
#include <cstdint>
#include <vector>

#include "src/core/camera.hpp"
#include "src/sampletree/sample_tree.hpp"

namespace lzb::sampletree {

// Pixels of the image inside the screen rectangle of a stopped node's bounding sphere or under
// its splat, counted once each.
// splat: the splat size, 0 when stopped nodes draw their triangles instead.
uint64_t approximatedPixels(const SampleTree& tree, const std::vector<uint32_t>& stops,
                            const Camera& camera, int splat, int threads = 1);

}  // namespace lzb::sampletree
