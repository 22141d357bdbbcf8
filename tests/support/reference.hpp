#pragma once
// The tests' exact references and accuracy figures, computed in one process as the program's
// report computes them (mpi::FrameDriver, src/image/reference.hpp).
#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/core/renderer.hpp"
#include "src/core/scene.hpp"
#include "src/image/metrics.hpp"
#include "src/image/reference.hpp"

namespace lzb::test {

// An exact renderer at the pixel centres and at the 4x4 sub-samples, shaded and reduced.
ReferenceFrame renderReference(Renderer& exact, const Scene& scene, const Camera& camera,
                               int frame = 0);

// The exact z-buffer's reference of `camera` (default options).
ReferenceFrame zbufferReference(const Scene& scene, const Camera& camera);

// The report's accuracy of `image`: against the ray caster (under `raycastOptions`), witnessed by
// rays; `image` is shaded from its IDs first.
Accuracy accuracy(const Scene& scene, const Camera& camera, Framebuffer image,
                  const RenderOptions& raycastOptions);

// The papers' correct-pixel rate measured closely for sub-pixel triangles: a pixel is correct
// when its ID (or emptiness) is seen by an exact z-buffer rendered at `factor` times the
// resolution anywhere in the pixel's factor x factor sub-pixels, widened by `margin` sub-pixels.
// An odd factor keeps the pixel's own centre among the sub-pixel centres.
double visibleInPixelRate(const Framebuffer& test, const Scene& scene, const Camera& camera,
                          int factor = 5, int margin = 1);

}  // namespace lzb::test
