#include "src/sqrt5/sector.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace lzb::sqrt5 {

namespace {

// Directions (node frame) through points along the image's border, 16 per side.
std::vector<glm::dvec3> borderRays(const Camera& camera, const glm::dmat3& toNode) {
  std::vector<glm::dvec3> rays;
  const double w = camera.width(), h = camera.height();
  constexpr int kPerSide = 16;
  for (int k = 0; k <= kPerSide; ++k) {
    const double f = double(k) / kPerSide;
    for (const glm::dvec2& px : {glm::dvec2(f * w, 0.0), glm::dvec2(f * w, h), glm::dvec2(0.0, f * h),
                                 glm::dvec2(w, f * h)})
      rays.push_back(toNode * camera.pixelDirection(px.x, px.y));
  }
  return rays;
}

// The m-distance (along m) where the ray from eye along r first meets the terrain, marching in
// steps of 1 % from the near plane; the far plane's when it meets none.
double firstHit(const ProceduralSpec& spec, const glm::dvec3& eye, const glm::dvec3& r,
                const glm::dvec3& m, double nearPlane, double farPlane) {
  for (double t = nearPlane; t < farPlane; t *= 1.01) {
    const glm::dvec3 q = eye + t * r;
    if (q.y <= spec.position(q.x / spec.size + 0.5, q.z / spec.size + 0.5).y) return glm::dot(q - eye, m);
  }
  return glm::dot(farPlane * r, m);
}

}  // namespace

std::optional<Sector> Sector::make(const ProceduralSpec& spec, const glm::dmat4& world,
                                   const Camera& camera) {
  const glm::dmat4 inv = glm::inverse(world);
  const glm::dmat3 toNode(inv);
  const glm::dvec3 eye(inv * glm::dvec4(camera.position(), 1.0));
  const glm::dvec3 forward = toNode * camera.forward();
  Sector s;
  s.extent = spec.size;
  s.g = {eye.x, 0.0, eye.z};
  const glm::dvec3 flat(forward.x, 0.0, forward.z);
  if (glm::length(flat) < std::sin(glm::radians(12.0)) * glm::length(forward)) return std::nullopt;
  s.m = glm::normalize(flat);
  const glm::dvec3 side(-s.m.z, 0.0, s.m.x);
  double halfTan = 0.0;
  for (const glm::dvec3& r : borderRays(camera, toNode)) {
    const double a = glm::dot(r, s.m), b = glm::dot(r, side);
    if (a <= std::cos(glm::radians(80.0)) * std::hypot(a, b)) return std::nullopt;
    halfTan = std::max(halfTan, std::abs(b / a));
  }
  s.p = side * (1.02 * halfTan);
  // Nothing nearer than where the image's lowest rays first meet the terrain can be seen (the
  // terrain stays below them until then), less 10 % for what lies between those rays.
  double dmin = 1e300;
  constexpr int kBottomRays = 16;
  for (int k = 0; k <= kBottomRays; ++k) {
    const glm::dvec3 r = toNode * camera.pixelDirection(camera.width() * double(k) / kBottomRays,
                                                        camera.height());
    dmin = std::min(dmin, firstHit(spec, eye, r, s.m, camera.nearPlane(), camera.farPlane()));
  }
  dmin = std::max(0.9 * dmin, std::max(1e-4 * spec.size, camera.nearPlane()));
  double dmax = 0.0;
  for (double cx : {-0.5, 0.5})
    for (double cz : {-0.5, 0.5})
      dmax = std::max(dmax, glm::dot(glm::dvec3(cx * spec.size, 0.0, cz * spec.size) - s.g, s.m));
  dmax = std::min(dmax, camera.farPlane());
  if (!(dmax > dmin * 1.001) || dmin >= 1e299) return std::nullopt;
  s.invDmin = 1.0 / dmin;
  s.invDmax = 1.0 / dmax;
  return s;
}

}  // namespace lzb::sqrt5
