#pragma once
// The one shading rule of every method: Lambert with one directional light and an ambient term,
// flat per triangle, two-sided (a triangle seen from its back is lit as if its normal faced the
// camera). The GLSL copy in src/zbuffer must stay equal to shade().
#include <cstdint>
#include <glm/glm.hpp>
#include <span>

#include "src/core/color.hpp"
#include "src/core/scene.hpp"

namespace lzb {

// normal: unit world-space normal; facesCamera: dot(normal, eye - vertex) >= 0.
inline Rgba8 shade(Rgba8 albedo, const glm::vec3& normal, bool facesCamera, const glm::vec3& toLight,
                   float ambient) {
  const glm::vec3 n = facesCamera ? normal : -normal;
  const float lambert = glm::max(glm::dot(n, toLight), 0.0f);
  const float k = ambient + (1.0f - ambient) * lambert;
  return packRgb(unpackRgb(albedo) * k);
}

inline glm::vec3 lightDirection(const Light& light) { return glm::vec3(glm::normalize(light.direction)); }

}  // namespace lzb

namespace lzb {

class Camera;
struct Framebuffer;

// Fills fb.color from fb.id with shade(): the colour of every exact pass comes from this one place.
void shadeFromIds(const Scene& scene, const Camera& camera, Framebuffer& fb);
// The same for the listed pixels alone: colors[p] from ids[p] for every p in `pixels`.
void shadePixels(const Scene& scene, const Camera& camera, std::span<const uint32_t> pixels,
                 std::span<const uint64_t> ids, std::span<Rgba8> colors);

// World-space shading inputs of one triangle placed by `transform`.
Rgba8 shadeTriangle(const Scene& scene, uint32_t node, uint32_t triangle, const glm::dmat4& transform,
                    const glm::dvec3& eye);

}  // namespace lzb
