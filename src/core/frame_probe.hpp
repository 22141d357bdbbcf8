#pragma once
// The frame's way (the hybrid's step 0, src/hybrid/README.md) decided for a whole data-parallel
// frame (--distribute data, src/regions/share.hpp): every part casts the coarse rays and each
// ray's nearest hit is taken over the parts of every rank; every part counts what lies in front
// of the probe's plane placed from those hits, and the counts are summed over the parts; every
// part then draws the frame the one way chosen from the sums. Minima and integer sums do not
// depend on which rank holds which part, so the choice is the same on any number of ranks.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "src/core/camera.hpp"
#include "src/core/renderer.hpp"

namespace lzb {

struct ProbeCounts {
  uint64_t triangles = 0;       // of the culled leaves in front of the probe's plane
  uint64_t sampledUnits = 0;    // units the point pass takes whole, culled in front of it
  uint64_t sceneTriangles = 0;  // the part's expanded triangles
};

class FrameProbe {
 public:
  virtual ~FrameProbe() = default;
  // The coarse rays of this frame's probe; 0 when the way is not probed (--frame-way local or
  // rays).
  virtual size_t probeRays(const Camera& camera) const = 0;
  // Phase 1: this part's nearest hit depth per coarse ray (infinity: none), valid until its next
  // call.
  virtual std::span<const double> coarseRayDepths(const Camera& camera) = 0;
  // Phase 2: this part's counts in front of the probe's plane, placed from the frame's depths.
  virtual ProbeCounts probe(const Camera& camera, std::span<const double> frameDepths) = 0;
  // The choice from the frame's depths and counts (casting every pixel, or not); its figures go
  // to stats' shared ones.
  virtual bool everyPixelPays(const Camera& camera, std::span<const double> frameDepths,
                              const ProbeCounts& frame, FrameStats& stats) const = 0;
  // Phase 3: the next render() draws its frame this way.
  virtual void setFrameWay(bool everyPixel) = 0;
};

}  // namespace lzb
