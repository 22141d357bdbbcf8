#include "src/core/shading.hpp"

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"

namespace lzb {

namespace {

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
};

Rgba8 shadePlaced(const Scene& scene, const Placement& p, uint32_t triangle, const glm::dvec3& eye) {
  const Mesh& mesh = scene.nodes[p.node].mesh;
  const glm::dvec3 n = glm::normalize(p.normalMatrix * glm::dvec3(mesh.normal(triangle)));
  const glm::dvec3 v0 =
      glm::dvec3(p.transform * glm::dvec4(glm::dvec3(mesh.vertex(triangle, 0)), 1.0));
  const bool facing = glm::dot(n, eye - v0) >= 0.0;
  return shade(mesh.colors[triangle], glm::vec3(n), facing, lightDirection(scene.light),
               float(scene.light.ambient));
}

}  // namespace

Rgba8 shadeTriangle(const Scene& scene, uint32_t node, uint32_t triangle, const glm::dmat4& transform,
                    const glm::dvec3& eye) {
  Placement p;
  p.set(node, transform);
  return shadePlaced(scene, p, triangle, eye);
}

void shadeFromIds(const Scene& scene, const Camera& camera, Framebuffer& fb) {
  const long n = long(fb.size());
  const glm::dvec3 eye = camera.position();
#pragma omp parallel
  {
    // Neighbouring pixels mostly show the same triangle, or another of the same placement:
    // remember the last one shaded and the last placement resolved.
    uint64_t lastId = kNoId;
    Rgba8 lastColor = kBackground;
    Placement placement;
#pragma omp for schedule(static)
    for (long i = 0; i < n; ++i) {
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
        lastColor = shadePlaced(scene, placement, uint32_t(id - placement.base), eye);
        lastId = id;
      }
      fb.color[size_t(i)] = lastColor;
    }
  }
}

}  // namespace lzb
