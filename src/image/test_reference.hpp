#pragma once
// Tests' exact reference in one process: an exact renderer at the pixel centres and at the 4x4
// sub-samples, shaded and reduced (the CLI does the same through mpi::FrameDriver).
#include "src/core/renderer.hpp"
#include "src/core/shading.hpp"
#include "src/image/reference.hpp"

namespace lzb::testing_util {

inline ReferenceFrame renderReference(Renderer& exact, const Scene& scene, const Camera& camera,
                                      int frame = 0) {
  const auto render = [&](const Camera& c) {
    Framebuffer fb(c.width(), c.height());
    FrameStats stats;
    exact.render(c, frame, WorkShare{}, fb, stats);
    shadeFromIds(scene, c, fb);  // as the frame driver does after compositing
    return fb;
  };
  return reduceReference(render(camera), render(subsampleCamera(camera)));
}

}  // namespace lzb::testing_util
