#pragma once
// --method surfels: rendering by surfels (Tobor, Schlick, Grisoni 2000). Per frame:
//   1. cull: the placements of objects in the frustum, each switched to a surfel level and sprite
//      or kept as polygons (placements.hpp), every rank alike;
//   2. surfelize: the levels this frame needs that are not cached yet (surfelize.hpp; every rank
//      builds the same, so each knows every placement's surfel count);
//   3. budget (--budget-ms): the surfel count the budget buys at the rate, as a fraction drawn of
//      every placement's collector, in its shuffled order;
//   4. deal: the work items in placement order - a polygon placement whole, a surfel placement in
//      runs of kJobPoints of its collector (src/splat/placement_jobs.hpp) - dealt to ranks in
//      runs of equal estimated cost (mpi/decomposition.hpp: surfels drawn, or kTriangleCost per
//      polygon), so one large object is split too;
//   5. polygons: this rank's polygon placements by the native z-buffer into the frame;
//   6. surfels: this rank's surfel placements splatted into a key buffer (surfel_draw.hpp);
//   7. combine: keys resolved and composited with the polygons by the (depth, ID) key.
// Colour comes from the IDs at the root (every pixel carries the ID of a representative triangle).
// The image depends on neither the thread count nor the ranks: every choice above is made from
// the camera and the scene, the work split only decides who draws what, and per-pixel minima
// compose in any order.
#include <memory>
#include <string>
#include <vector>

#include "src/core/depth_key.hpp"
#include "src/core/renderer.hpp"
#include "src/splat/placement_jobs.hpp"
#include "src/surfels/normal_quantizer.hpp"
#include "src/surfels/placements.hpp"
#include "src/surfels/surfel_draw.hpp"
#include "src/surfels/surfel_params.hpp"
#include "src/surfels/surfelize.hpp"
#include "src/zbuffer/native_raster.hpp"

namespace lzb::surfels {

class SurfelRenderer : public Renderer {
 public:
  // Builds nothing yet unless params.buildAtSetup (then every level of every object); measures the
  // splat rate when the budget needs it. Throws InputError for invalid params.
  SurfelRenderer(const Scene& scene, const RenderOptions& options, const SurfelParams& params);

  std::string name() const override { return "surfels"; }
  std::string decomposition() const override;
  void render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
              FrameStats& stats) override;
  FrameStats setupStats() const override;

  // One frame as it passes through the stages.
  struct Frame {
    const Camera* camera = nullptr;
    WorkShare share;
    std::vector<SurfelPlacement> placements;
    std::vector<uint64_t> work;    // per placement: surfels to draw, or triangles
    uint64_t selected = 0;         // surfels of every surfel placement (before the budget)
    uint64_t budget = 0;           // surfels the budget buys (0: no budget)
    PlacementJobs items;           // placement order; polygons: one item, begin == end == 0
    std::vector<uint32_t> mine;    // this rank's items
  };
  void cull(Frame& f) const;
  uint64_t buildLevels(const Frame& f);  // returns the levels built
  void applyBudget(Frame& f) const;
  void deal(Frame& f) const;
  void drawPolygons(const Frame& f, Framebuffer& fb, FrameStats& stats);
  void drawSurfelPass(const Frame& f, FrameStats& stats);
  void combine(Framebuffer& fb);

  // The level of detail `level` of `node`, built on first use and kept.
  const SurfelLevel& level(uint32_t node, int index);
  // Surfels per millisecond the budget converts with (given, or measured at set-up).
  double budgetRate() const {
    return params_.budgetRate > 0.0 ? params_.budgetRate : measuredRate_;
  }
  const SurfelParams& params() const { return params_; }
  const OctahedralNormals& normals() const { return normals_; }

 private:
  void report(const Frame& f, FrameStats& stats) const;
  void reportMemory(FrameStats& stats) const;
  void measureRate();

  const Scene& scene_;
  RenderOptions options_;
  SurfelParams params_;
  OctahedralNormals normals_;
  std::vector<Domain> domains_;                                    // per node
  std::vector<Bounds> meshBounds_;                                 // per node: its own triangles
  std::vector<std::vector<std::unique_ptr<SurfelLevel>>> levels_;  // [node][level]
  WholeNodeLists wholeNodes_;                                      // placements as polygons
  NativeRasterizer raster_;
  KeyBuffer keys_;
  Framebuffer points_;
  double setupBuildSeconds_ = 0.0, rateSeconds_ = 0.0, measuredRate_ = 0.0;
};

// A grey closed unit sphere of `slices` x `stacks` (tests and the rate measurement).
Mesh uvSphere(int slices, int stacks);

}  // namespace lzb::surfels
