#pragma once
// The tests' one way to render a frame: a renderer's share of frame `frame` into a fresh buffer,
// and the frames of the two exact methods built for the purpose.
#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/core/renderer.hpp"
#include "src/core/scene.hpp"

namespace lzb::test {

// Depth and IDs of `share` of frame `frame` (colour only where the renderer fills it in); the
// frame's own statistics go to *stats when given (replacing what it held).
Framebuffer renderFrame(Renderer& r, const Camera& camera, FrameStats* stats = nullptr,
                        WorkShare share = {}, int frame = 0);

// The exact ray caster's frame (depth and IDs at the pixel centres) under `options`.
Framebuffer exactFrame(const Scene& scene, const Camera& camera, const RenderOptions& options);

// The exact z-buffer's frame (depth and IDs) under `options`; `shade` adds the colour the frame
// driver shades from the IDs after compositing.
Framebuffer zbufferFrame(const Scene& scene, const Camera& camera,
                         const RenderOptions& options = RenderOptions{}, bool shade = false,
                         FrameStats* stats = nullptr, WorkShare share = {});

}  // namespace lzb::test
