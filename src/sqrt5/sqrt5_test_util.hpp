#pragma once
// Scenes, frames and the exact reference for the sqrt5 tests.
#include <cmath>
#include <string>

#include "raycast/exact/ray_witness.hpp"
#include "raycast/exact/raycast_renderer.hpp"
#include "src/core/shading.hpp"
#include "src/image/metrics.hpp"
#include "src/image/test_reference.hpp"
#include "src/scene/load.hpp"
#include "src/sqrt5/sqrt5_renderer.hpp"

namespace lzb::sqrt5::testing {

inline RenderOptions options(int threads = 2) {
  RenderOptions o;
  o.method = "sqrt5";
  o.threads = threads;
  o.quiet = true;
  return o;
}

inline Camera defaultCamera(const Scene& s, int w, int h) {
  return Camera(withClipPlanes(*s.camera, s.bounds()), w, h);
}

inline Framebuffer render(Renderer& r, const Camera& cam, FrameStats* stats = nullptr,
                          WorkShare share = {}) {
  Framebuffer fb(cam.width(), cam.height());
  FrameStats s;
  r.render(cam, 0, share, fb, s);
  if (stats) *stats = std::move(s);
  return fb;
}

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

inline size_t covered(const Framebuffer& f) {
  size_t n = 0;
  for (size_t i = 0; i < f.size(); ++i) n += f.covered(i);
  return n;
}

// The report's accuracy: against raycast, witnessed by rays.
inline Accuracy accuracy(const Scene& scene, const Camera& cam, Framebuffer image) {
  RaycastRenderer raycast(scene, options());
  shadeFromIds(scene, cam, image);
  const RayWitness witness(scene, raycast.embreeScene(), cam);
  return compare(image, testing_util::renderReference(raycast, scene, cam), &witness);
}

inline bool sameFrame(const Framebuffer& a, const Framebuffer& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a.id[i] != b.id[i] || !(a.depth[i] == b.depth[i] || (std::isinf(a.depth[i]) && std::isinf(b.depth[i]))))
      return false;
  return true;
}

}  // namespace lzb::sqrt5::testing
