#pragma once
// --method sqrt5: interactive sampling and rendering of complex and procedural geometry
// (Stamminger & Drettakis 2001). Per frame:
//   1. cull: the placements whose bounds meet the frustum (placements.hpp), every rank alike;
//   2. plan: per procedural placement the initial grid of eq. (3) (refine.hpp), cut into runs of
//      rows; a terrain seen along the ground is sampled in its sector instead (sector.hpp), with
//      an initial grid of step 2 sqrt(A'min) pixels across the image (n = max(W, H) /
//      (2 sqrt A'min)), cut into runs of constant-s lines, each culled against its horizon front
//      to back (horizon.hpp, --horizon); per mesh placement its Halton prefix length n_s = A /
//      (d~^2 A'min) from the nearest distance of its bounds (halton.hpp; each unique mesh's vector
//      extended to the longest prefix this frame), cut into runs of kJobPoints; the runs are dealt
//      to ranks in contiguous runs of equal estimated cost (mpi/decomposition.hpp: roots, or
//      samples); a mesh placement whose prefix would be at least kPolygonFactor (4) x its triangle
//      count (points cost as much there) is drawn as polygons instead: one unit of kTriangleCost
//      per triangle (the paper's trade, sections 4 and 7: polygons are more efficient when they
//      cover many pixels; src/surfels switches per object alike);
//   3. sample: this rank's runs, on OpenMP threads: sqrt(5) trees grown from the roots
//      (refine.hpp) and Halton prefixes, every sample splatted through the splatting core with the
//      ID of its triangle (the tessellated triangle holding its (u, v), or the mesh triangle it
//      lies on) and a splat of d = max(1, ceil(sqrt(2 A'min))) pixels;
//   4. polygons: this rank's polygon placements by the native z-buffer into the frame
//      (src/zbuffer/native_raster.hpp);
//   5. resolve: the key buffer into the frame, composited with the polygons by (depth, ID).
// Nothing depends on the rank or thread count: the plan follows from the camera and the scene,
// the deal only decides who draws which run, and the key buffer takes per-pixel minima.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "src/core/depth_key.hpp"
#include "src/core/renderer.hpp"
#include "src/splat/placement_jobs.hpp"
#include "src/sqrt5/forest_cache.hpp"
#include "src/sqrt5/halton.hpp"
#include "src/sqrt5/horizon.hpp"
#include "src/sqrt5/placements.hpp"
#include "src/sqrt5/refine.hpp"
#include "src/sqrt5/sqrt5_params.hpp"
#include "src/zbuffer/native_raster.hpp"

namespace lzb::sqrt5 {

// Roots per work item at least (Halton samples per item: kJobPoints, placement_jobs.hpp).
constexpr uint64_t kJobRoots = 1024;
// Halton samples of one placement at most (a mesh nearer than its size asks for unbounded ones).
constexpr uint64_t kMaxHaltonSamples = uint64_t(1) << 22;
// A mesh placement is drawn as polygons when its Halton prefix n_s >= kPolygonFactor * m (m its
// triangle count): by kTriangleCost (placement_jobs.hpp) points are cheaper below, and a prefix
// covers a pixel only with some probability where exact triangles cover it surely (coplanar and
// edge-on surfaces; measured against k = 1: README).
constexpr double kPolygonFactor = kTriangleCost;

class Sqrt5Renderer : public Renderer {
 public:
  Sqrt5Renderer(const Scene& scene, const RenderOptions& options, const Sqrt5Params& params);

  std::string name() const override { return "sqrt5"; }
  std::string decomposition() const override;
  void render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
              FrameStats& stats) override;
  FrameStats setupStats() const override;

  struct Frame {
    const Camera* camera = nullptr;
    WorkShare share;
    std::vector<SampledPlacement> placements;
    std::vector<int> side;           // per placement: initial grid side n (procedural), else 0
    std::vector<std::optional<Sector>> sectors;  // per placement: a terrain's sector
    std::vector<uint64_t> halton;    // per placement: Halton prefix length (mesh), else 0
    std::vector<uint64_t> polygons;  // per placement: triangles drawn exactly (mesh), else 0
    // runs of lines of a procedural placement's initial grid (rows; a sector's constant-s
    // columns), of a mesh placement's Halton samples, or a polygon placement whole
    PlacementJobs jobs;
    std::vector<uint32_t> mine;
    std::vector<std::vector<CachedLine*>> cached;  // per mine: its lines' cache entries, if cached
  };
  // Stages 1 and 2: the frame's placements, plan and this rank's runs (with their cache lines).
  Frame prepare(const Camera& camera, const WorkShare& share);
  void plan(Frame& f);
  void deal(Frame& f) const;
  struct DrawCounts {
    RefineCounts trees;
    HorizonCounts horizon;
    ForestCacheCounts cache;
    uint64_t haltonDrawn = 0, splatted = 0;
    void merge(const DrawCounts& o);
  };
  DrawCounts draw(const Frame& f);
  // Stage 4: this rank's polygon placements into fb (depth and ID); returns placements, triangles.
  std::pair<uint64_t, uint64_t> drawPolygons(const Frame& f, Framebuffer& fb);
  const Sqrt5Params& params() const { return params_; }

 private:
  template <bool kWide, bool kPixel>
  DrawCounts drawWith(const Frame& f);
  struct Scratch {
    std::vector<std::pair<glm::dvec2, int>> stack;
    std::vector<uint32_t> cachedStack;
    std::vector<glm::dvec2> kids;
  };
  template <class Splatter>
  void drawJob(const Frame& f, size_t k, Splatter& out, DrawCounts& counts, Scratch& s) const;
  void attachCache(Frame& f);
  void report(const Frame& f, const DrawCounts& c, FrameStats& stats) const;
  uint64_t haltonBytes() const;

  const Scene& scene_;
  RenderOptions options_;
  Sqrt5Params params_;
  std::vector<Bounds> meshBounds_;                      // per node: its own surface
  std::vector<std::unique_ptr<HaltonSurface>> halton_;  // per mesh node, built on first use
  WholeNodeLists wholeNodes_;                           // mesh nodes drawn as polygons
  ForestCache cache_;
  NativeRasterizer raster_;
  KeyBuffer keys_;
};

}  // namespace lzb::sqrt5
