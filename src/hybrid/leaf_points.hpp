#pragma once
// The hybrid's point pass over octree leaves behind the partition plane whose triangles are too
// small to be worth exact drawing: the randomized z-buffer's rule (Wand et al., section 7.1)
// applied to the local z-buffering octree's leaves.
//
// Rule. A placed node with instances is sampled as one unit with everything under it, wherever
// it lies, when its bounds (instances included) pass the same two tests (an instanced field of
// 10^12 sub-pixel triangles is then a few thousand units, not a cull through every instance).
// A whole placed node is sampled as one unit, wherever it lies, when its triangles' bounds
// span a depth ratio (depthMax / depthMin)^2 of at most kNodeDepthRatio (the samples' density
// follows depthMin: rzb's eps) and its largest triangle, scaled by the instance path and seen at
// depthMin, covers less than `thresholdPx` pixels (d^2 / 10^4 by default, HybridParams):
// the cull then lists none of its leaves, so neither the near pass nor the rays see it, and its
// samples composite with both by depth. Otherwise, behind the plane, its leaves are judged one by
// one (content box wholly behind the plane, largest triangle below the threshold). The ray walk
// skips exactly what is sampled (the rule is its LeafFilter), so every triangle is drawn by one
// pass or the other, or by both where a triangle spans leaves of both kinds.
//
// Samples. A sampled leaf gets area x areaScale x (pixels per unit at depthMin)^2 x
// samplesPerPixel samples (area in the node frame, scaled by the path's largest area factor: an
// upper bound), stochastically rounded, at most 16 image-covering layers. Sample i of n takes
// stratum [i, i + 1) / n of the leaf's area prefix sums, jittered, and a uniform point of the
// triangle there. Randomness is Philox keyed by (seed, frame) with the counter (leaf key, i), the
// leaf key naming the leaf and its placement: any rank or thread draws the same samples.
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "raycast/lzb/lzb_cull.hpp"
#include "raycast/lzb/lzb_leaf_filter.hpp"
#include "src/core/camera.hpp"
#include "src/core/depth_key.hpp"
#include "src/core/philox_stream.hpp"
#include "src/hybrid/leaf_areas.hpp"
#include "src/splat/splatter.hpp"

namespace lzb::hybrid {

struct PointParams {
  int splat = 1;                 // d: samples are d x d splats
  double samplesPerPixel = 1.0;  // per pixel of projected area: oversample x ln(pixels) / d^2
  double thresholdPx = 0.0;      // a sampled leaf's largest projected triangle is below this
  bool dropBackfaces = true;
};

class SampledLeafRule : public localz::LeafFilter {
 public:
  // Leaves are judged behind zClip, which may be set once the plane is known (the whole-node
  // rule does not need it: the cull applies that one before the plane is placed).
  SampledLeafRule(const localz::LzbAccel& accel, const LeafAreas& areas, double pixelScale,
                  double thresholdPx)
      : accel_(accel), areas_(areas), pixelScale_(pixelScale), thresholdPx_(thresholdPx) {}
  void setPlane(double zClip) { zClip_ = zClip; }
  bool nodeDrawnElsewhere(uint32_t node, const localz::LeafPlacement& p) const override;
  bool drawnElsewhere(uint32_t node, uint32_t leaf, const localz::LeafPlacement& p) const override;
  bool subtreeDrawnElsewhere(uint32_t node, const localz::LeafPlacement& p) const override;
  // The rule with the leaf's nearest view depth known (the cull's CullLeaf::depthMin).
  bool sampled(uint32_t node, uint32_t leaf, double depthMin, double areaScale) const;
  // False when no leaf of the placed node can be sampled (judged at its farthest depth with its
  // smallest leaf's largest triangle), so its leaves need no look one by one.
  bool mayTakeLeaves(uint32_t node, const localz::LeafPlacement& p) const;

 private:
  // The whole-unit rule: a box of the unit (node frame) within the depth ratio, its largest
  // triangle (node frame) below the threshold at the box's nearest depth.
  bool wholeUnit(const Bounds& box, double maxArea, const localz::LeafPlacement& p) const;

  const localz::LzbAccel& accel_;
  const LeafAreas& areas_;
  double zClip_ = std::numeric_limits<double>::infinity(), pixelScale_, thresholdPx_;
};

constexpr uint32_t kWholeNode = ~uint32_t(0);
constexpr uint32_t kSubtree = ~uint32_t(0) - 1;  // the node and everything it instances
constexpr double kNodeDepthRatio = 1.5;

struct SampledLeaf {
  uint32_t path, leaf;  // localz::CulledScene::paths index; octree node of the path's scene node,
                        // or kWholeNode for all its triangles, kSubtree for all under it
  uint64_t key;         // Philox key of the leaf at this placement
  uint64_t samples;
  double depthMin;
};

struct SampledUnits {
  std::vector<SampledLeaf> leaves;  // the units with samples
  uint64_t accepted = 0;            // units the rule takes, with samples or none
};

// The placed nodes and culled leaves the rule samples, in cull order (which no rank count changes),
// with their sample counts. Prepares the areas' lists and sums (LeafAreas::prepareSampling) at the
// first unit the rule takes.
SampledUnits sampledLeaves(const localz::LzbAccel& accel, const LeafAreas& areas,
                           const localz::CulledScene& culled, const SampledLeafRule& rule,
                           const Camera& camera, const PointParams& params,
                           const SampleStream& stream);

struct PointCounts {
  uint64_t drawn = 0, backfacing = 0, splatted = 0;
};

// Splats the samples of leaves[i] for i in `mine` into keys (sized to the camera) on `threads`
// threads; the result depends on neither.
PointCounts splatLeaves(const localz::LzbAccel& accel, const LeafAreas& areas,
                        const localz::CulledScene& culled, std::span<const SampledLeaf> leaves,
                        std::span<const uint32_t> mine, const Camera& camera,
                        const PointParams& params, const SampleStream& stream, KeyBuffer& keys,
                        int threads);

}  // namespace lzb::hybrid
