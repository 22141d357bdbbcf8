#include "src/core/shading.hpp"

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/core/prefetch.hpp"

namespace lzb {

namespace {

// The frame's constants: the eye and the light, normalised once rather than at every pixel.
struct Lighting {
  glm::dvec3 eye;
  glm::vec3 toLight;
  float ambient;
  Lighting(const Scene& scene, const glm::dvec3& e)
      : eye(e), toLight(lightDirection(scene.light)), ambient(float(scene.light.ambient)) {}
};

// A placement of a node (a leaf of the instance tree): its expanded IDs [base, end), transform
// and normal matrix, worked out once for the run of pixels that show it.
struct Placement {
  uint64_t base = 1, end = 0;  // empty
  uint32_t node = 0;
  glm::dmat4 transform{1.0};
  glm::dmat3 normalMatrix{1.0};

  void set(uint32_t n, const glm::dmat4& m) {
    node = n;
    transform = m;
    normalMatrix = glm::transpose(glm::inverse(glm::dmat3(m)));
  }
  // transform * (p, 1), summed in glm's order ((c0 x + c1 y) + (c2 z + c3)): the same bits
  // without the w column's products.
  glm::dvec3 place(const glm::vec3& p) const {
    const glm::dvec3 c0(transform[0]), c1(transform[1]), c2(transform[2]), c3(transform[3]);
    return (c0 * double(p.x) + c1 * double(p.y)) + (c2 * double(p.z) + c3);
  }
};

Rgba8 shadePlaced(const Scene& scene, const Placement& p, uint32_t triangle, const Lighting& l) {
  const Mesh& mesh = scene.nodes[p.node].mesh;
  const glm::dvec3 n = glm::normalize(p.normalMatrix * glm::dvec3(mesh.normal(triangle)));
  const bool facing = glm::dot(n, l.eye - p.place(mesh.vertex(triangle, 0))) >= 0.0;
  return shade(mesh.color(triangle), glm::vec3(n), facing, l.toLight, l.ambient);
}

// Sub-pixel triangles are shaded once each from scattered indices and vertices: their triangle
// indices are fetched 16 pixels ahead, their corners and colour 8 ahead (within the placement).
void prefetchAhead(const Scene& scene, const Placement& p, const Framebuffer& fb, long i, long n) {
  constexpr long kIndices = 16, kCorners = 8;
  if (p.end <= p.base) return;
  const Mesh& mesh = scene.nodes[p.node].mesh;
  if (i + kIndices < n) {
    const uint64_t id = fb.id[size_t(i + kIndices)];
    if (id >= p.base && id < p.end) prefetchRead(&mesh.indices[3 * (id - p.base)]);
  }
  if (i + kCorners < n) {
    const uint64_t id = fb.id[size_t(i + kCorners)];
    if (id < p.base || id >= p.end) return;
    const uint32_t* c = &mesh.indices[3 * (id - p.base)];
    for (int k = 0; k < 3; ++k) prefetchRead(&mesh.positions[c[k]]);
    prefetchRead(&mesh.color(id - p.base));
  }
}

}  // namespace

Rgba8 shadeTriangle(const Scene& scene, uint32_t node, uint32_t triangle, const glm::dmat4& transform,
                    const glm::dvec3& eye) {
  Placement p;
  p.set(node, transform);
  return shadePlaced(scene, p, triangle, Lighting(scene, eye));
}

void shadeFromIds(const Scene& scene, const Camera& camera, Framebuffer& fb) {
  const long n = long(fb.size());
  const Lighting lighting(scene, camera.position());
#pragma omp parallel
  {
    // Neighbouring pixels mostly show the same triangle, or another of the same placement:
    // remember the last one shaded and the last placement resolved.
    uint64_t lastId = kNoId;
    Rgba8 lastColor = kBackground;
    Placement placement;
#pragma omp for schedule(static)
    for (long i = 0; i < n; ++i) {
      prefetchAhead(scene, placement, fb, i, n);
      const uint64_t id = fb.id[size_t(i)];
      if (id == kNoId) {
        fb.color[size_t(i)] = kBackground;
        continue;
      }
      if (id != lastId) {
        if (id < placement.base || id >= placement.end) {
          const auto ref = scene.resolve(id);
          if (!ref) {
            lastId = id;
            lastColor = kBackground;
            fb.color[size_t(i)] = lastColor;
            continue;
          }
          placement.set(ref->node, ref->transform);
          placement.base = id - ref->triangle;
          placement.end = placement.base + scene.nodes[ref->node].mesh.size();
        }
        lastColor = shadePlaced(scene, placement, uint32_t(id - placement.base), lighting);
        lastId = id;
      }
      fb.color[size_t(i)] = lastColor;
    }
  }
}

}  // namespace lzb
