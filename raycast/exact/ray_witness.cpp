#include "raycast/exact/ray_witness.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "raycast/exact/raycast_renderer.hpp"

namespace lzb {
namespace {

// A convex polygon: a triangle clipped by 2 depth planes (5 vertices at most), then by the 4 sides
// of a pixel (one more vertex each): 9 at most.
template <typename Point>
struct Polygon {
  std::array<Point, 9> v;
  int n = 0;
  void add(const Point& p) { v[size_t(n++)] = p; }
};

// Sutherland-Hodgman: the part of `in` where inside(p) >= 0 (inside is affine along edges).
template <typename Point, typename Inside>
Polygon<Point> clip(const Polygon<Point>& in, Inside inside) {
  Polygon<Point> out;
  for (int k = 0; k < in.n; ++k) {
    const Point& a = in.v[size_t(k)];
    const Point& b = in.v[size_t((k + 1) % in.n)];
    const double da = inside(a), db = inside(b);
    if (da >= 0.0) out.add(a);
    if ((da >= 0.0) != (db >= 0.0)) out.add(a + (da / (da - db)) * (b - a));
  }
  return out;
}

Polygon<glm::dvec3> worldTriangle(const Scene& scene, const Scene::TriangleRef& ref) {
  const Mesh& mesh = scene.nodes[ref.node].mesh;
  Polygon<glm::dvec3> t;
  for (int k = 0; k < 3; ++k)
    t.add(glm::dvec3(ref.transform * glm::dvec4(glm::dvec3(mesh.vertex(ref.triangle, k)), 1.0)));
  return t;
}

// Step 1 of the rule: T's part between near and far, in pixel coordinates, inside pixel (x, y).
Polygon<glm::dvec2> partInPixel(const Polygon<glm::dvec3>& triangle, const Camera& camera, int x,
                                int y) {
  const auto depth = [&](const glm::dvec3& p) { return camera.viewDepth(p); };
  Polygon<glm::dvec3> slab =
      clip(triangle, [&](const glm::dvec3& p) { return depth(p) - camera.nearPlane(); });
  slab = clip(slab, [&](const glm::dvec3& p) { return camera.farPlane() - depth(p); });
  Polygon<glm::dvec2> p;
  for (int k = 0; k < slab.n; ++k) p.add(glm::dvec2(camera.project(slab.v[size_t(k)])));
  const double x0 = x, x1 = x + 1.0, y0 = y, y1 = y + 1.0;
  p = clip(p, [&](const glm::dvec2& q) { return q.x - x0; });
  p = clip(p, [&](const glm::dvec2& q) { return x1 - q.x; });
  p = clip(p, [&](const glm::dvec2& q) { return q.y - y0; });
  return clip(p, [&](const glm::dvec2& q) { return y1 - q.y; });
}

double area(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}

// Calls hit(point) on the n^2 centroids of triangle (a, b, c)'s regular subdivision, stopping
// when it returns true.
template <typename Hit>
bool anyLatticePoint(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, int n,
                     Hit hit) {
  const glm::dvec2 u = (b - a) / double(n), v = (c - a) / double(n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      if (hit(a + (i + 1.0 / 3.0) * u + (j + 1.0 / 3.0) * v)) return true;
      if (i + j < n - 1 && hit(a + (i + 2.0 / 3.0) * u + (j + 2.0 / 3.0) * v)) return true;
    }
  return false;
}

// Step 2 of the rule: P's centroid, then lattice points of its fan triangles by area.
template <typename Hit>
bool anyPointOf(const Polygon<glm::dvec2>& p, Hit hit) {
  glm::dvec2 c(0.0);
  for (int k = 0; k < p.n; ++k) c += p.v[size_t(k)] / double(p.n);
  if (hit(c)) return true;
  double total = 0.0;
  for (int k = 0; k < p.n; ++k) total += area(c, p.v[size_t(k)], p.v[size_t((k + 1) % p.n)]);
  if (!(total > 0.0)) return false;  // P is a segment or a point: the centroid was its ray
  for (int k = 0; k < p.n; ++k) {
    const glm::dvec2& a = p.v[size_t(k)];
    const glm::dvec2& b = p.v[size_t((k + 1) % p.n)];
    const double share = area(c, a, b) / total;
    const int n = std::max(1, int(std::floor(std::sqrt(kWitnessRays * share))));
    if (anyLatticePoint(c, a, b, n, hit)) return true;
  }
  return false;
}

}  // namespace

bool anyWitnessRay(const Scene& scene, const Camera& camera, int x, int y, uint64_t id,
                   const std::function<bool(const glm::dvec3&)>& ray) {
  const std::optional<Scene::TriangleRef> ref = scene.resolve(id);
  if (!ref) return false;
  const Polygon<glm::dvec2> p = partInPixel(worldTriangle(scene, *ref), camera, x, y);
  if (p.n < 3) return false;  // T does not reach the pixel between near and far
  return anyPointOf(p, [&](const glm::dvec2& q) { return ray(camera.pixelDirection(q.x, q.y)); });
}

bool RayWitness::visibleInPixel(int x, int y, uint64_t id) const {
  return anyWitnessRay(scene_, camera_, x, y, id, [&](const glm::dvec3& dir) {
    return embree_.intersect(camera_.position(), dir, camera_.nearPlane(), camera_.farPlane()).id ==
           id;
  });
}

WitnessScene::WitnessScene(const Scene& scene, const Renderer* reference,
                           const RenderOptions& options)
    : scene_(scene) {
  // The raycast reference traces this very scene already: its BVHs serve the witness too.
  if (const auto* raycast = dynamic_cast<const RaycastRenderer*>(reference)) {
    embree_ = &raycast->embreeScene();
    return;
  }
  owned_ = std::make_unique<EmbreeScene>(scene, withRenderOptions({}, options));
  embree_ = owned_.get();
}

}  // namespace lzb
