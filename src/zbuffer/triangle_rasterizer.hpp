#pragma once
// The exact z-buffer as a building block: several passes (the whole scene, a near scene clipped at
// a partition plane, a potentially visible list, the large-triangle fallback of the randomized
// z-buffer) draw triangles of scene nodes into one ID + depth target between begin() and end().
//
// Contract shared by every pass:
// - Depth is THE convention of src/core/camera.hpp (view depth, float), stored exactly as the
//   framebuffer holds it; the depth test is strict (GL_LESS), so on an exact tie the triangle
//   drawn first stays. Callers that need rank-count independence draw in ascending ID order
//   within a pass and combine passes with compositeNearer (min over (depth, ID)).
// - A triangle's depth at a pixel is the same whichever draw call (range or list) draws it.
// - Positions are made camera-relative in double before rounding to float.
// - Must be used from one thread; the GL context is made current in begin().
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <string>

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/core/scene.hpp"

namespace lzb {

struct RasterCounts {
  uint64_t triangles = 0;  // triangles handed to GL since begin()
  uint64_t drawCalls = 0;
  double uploadSeconds = 0.0;    // first-use uploads of node meshes since begin()
  double readbackSeconds = 0.0;  // end()'s and read()'s reading and converting, after GL
};

class TriangleRasterizer {
 public:
  // scene: finalized, outlives this. Creates the OSMesa context (llvmpipe threads: LP_NUM_THREADS,
  // set by lzb::useThreads before the first context of the process).
  explicit TriangleRasterizer(const Scene& scene);
  ~TriangleRasterizer();
  TriangleRasterizer(const TriangleRasterizer&) = delete;
  TriangleRasterizer& operator=(const TriangleRasterizer&) = delete;

  // Starts a pass set: clears the target to empty, sets the camera. farClip (view depth, <=
  // camera.farPlane()) clips everything beyond it, e.g. at a partition plane; 0 = camera far.
  // Clipping drops fragments deeper than farClip (exactly: depth > farClip as doubles) and leaves
  // the rest of the triangle's pixels and depths as an unclipped draw gives them.
  void begin(const Camera& camera, double farClip = 0.0);
  // Changes the far clip between draws (e.g. the near scene up to the plane, then the PVL).
  void setFarClip(double farClip);
  // Triangles [first, first + count) of node's mesh placed by world; triangle `first` gets
  // ID firstId, the next firstId + 1, ... The node's mesh is uploaded once, on first use.
  void drawRange(uint32_t node, const glm::dmat4& world, uint64_t first, uint64_t count,
                 uint64_t firstId);
  // The listed triangles of node's mesh (any order, duplicates allowed); triangle t gets ID
  // idBase + t. Uses the node's uploaded mesh with an index list (no vertex copies). Drawn in list
  // order, except that a mesh of over MeshBuffers::kChunkTriangles is drawn chunk by chunk (list
  // order within each), so an ascending list is always drawn in its order.
  void drawList(uint32_t node, const glm::dmat4& world, std::span<const uint32_t> triangles,
                uint64_t idBase);
  // Hands what was drawn so far to llvmpipe's rasterizer threads without waiting, so they work
  // while the caller goes on drawing (otherwise a pass that does not fill llvmpipe's bins is only
  // rasterized in end()). Changes nothing in the result.
  void flush();
  // Waits for GL, reads IDs and depths into fb (sized to the camera; row 0 = top; colour is left
  // to the caller, e.g. shadeFromIds). Pixels no triangle covered get kNoId / kEmptyDepth.
  void end(Framebuffer& fb);
  // Like end(), but the pass set stays open: later draws go on into the same buffers (depth test
  // against what is there), e.g. a pass drawn on top of a clipped one read here first. counts()
  // keep accumulating; readbackSeconds adds up every read.
  void read(Framebuffer& fb);

  const RasterCounts& counts() const { return counts_; }
  // GL version and renderer, for reports.
  const std::string& description() const;

 private:
  // Waits for GL and reads IDs and depths into fb (end() and read()).
  void readInto(Framebuffer& fb);

  struct Impl;
  std::unique_ptr<Impl> impl_;
  RasterCounts counts_;
};

}  // namespace lzb
