#pragma once
// The z-buffer fallback (section 7.1): the triangles of the selected boxes whose triangles would
// receive too many samples are drawn by an exact z-buffer, gathered as draw lists (one per
// instance path, ascending expanded IDs). By default the native multithreaded z-buffer
// (src/zbuffer/native_raster.hpp) draws them; `--fallback-render gl` draws them with OSMesa
// (TriangleRasterizer) in list order, so equal depths keep the smaller ID. Both keep the
// (depth, id) minimum, so the result is composited with the point pass (and across ranks) by
// compositeNearer.
#include <memory>
#include <vector>

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/rzb/box_selection.hpp"
#include "src/rzb/rzb_params.hpp"
#include "src/zbuffer/draw_lists.hpp"
#include "src/zbuffer/native_raster.hpp"
#include "src/zbuffer/triangle_rasterizer.hpp"

namespace lzb::rzb {

struct FallbackCounts {
  uint64_t boxes = 0, triangles = 0, drawCalls = 0;
};

// Sorts mesh indices (each below meshSize) and drops repeats: through a bitmap of the mesh where
// the list is dense in it (a whole instance's mesh: a field of scanned meshes sends millions of
// fallback triangles a frame), else by sorting.
void ascendingOnce(std::vector<uint32_t>& triangles, uint32_t meshSize);

// The triangles of the fallback boxes among boxes[mine] as draw lists: per (ID base, scene node),
// ascending, each triangle once; lists in ascending ID base; sorted on `threads` threads.
DrawLists fallbackLists(const std::vector<SelectedBox>& boxes, const std::vector<uint32_t>& mine,
                        int threads);

class FallbackPass {
 public:
  // threads: the native z-buffer's threads (OSMesa's follow LP_NUM_THREADS).
  FallbackPass(const Scene& scene, FallbackRender render, int threads)
      : scene_(scene), render_(render), threads_(threads) {}
  // Draws the fallback boxes among boxes[mine] into fb (depth and ID; sized to the camera,
  // empty). Returns false (fb untouched) when there were none.
  bool draw(const Camera& camera, const std::vector<SelectedBox>& boxes,
            const std::vector<uint32_t>& mine, Framebuffer& fb, FallbackCounts& counts);

 private:
  void drawNative(const Camera& camera, const DrawLists& lists, Framebuffer& fb);
  void drawGl(const Camera& camera, const DrawLists& lists, Framebuffer& fb);

  const Scene& scene_;
  FallbackRender render_;
  int threads_;
  NativeRasterizer native_;                // keeps its bins between frames
  std::unique_ptr<TriangleRasterizer> gl_;  // created on first use (a GL context)
};

}  // namespace lzb::rzb
