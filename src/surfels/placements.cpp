#include "src/surfels/placements.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "src/core/visible_placements.hpp"

namespace lzb::surfels {

LevelChoice chooseLevel(double cellPx1, const SurfelParams& p) {
  if (!(cellPx1 < std::numeric_limits<double>::infinity())) return {};
  const auto passes = [&](int grid, int d) {
    return cellPx1 / grid <= p.cellFraction * p.coverSide(d);
  };
  for (size_t l = 0; l < p.grids.size(); ++l) {
    if (!passes(p.grids[l], p.sprite)) continue;
    int d = 1;
    while (!passes(p.grids[l], d)) ++d;
    return {int(l), d};
  }
  return {};
}

namespace {

// Each visible placement measured and switched to a level or polygons, in the walk's order.
struct Switch {
  const std::vector<Domain>& domains;
  const std::vector<Bounds>& meshBounds;
  const Camera& camera;
  const SurfelParams& params;
  const double tanX, tanY;
  std::vector<SurfelPlacement> out;

  // The cube's projected extent in pixels at the object's nearest depth. A cell's edges span
  // |right . e| across and |forward . e| in depth, which adds |x / z| of that off axis: the
  // largest |x / z| over the object's box corners (the ratio's extremes over a box with z > 0
  // lie at its corners), at most the frustum's edge.
  void measure(SurfelPlacement& p, const Domain& d, const Bounds& box) const {
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (int i = 0; i < 3; ++i) {
      const glm::dvec3 e = glm::dvec3(p.world[i]) * d.side;
      sx += std::abs(glm::dot(camera.right(), e));
      sy += std::abs(glm::dot(camera.up(), e));
      sz += std::abs(glm::dot(camera.forward(), e));
    }
    p.depthMin = std::numeric_limits<double>::infinity();
    double slopeX = 0.0, slopeY = 0.0;
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 v = glm::dvec3(p.world * glm::dvec4(box.corner(c), 1.0)) - camera.position();
      const double z = glm::dot(v, camera.forward());
      p.depthMin = std::min(p.depthMin, z);
      slopeX = std::max(slopeX, std::abs(glm::dot(v, camera.right())) / z);
      slopeY = std::max(slopeY, std::abs(glm::dot(v, camera.up())) / z);
    }
    if (p.depthMin <= camera.nearPlane()) {
      p.cellPx1 = std::numeric_limits<double>::infinity();
      return;
    }
    p.cellPx1 = camera.pixelsPerUnitAt(p.depthMin) *
                std::max(sx + std::min(slopeX, tanX) * sz, sy + std::min(slopeY, tanY) * sz);
  }

  void add(uint32_t node, const glm::dmat4& world, uint64_t idBase) {
    SurfelPlacement p;
    p.node = node;
    p.world = world;
    p.idBase = idBase;
    measure(p, domains[node], meshBounds[node]);
    const LevelChoice c = chooseLevel(p.cellPx1, params);
    p.level = c.level;
    p.sprite = c.sprite;
    out.push_back(p);
  }
};

}  // namespace

std::vector<SurfelPlacement> visiblePlacements(const Scene& scene, const std::vector<Domain>& domains,
                                         const std::vector<Bounds>& meshBounds,
                                         const Camera& camera, const SurfelParams& params) {
  const double halfW = 0.5 * camera.width(), halfH = 0.5 * camera.height();
  const double scale = camera.pixelsPerUnitAt(1.0);
  Switch s{domains, meshBounds, camera, params, halfW / scale, halfH / scale, {}};
  forEachVisiblePlacement(scene, meshBounds, camera.frustum(),
                          [&](uint32_t node, const glm::dmat4& world, uint64_t idBase,
                              const Bounds&) { s.add(node, world, idBase); });
  return std::move(s.out);
}

}  // namespace lzb::surfels
