#pragma once
// Leaves whose triangles another pass draws (the hybrid method's point pass): the ray walk does
// not test them, so a ray walks on through them to what lies beyond. The decision is a function
// of the leaf and of its placement along the instance path, evaluated alike by the walker and by
// the pass that draws the leaves (both derive the placement from the same world matrix, composed
// root first as the frustum cull composes it, so they agree bit for bit).
#include <cstdint>
#include <glm/glm.hpp>

#include "src/core/bounds.hpp"

namespace lzb::localz {

// A leaf's placement: view depth of a node-frame point p is dot(depthGrad, p) + depthOffset, and
// the instance path scales areas by at most areaScale.
struct LeafPlacement {
  glm::dvec3 depthGrad{0.0};
  double depthOffset = 0.0;
  double areaScale = 1.0;
};

// The view depth of node-frame points under the node-frame -> world map `world`, as gradient and
// offset (the cull's and the walker's one formula).
inline void depthPlane(const glm::dmat4& world, const glm::dvec3& eye, const glm::dvec3& forward,
                       glm::dvec3& grad, double& offset) {
  grad = glm::transpose(glm::dmat3(world)) * forward;
  offset = glm::dot(glm::dvec3(world[3]) - eye, forward);
}

// The view-depth range of a node-frame box under a placement (the cull's and the filter's one
// formula).
inline void depthRange(const Bounds& b, const glm::dvec3& depthGrad, double depthOffset,
                       double& lo, double& hi) {
  const glm::dvec3 c = b.center(), h = 0.5 * b.extent();
  const double mid = glm::dot(depthGrad, c) + depthOffset;
  const double reach = glm::dot(glm::abs(depthGrad), h);
  lo = mid - reach;
  hi = mid + reach;
}

class LeafFilter {
 public:
  virtual ~LeafFilter() = default;
  // True when all triangles of scene node `node`, so placed, are drawn by the other pass (checked
  // first: the walk then skips the node's triangles, and its whole walk when it has no instances).
  virtual bool nodeDrawnElsewhere(uint32_t node, const LeafPlacement& p) const = 0;
  // True when node `node` (one with instances), so placed, and everything it instances are
  // drawn by the other pass: neither the cull nor the walk goes into it.
  virtual bool subtreeDrawnElsewhere(uint32_t /*node*/, const LeafPlacement& /*p*/) const {
    return false;
  }
  // True when leaf `leaf` of scene node `node`, so placed, is drawn by the other pass.
  virtual bool drawnElsewhere(uint32_t node, uint32_t leaf, const LeafPlacement& p) const = 0;
};

}  // namespace lzb::localz
