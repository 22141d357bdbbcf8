#include "src/sqrt5/horizon.hpp"

#include <algorithm>
#include <cmath>

namespace lzb::sqrt5 {

double HorizonLine::reach(const glm::dvec3& c, const glm::dvec3& cu, const glm::dvec3& cv) const {
  // descendants lie within 0.81 |u_0| of the root in the lattice: linearly, within 0.81 times the
  // hypotenuse of the spawning vectors' image heights; 1.2 for the curvature
  return 1.2 * 0.81 * std::hypot(up(cu) - up(c), up(cv) - up(c));
}

bool HorizonLine::hidden(const glm::dvec2& uv, HorizonCounts& counts) {
  const Sector& s = *view_.sector;
  const bool on = view_.onSurface(uv);
  const double near = view_.nearPlane;
  const glm::dvec2 du = uv + lattice_.u(0), dv = uv + lattice_.v(0);
  const auto inFront = [near](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    return a.z > near && b.z > near && c.z > near;
  };
  // Hidden by more than kMarginPixels: the nearer terrain's samples then cover the pixel too (at
  // its silhouette a point just below the horizon can fall into a pixel they do not reach).
  const double margin = kMarginPixels / view_.pixelScale;
  // first at the terrain's largest height: no noise evaluated
  const double top = view_.surface->spec.maxDisplacement();
  const auto atTop = [&](const glm::dvec2& p) {
    const glm::dvec3 b = s.base(p);
    return view_.toView({b.x, top, b.z});
  };
  const glm::dvec3 t = atTop(uv), tu = atTop(du), tv = atTop(dv);
  if (on && inFront(t, tu, tv) && up(t) + reach(t, tu, tv) + margin < horizon_) {
    ++counts.culledAtTop;
    return true;
  }
  const glm::dvec3 c = view_.point(uv), cu = view_.point(du), cv = view_.point(dv);
  if (on && inFront(c, cu, cv) && up(c) + reach(c, cu, cv) + margin < horizon_) {
    ++counts.culledByReal;
    return true;
  }
  if (on && c.z > near) horizon_ = std::max(horizon_, up(c));
  return false;
}

}  // namespace lzb::sqrt5
