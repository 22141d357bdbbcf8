#include "tests/support/render.hpp"

#include <utility>

#include "raycast/exact/raycast_renderer.hpp"
#include "src/core/shading.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"

namespace lzb::test {

Framebuffer renderFrame(Renderer& r, const Camera& camera, FrameStats* stats, WorkShare share,
                        int frame) {
  Framebuffer fb(camera.width(), camera.height());
  FrameStats local;
  r.render(camera, frame, share, fb, local);
  if (stats) *stats = std::move(local);
  return fb;
}

Framebuffer exactFrame(const Scene& scene, const Camera& camera, const RenderOptions& options) {
  RaycastRenderer raycast(scene, options);
  return renderFrame(raycast, camera);
}

Framebuffer zbufferFrame(const Scene& scene, const Camera& camera, const RenderOptions& options,
                         bool shade, FrameStats* stats, WorkShare share) {
  ZBufferRenderer z(scene, options);
  Framebuffer fb = renderFrame(z, camera, stats, share);
  if (shade) shadeFromIds(scene, camera, fb);  // as the frame driver does after compositing
  return fb;
}

}  // namespace lzb::test
