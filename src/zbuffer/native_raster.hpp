#pragma once
// The native z-buffer: a multithreaded software z-buffer that any pass can use (lzb's near pass
// and PVL, `--near-render native`, `--pvl-render native`; rzb's fallback, `--fallback-render
// native`). A pass draws draw lists either at
// every pixel (optionally clipped per fragment at a far depth: lzb's near pass stops at the
// partition plane) or only at the "open" pixels of a mask (lzb's PVL pass draws only the near
// pass's unfinished pixels; every ray-cast pixel is one, and a PVL triangle can cover no other
// unfinished pixel than a ray-cast one except by rounding at the edge of a projected object).
//
// Per pixel it keeps the nearer (depth, ID) by the compositing key's rule (src/core/depth_key.hpp),
// so the result does not depend on the order of triangles, the thread count or the split of the
// lists over ranks (compositing the ranks' images gives the 1-rank image bit for bit).
//
// Rasterization: positions camera-relative in double, clipped in view space at the near plane
// (and at a guard band far outside the image, which keeps fixed-point coordinates small), snapped
// to 1/256 pixel; edge functions in exact integers at pixel centres (i + 0.5, j + 0.5) with
// OSMesa's tie rule (a centre on an edge belongs to left and image-bottom edges: GL's top-left
// rule in y-up window coordinates), so a pixel centre on an edge shared by two triangles is
// covered exactly once, by the triangle OSMesa gives it.
// Depth: 1/depth is affine on screen (a planar triangle), evaluated at the pixel centre from the
// unsnapped vertices in double, stored as float
// view depth (src/core/camera.hpp); fragments beyond the camera's far plane are dropped. No
// back-face culling (the z-buffer passes draw both sides too).
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "mpi/decomposition.hpp"
#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/core/scene.hpp"
#include "src/zbuffer/draw_lists.hpp"

namespace lzb {

constexpr int kSubpixelBits = 8;  // fixed point: 1/256 pixel

// A screen-space vertex: pixel coordinates (x right, y down) and view depth (> 0).
struct ScreenVertex {
  double x = 0.0, y = 0.0, depth = 0.0;
};

// A triangle ready to rasterize: snapped vertices with a positive area, pixel bounding box of the
// pixel centres it may cover, clamped to the image.
struct RasterTriangle {
  int32_t x[3], y[3];  // fixed point, counter-clockwise on screen (positive edge functions)
  // 1 / view depth at pixel position (px, py) = a px + b py + c, from the unsnapped vertices
  // (snapping moves a vertex up to 1/512 pixel, which on a steep triangle would move depth).
  double a, b, c;
  double invDepthMin, invDepthMax;  // of the vertices: the plane is clamped to them
  uint64_t id = 0;
  int32_t x0, x1, y0, y1;  // pixels [x0, x1) x [y0, y1)
};

// Snaps v and sets up t. False (t unusable) when the triangle is degenerate after snapping or
// covers no pixel centre of a width x height image. Vertices must lie within about 2^21 pixels.
bool setupTriangle(const ScreenVertex (&v)[3], uint64_t id, int width, int height,
                   RasterTriangle& t);

// Draws t into fb at the pixels of rows [rowBegin, rowEnd) with open[i] != 0 (nullptr: every
// pixel), keeping the minimum (depth, id); fragments deeper than farDepth are dropped. Touches
// fb.depth and fb.id only (colour comes later from the IDs). Returns the fragments written.
uint64_t rasterizeTriangle(const RasterTriangle& t, int rowBegin, int rowEnd, const uint8_t* open,
                           double farDepth, Framebuffer& fb);

// Clips a view-space triangle (x right, y up, depth forward) at the near plane and the guard band
// and projects it: appends 0 (all clipped away), 1 or, after clipping, a fan of several screen
// triangles to out. scale = camera.pixelsPerUnitAt(1).
void clipAndProject(const glm::dvec3 (&view)[3], double nearDepth, double scale, int width,
                    int height, std::vector<std::array<ScreenVertex, 3>>& out);

struct NativeRasterCounts {
  uint64_t triangles = 0;  // triangles of the lists
  uint64_t setUp = 0;      // screen triangles that may cover a pixel centre (after clipping)
  uint64_t clipped = 0;    // triangles that needed clipping (near plane or guard band)
  uint64_t fragments = 0;  // fragments written (passed the depth test; depends on the order)
};

// Triangles given by world positions and IDs (the sample tree's nodes, which are no scene node's
// mesh): triangles [begin, end) of every range, positions 3 per triangle.
struct SoupRange {
  uint64_t begin = 0, end = 0;
};
struct TriangleSoup {
  std::span<const glm::vec3> positions;
  std::span<const uint64_t> ids;
  std::span<const SoupRange> ranges;
};

// Draws draw lists (or a triangle soup) into fb at open pixels. Keeps its per-thread bins
// between frames.
class NativeRasterizer {
 public:
  // open: one byte per pixel of fb (fb.index order), nonzero where triangles may be drawn; empty:
  // every pixel. Fragments deeper than farClip (0: the camera's far plane) are dropped. Only the
  // lists' triangles [part.begin, part.end) in list order are drawn (default: all), so ranks
  // can split a pass by contiguous ranges and composite.
  void draw(const Scene& scene, const Camera& camera, const DrawLists& lists,
            std::span<const uint8_t> open, int threads, Framebuffer& fb, double farClip = 0.0,
            IdRange part = {0, ~uint64_t(0)});
  // The soup's triangles at every pixel, up to the camera's far plane.
  void drawSoup(const Camera& camera, const TriangleSoup& soup, int threads, Framebuffer& fb);
  const NativeRasterCounts& counts() const { return counts_; }

  static constexpr int kBandRows = 16;  // rows per band: the unit of threads in rasterization

 private:
  void clearBins(int threads, int height);
  uint64_t rasterizeBins(int threads, const uint8_t* mask, double farDepth, Framebuffer& fb);

  std::vector<std::vector<std::vector<RasterTriangle>>> bins_;  // [thread][band]
  NativeRasterCounts counts_;
};

}  // namespace lzb
