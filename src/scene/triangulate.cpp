#include "src/scene/triangulate.hpp"

#include <cmath>

namespace lzb {

namespace {

double cross2(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// True when p lies inside or on the counter-clockwise triangle (a, b, c).
bool inTriangle(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b,
                const glm::dvec2& c) {
  return cross2(a, b, p) >= 0.0 && cross2(b, c, p) >= 0.0 && cross2(c, a, p) >= 0.0;
}

}  // namespace

void triangulatePolygon(std::span<const glm::dvec3> polygon,
                        std::vector<std::array<uint32_t, 3>>& triangles) {
  const uint32_t n = uint32_t(polygon.size());
  if (n < 3) return;
  if (n == 3) {
    triangles.push_back({0, 1, 2});
    return;
  }
  // Newell normal: robust for non-planar and concave polygons.
  glm::dvec3 normal(0.0);
  for (uint32_t i = 0; i < n; ++i) {
    const glm::dvec3 &a = polygon[i], &b = polygon[(i + 1) % n];
    normal +=
        glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  // Project along the dominant normal axis, mirrored so the polygon runs counter-clockwise.
  const glm::dvec3 an = glm::abs(normal);
  const int drop = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
  const int u = (drop + 1) % 3, v = (drop + 2) % 3;
  const double flip = normal[drop] < 0.0 ? -1.0 : 1.0;
  std::vector<glm::dvec2> p(n);
  for (uint32_t i = 0; i < n; ++i) p[i] = {polygon[i][u], flip * polygon[i][v]};

  std::vector<uint32_t> ring(n);
  for (uint32_t i = 0; i < n; ++i) ring[i] = i;
  const bool flat = !(glm::length(normal) > 0.0) || !std::isfinite(glm::length(normal));
  size_t at = 0;
  while (ring.size() > 3) {
    const size_t m = ring.size();
    bool clipped = false;
    for (size_t tries = 0; tries < m && !flat; ++tries, at = (at + 1) % m) {
      const uint32_t a = ring[(at + m - 1) % m], b = ring[at], c = ring[(at + 1) % m];
      if (!(cross2(p[a], p[b], p[c]) > 0.0)) continue;  // reflex or collinear corner
      bool empty = true;
      for (uint32_t k : ring)
        if (k != a && k != b && k != c && inTriangle(p[k], p[a], p[b], p[c])) {
          empty = false;
          break;
        }
      if (!empty) continue;
      triangles.push_back({a, b, c});
      ring.erase(ring.begin() + std::ptrdiff_t(at));
      at %= ring.size();
      clipped = true;
      break;
    }
    if (!clipped) {
      // No clean ear (degenerate or self-intersecting): cut the current corner regardless.
      const size_t k = at % m;
      triangles.push_back({ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]});
      ring.erase(ring.begin() + std::ptrdiff_t(k));
      at = k % ring.size();
    }
  }
  triangles.push_back({ring[0], ring[1], ring[2]});
}

}  // namespace lzb
