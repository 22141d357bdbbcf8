#pragma once
// Horizon occlusion culling of a terrain's initial samples (section 3.4). The initial grid is
// processed line by line (constant s: one ray from the eye's ground point, one image line),
// front to back (t ascending). The horizon is the highest image position of the terrain points
// met so far on the line; a later point that projects below it is hidden by the terrain between
// (the terrain is a heightfield and the line lies in a vertical plane through the eye). A culled
// root drops its whole tree, so its descendants' reach is added: they lie within 0.81 |u_0| of it
// in the lattice, so (to first order) within 0.81 x the hypotenuse of the image heights of its
// spawning vectors' ends above or below it; 1.2 for the curvature (the paper extrapolates the
// children's elevation by the terrain gradient; this is that gradient composed with the
// projection). Two tests: first everything at the terrain's largest height (no noise evaluated:
// most far points of a view along the ground go here), then at the real heights. A root is culled
// only when that reach stays kMarginPixels below the horizon: a point hidden by the surface but
// just below its silhouette can fall into a pixel no nearer sample reaches.
#include <cstdint>

#include "src/sqrt5/refine.hpp"

namespace lzb::sqrt5 {

constexpr double kMarginPixels = 1.5;

struct HorizonCounts {
  uint64_t culledAtTop = 0;   // culled by the first test (largest height)
  uint64_t culledByReal = 0;  // culled by the second (real height, extrapolated)
};

// The culling state of one line.
class HorizonLine {
 public:
  HorizonLine(const ProceduralView& view, const Sqrt5Lattice& lattice) : view_(view), lattice_(lattice) {}
  // Whether the root at uv (the next one along the line, front to back) and its tree are hidden;
  // when not, the root's own height raises the horizon.
  bool hidden(const glm::dvec2& uv, HorizonCounts& counts);

 private:
  double reach(const glm::dvec3& c, const glm::dvec3& cu, const glm::dvec3& cv) const;
  double up(const glm::dvec3& c) const { return c.y / c.z; }  // image height, any focal length

  const ProceduralView& view_;
  const Sqrt5Lattice& lattice_;
  double horizon_ = -1e300;
};

}  // namespace lzb::sqrt5
