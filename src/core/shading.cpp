#include "src/core/shading.hpp"

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"

namespace lzb {

Rgba8 shadeTriangle(const Scene& scene, uint32_t node, uint32_t triangle, const glm::dmat4& transform,
                    const glm::dvec3& eye) {
  const Mesh& mesh = scene.nodes[node].mesh;
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(transform)));
  const glm::dvec3 n = glm::normalize(normalMatrix * glm::dvec3(mesh.normals[triangle]));
  const glm::dvec3 v0 = glm::dvec3(transform * glm::dvec4(glm::dvec3(mesh.vertex(triangle, 0)), 1.0));
  const bool facing = glm::dot(n, eye - v0) >= 0.0;
  return shade(mesh.colors[triangle], glm::vec3(n), facing, lightDirection(scene.light),
               float(scene.light.ambient));
}

void shadeFromIds(const Scene& scene, const Camera& camera, Framebuffer& fb) {
  const long n = long(fb.size());
#pragma omp parallel
  {
    // Neighbouring pixels mostly show the same triangle: remember the last one shaded.
    uint64_t lastId = kNoId;
    Rgba8 lastColor = kBackground;
#pragma omp for schedule(static)
    for (long i = 0; i < n; ++i) {
      const uint64_t id = fb.id[size_t(i)];
      if (id == kNoId) {
        fb.color[size_t(i)] = kBackground;
        continue;
      }
      if (id != lastId) {
        auto ref = scene.resolve(id);
        lastColor = ref ? shadeTriangle(scene, ref->node, ref->triangle, ref->transform, camera.position())
                        : kBackground;
        lastId = id;
      }
      fb.color[size_t(i)] = lastColor;
    }
  }
}

}  // namespace lzb
