#include "src/zbuffer/zbuffer_renderer.hpp"

#include "mpi/decomposition.hpp"
#include "src/core/shading.hpp"
#include "src/core/timer.hpp"

namespace lzb {

ZBufferRenderer::ZBufferRenderer(const Scene& scene, const RenderOptions& /*options*/)
    : scene_(scene), walk_(scene), rasterizer_(scene) {}

std::string ZBufferRenderer::decomposition() const {
  return "sort-last by triangle ID: rank r draws the r-th of equal contiguous ranges of the "
         "expanded triangle-ID order (cutting a draw item where needed) in ascending ID order with "
         "a strict depth test, so compositing by the nearest (depth, ID) reproduces the 1-rank "
         "image exactly";
}

void ZBufferRenderer::render(const Camera& camera, int /*frame*/, const WorkShare& share,
                             Framebuffer& fb, FrameStats& stats) {
  requireFrameSize(fb, camera, "zbuffer");
  Stopwatch clock;
  rasterizer_.begin(camera);
  const IdRange range = shareRange(scene_.expandedTriangles(), share);
  const WalkCounts counts = walk_.walk(camera.frustum(), range, [&](const DrawCall& d) {
    rasterizer_.drawRange(d.node, d.world, d.first, d.count, d.firstId);
  });
  rasterizer_.end(fb);
  const RasterCounts& raster = rasterizer_.counts();
  const double drawSeconds = clock.lap() - raster.uploadSeconds - raster.readbackSeconds;
  stats.addStage("upload", raster.uploadSeconds);
  stats.addStage("draw", drawSeconds);
  stats.addStage("readback", raster.readbackSeconds);
  stats.addCount("triangles_drawn", double(counts.triangles));
  stats.addCount("draw_items", double(counts.items));
  stats.addCount("draw_items_culled", double(counts.culled));
  stats.addCount("draw_calls", double(raster.drawCalls));
}

}  // namespace lzb
