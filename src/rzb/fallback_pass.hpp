#pragma once
// The z-buffer fallback (section 7.1): the triangles of the selected boxes whose triangles would
// receive too many samples are drawn by the exact OSMesa z-buffer (src/zbuffer's
// TriangleRasterizer), in ascending expanded-ID order (one draw list per instance path, sorted),
// so equal depths keep the smaller ID as compositeNearer does. The result is composited with the
// point pass by (depth, id).
#include <memory>
#include <vector>

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/rzb/box_selection.hpp"
#include "src/zbuffer/triangle_rasterizer.hpp"

namespace lzb::rzb {

struct FallbackCounts {
  uint64_t boxes = 0, triangles = 0, drawCalls = 0;
};

class FallbackPass {
 public:
  explicit FallbackPass(const Scene& scene) : scene_(scene) {}
  // Draws the fallback boxes among boxes[mine] into fb (depth and ID; sized to the camera).
  // Returns false (fb untouched) when there were none.
  bool draw(const Camera& camera, const std::vector<SelectedBox>& boxes,
            const std::vector<uint32_t>& mine, Framebuffer& fb, FallbackCounts& counts);

 private:
  const Scene& scene_;
  std::unique_ptr<TriangleRasterizer> raster_;  // created on first use (a GL context)
};

}  // namespace lzb::rzb
