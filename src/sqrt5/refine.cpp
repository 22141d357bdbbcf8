#include "src/sqrt5/refine.hpp"

#include <algorithm>
#include <cmath>

namespace lzb::sqrt5 {

ProceduralView ProceduralView::make(const ProceduralSurface& surface, const Sector* sector,
                                    const glm::dmat4& world, uint64_t idBase,
                                    const Camera& camera, double amin, int levels) {
  ProceduralView v;
  v.surface = &surface;
  v.sector = sector;
  v.toCamera = camera.view() * world;
  v.idBase = idBase;
  v.pixelScale = camera.pixelsPerUnitAt(1.0);
  v.width = camera.width();
  v.height = camera.height();
  v.cx = 0.5 * v.width;
  v.cy = 0.5 * v.height;
  v.nearPlane = camera.nearPlane();
  v.farPlane = camera.farPlane();
  v.amin = amin;
  v.levels = levels;
  return v;
}

double ProceduralView::projectedLength(const glm::dvec3& c, const glm::dvec3& e) const {
  const double z = std::max(c.z, nearPlane), s = pixelScale / z;
  const double dx = s * (e.x - c.x / z * e.z), dy = s * (e.y - c.y / z * e.z);
  return std::sqrt(dx * dx + dy * dy);
}

bool ProceduralView::undersampledBy(const glm::dvec3& c, const glm::dvec3& a,
                                    const glm::dvec3& b) const {
  const double side = std::max(projectedLength(c, a), projectedLength(c, b));
  if (side * side <= amin) return false;
  // Descendants stay within 0.81 |u_i| of the sample in (u, v); 1.5 leaves room for curvature.
  // Refined only when that ball meets the view frustum (camera space, z the depth).
  const double r = 1.5 * std::max(glm::length(a), glm::length(b));
  if (c.z + r < nearPlane || c.z - r > farPlane) return false;
  const double tx = cx / pixelScale, ty = cy / pixelScale;
  const double nx = std::sqrt(1.0 + tx * tx), ny = std::sqrt(1.0 + ty * ty);
  return (tx * c.z - c.x) / nx >= -r && (tx * c.z + c.x) / nx >= -r &&
         (ty * c.z - c.y) / ny >= -r && (ty * c.z + c.y) / ny >= -r;
}

void RefineCounts::merge(const RefineCounts& o) {
  roots += o.roots;
  generated += o.generated;
  refined += o.refined;
  drawn += o.drawn;
  atLevelBound += o.atLevelBound;
  deepest = std::max(deepest, o.deepest);
}

int initialSide(double worldArea, double distance, double pixelScale, double amin) {
  const double d = std::max(distance, 1e-300);
  const double ns = worldArea * pixelScale * pixelScale / (amin * d * d);
  if (!(ns < double(kMaxInitialSide) * kMaxInitialSide)) return kMaxInitialSide;
  // Rounded up to the ladder 2^(k/4): a moving camera keeps its grid (and the cached forests)
  // until its distance changes by 19 %.
  const double k = std::ceil(4.0 * std::log2(std::max(std::sqrt(ns), 1.0)) - 1e-9);
  return std::clamp(int(std::ceil(std::exp2(k / 4.0) - 1e-9)), 1, kMaxInitialSide);
}

}  // namespace lzb::sqrt5
