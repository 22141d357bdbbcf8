#include "tests/support/reference.hpp"

#include "raycast/exact/ray_witness.hpp"
#include "raycast/exact/raycast_renderer.hpp"
#include "src/core/shading.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"
#include "tests/support/render.hpp"

namespace lzb::test {

ReferenceFrame renderReference(Renderer& exact, const Scene& scene, const Camera& camera,
                               int frame) {
  const auto render = [&](const Camera& c) {
    Framebuffer fb(c.width(), c.height());
    FrameStats stats;
    exact.render(c, frame, WorkShare{}, fb, stats);
    shadeFromIds(scene, c, fb);  // as the frame driver does after compositing
    return fb;
  };
  return reduceReference(render(camera), render(subsampleCamera(camera)));
}

ReferenceFrame zbufferReference(const Scene& scene, const Camera& camera) {
  ZBufferRenderer z(scene, RenderOptions{});
  return renderReference(z, scene, camera);
}

Accuracy accuracy(const Scene& scene, const Camera& camera, Framebuffer image,
                  const RenderOptions& raycastOptions) {
  RaycastRenderer raycast(scene, raycastOptions);
  shadeFromIds(scene, camera, image);
  const RayWitness witness(scene, raycast.embreeScene(), camera);
  return compare(image, renderReference(raycast, scene, camera), &witness);
}

double visibleInPixelRate(const Framebuffer& test, const Scene& scene, const Camera& camera,
                          int factor, int margin) {
  const Camera fine(camera.spec(), camera.width() * factor, camera.height() * factor);
  const Framebuffer ref = zbufferFrame(scene, fine);
  size_t correct = 0;
  for (int y = 0; y < test.height; ++y)
    for (int x = 0; x < test.width; ++x) {
      const uint64_t id = test.id[test.index(x, y)];
      bool ok = false;
      for (int sy = y * factor - margin; sy < (y + 1) * factor + margin && !ok; ++sy)
        for (int sx = x * factor - margin; sx < (x + 1) * factor + margin && !ok; ++sx)
          if (sx >= 0 && sy >= 0 && sx < ref.width && sy < ref.height)
            ok = ref.id[ref.index(sx, sy)] == id;
      correct += ok;
    }
  return double(correct) / double(test.size());
}

}  // namespace lzb::test
