#pragma once
// The terrain's sector parameterisation (Stamminger & Drettakis, section 3.4). Around g, the
// eye's projection onto the terrain's base plane (y = 0, node frame), the sector of base points
// the view can reach is
//   b(u, v) = g + (m + u p) d(v),   u in [-1, 1], v in [0, 1],
//   d(v) = 1 / (1 / dmin - v (1 / dmin - 1 / dmax)),
// with m the view direction projected onto the base plane (unit), p perpendicular to it, scaled so
// that u = +-1 reaches the image's side edges, d the distance along m. Projected, the image
// position of a base point is about proportional to 1 / d when looking along the ground, so a
// uniform (u, v) grid is about uniform in the image. dmin is where the image's lowest rays first
// meet the terrain (marched in 1 % steps; nothing nearer can be seen), times 0.9; dmax the
// farthest terrain corner along m (the sector is clipped to the terrain's extent: base points
// outside it are not drawn).
//
// The lattice's unit square maps to it by u = 2 s - 1, v = t. A constant-s line is a ray from g
// on the base plane, in a vertical plane through the eye: the terrain above it projects onto
// one image line, and a point farther along it is hidden when it projects below the highest point
// nearer along it (the horizon culling of the renderer).
#include <optional>

#include <glm/glm.hpp>

#include "src/core/camera.hpp"
#include "src/core/procedural.hpp"

namespace lzb::sqrt5 {

struct Sector {
  glm::dvec3 g{0.0}, m{0.0}, p{0.0};
  double invDmin = 1.0, invDmax = 0.0;
  double extent = 1.0;

  // The sector of `spec` (a terrain) placed by `world` for `camera`, or none when the view looks
  // too steeply up or down (within 12 degrees of vertical) or wider than 80 degrees to a side of
  // m, or the terrain lies behind: such views sample the terrain's own (u, v) square.
  static std::optional<Sector> make(const ProceduralSpec& spec, const glm::dmat4& world,
                                    const Camera& camera);
  double distance(double t) const { return 1.0 / (invDmin - t * (invDmin - invDmax)); }
  glm::dvec3 base(const glm::dvec2& st) const { return g + (m + (2.0 * st.x - 1.0) * p) * distance(st.y); }
  // The terrain's own parameters of a base point (inside the extent when both are in [0, 1]).
  glm::dvec2 terrainUv(const glm::dvec3& b) const { return {b.x / extent + 0.5, b.z / extent + 0.5}; }
};

}  // namespace lzb::sqrt5
