#pragma once
// Scenes, frames and the exact reference for the surfel tests.
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "raycast/exact/ray_witness.hpp"
#include "raycast/exact/raycast_renderer.hpp"
#include "raycast/lzb/lzb_test_util.hpp"
#include "src/core/shading.hpp"
#include "src/image/metrics.hpp"
#include "src/image/test_reference.hpp"
#include "src/surfels/surfel_renderer.hpp"

namespace lzb::surfels::testing {

inline RenderOptions options(int threads = 2) {
  RenderOptions o;
  o.method = "surfels";
  o.threads = threads;
  o.quiet = true;
  return o;
}

// One closed sphere node placed at each of `centres` with radius `radius`.
inline Scene spheres(const std::vector<glm::dvec3>& centres, double radius = 1.0) {
  Scene s;
  s.source = "test spheres";
  s.root = s.addNode("root");
  const uint32_t ball = s.addNode("ball");
  s.nodes[ball].mesh = uvSphere(48, 24);
  for (const glm::dvec3& c : centres)
    s.nodes[s.root].instances.push_back(
        {ball, glm::scale(glm::translate(glm::dmat4(1.0), c), glm::dvec3(radius))});
  s.finalize();
  return s;
}

inline Camera lookAt(const glm::dvec3& eye, const glm::dvec3& target, int w, int h,
                     double fov = 45.0) {
  CameraSpec spec;
  spec.position = eye;
  spec.lookAt = target;
  spec.fovyDegrees = fov;
  spec.nearPlane = 0.05;
  spec.farPlane = 1000.0;
  return Camera(spec, w, h);
}

inline Framebuffer render(Renderer& r, const Camera& cam, FrameStats* stats = nullptr,
                          WorkShare share = {}) {
  Framebuffer fb(cam.width(), cam.height());
  FrameStats s;
  r.render(cam, 0, share, fb, s);
  if (stats) *stats = std::move(s);
  return fb;
}

// The exact ray caster's frame (depth and IDs at the pixel centres).
inline Framebuffer exact(const Scene& scene, const Camera& cam) {
  RaycastRenderer raycast(scene, options());
  return render(raycast, cam);
}

// Pixels the exact frame covers and `image` leaves empty.
inline size_t holes(const Framebuffer& image, const Framebuffer& exactFrame) {
  size_t n = 0;
  for (size_t i = 0; i < image.size(); ++i) n += exactFrame.covered(i) && !image.covered(i);
  return n;
}

// The report's accuracy: against raycast, witnessed by rays.
inline Accuracy accuracy(const Scene& scene, const Camera& cam, Framebuffer image) {
  RaycastRenderer raycast(scene, options());
  shadeFromIds(scene, cam, image);
  const RayWitness witness(scene, raycast.embreeScene(), cam);
  return compare(image, testing_util::renderReference(raycast, scene, cam), &witness);
}

}  // namespace lzb::surfels::testing
