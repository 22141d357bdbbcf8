#pragma once
// --method hybrid: local z-buffering and the randomized z-buffer in one frame, composed from
// their stages (raycast/lzb/lzb_renderer.hpp and the point pass of leaf_points.hpp):
//   1. cull, partition plane, near scene by the native z-buffer clipped at the plane, unfinished
//      pixels (local z-buffering's steps 1-4);
//   2. behind the plane, the octree leaves whose triangles project below the fallback threshold
//      are point-sampled into a key buffer (the randomized z-buffer's point pass);
//   3. the rest of the far scene by object-oriented lazy ray casting with the coherent walk
//      (local z-buffering's final stage) from the unfinished pixels: the walk skips the sampled
//      leaves and nodes, so a ray only looks for the large triangles; its PVL is z-buffered at the
//      unfinished pixels;
//   4. the passes composited by the compositing key; colour from the IDs at the root.
// Ranks: every rank renders the near pass; the sampled leaves and nodes are dealt by their sample
// counts (mpi/decomposition.hpp), the screen tiles of the rays interleaved. Rays do not depend on
// the samples (a ray stopped at its rank's nearest sample would look deeper on a rank holding
// fewer samples), so the ranks' composite is the 1-rank image.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "raycast/exact/pixel_cast.hpp"
#include "raycast/lzb/lzb_renderer.hpp"
#include "src/core/depth_key.hpp"
#include "src/core/frame_probe.hpp"
#include "src/core/renderer.hpp"
#include "src/core/timer.hpp"
#include "src/hybrid/leaf_areas.hpp"
#include "src/hybrid/leaf_points.hpp"

namespace lzb::hybrid {

// How the exact part of the far scene is drawn: lazy ray casting (object-oriented, coherent
// walk or Embree) -> PVL -> z-buffer, or each unfinished pixel's Embree hit (direct, the naive
// stage of local z-buffering), or the cheaper of the two by the culled triangles per pixel.
enum class FarPass { kAuto, kLazy, kDirect };
FarPass parseFarPass(const std::string& text, const std::string& field);
std::string toString(FarPass p);

// How a frame is drawn: local z-buffering with the point pass (the stages above), or every pixel
// cast by Embree as --method raycast does (pixel_cast.hpp), or the cheaper of the two by the
// frame's probe (castEveryPixelPays).
enum class FrameWay { kAuto, kLocal, kRays };
FrameWay parseFrameWay(const std::string& text, const std::string& field);
std::string toString(FrameWay w);

struct HybridParams {
  double oversample = 1.0;   // scales the ln(pixels) samples per pixel of projected area
  int splat = 1;             // d
  double fallbackPx = 0.0;   // sampled leaves' largest projected triangle; 0: kAutoFallbackPx d^2
  // The automatic threshold per d^2 pixels: sampling pays only for geometry the exact path cannot
  // hold (instancing far below a pixel). rzb's d^2 / ln(pixels) (~0.08 px) sampled the forest,
  // the field and the sphereflake at 3-4x the frame time of lazy ray casting, less accurately
  // (any sampled unit also sends the rays through the octree walk instead of Embree).
  static constexpr double kAutoFallbackPx = 1e-4;
  bool dropBackfaces = true;
  FarPass farPass = FarPass::kAuto;
  // Auto: direct rays from this many culled triangle entries per pixel (a direct frame samples
  // nothing, and its cull may stop at the median coarse hit depth: cullForFarPass). A lazy ray's leaf
  // look-ups, OOR objects and PVL grow with the far leaves per pixel, an Embree ray hardly
  // (lzb final against naive, 2 threads: paper city 6.4 per pixel 7.4 vs 8.7 ms; the city at
  // 200 x 200, 43: 3.3 vs 2.7; forest 1080p, 33: 122 vs 88; forest 640 x 480, 182: 39 vs 31).
  static constexpr double kDirectTrianglesPerPixel = 16.0;
  FrameWay frameWay = FrameWay::kAuto;
  // The probe's plane: the coarse hit with this share of the hits in front of it, near enough
  // for its cull to be cheap beside a frame's, far enough to finish some pixels.
  static constexpr double kProbeQuantile = 1.0 / 16.0;
  // The probe's cost of a near triangle in direct rays where the scene holds at least
  // kDirectTrianglesPerPixel (its far pass may be direct): its leaf's cull, the plane's binning
  // and its raster against a packet ray (the landscape at 10^7, 640 x 480, one frame: cull 4.4,
  // plane 1.1 and near 3.2 ms for 14 K near triangles, 620 ns each; 48 ns a ray of raycast).
  // In a sparser scene 1, the cost plane's unit: there the lazy far pass skips the empty pixels
  // that casting every pixel pays for.
  static constexpr double kDenseNearTriangleCost = 13.0;
  // After the plane of a frame the probe kept local: a pixel cast as raycast casts it costs this
  // many of the cost plane's near triangles, and the frame casts every pixel when the plane's
  // estimate costs more (runs/peers/frame_way.py, every frame both ways: local was faster where
  // the estimate was below 0.2-0.48 of the castable pixels, and slower from 0.59, on the cities,
  // the armadillo and the landscape at 10^6).
  static constexpr double kCastPixelCost = 0.5;
  // A frame cast every pixel walks its screen cover (screen_cover.hpp) when the probe's coarse
  // rays hit in less than this share of the castable pixels (the rest would miss), up to this
  // many octree nodes and instances per castable 4 x 4 block (the city's distant frames at
  // 1080p visit 0.1-0.4; a walk costs about 0.15 us a node, a block's 16 rays 2-6 us).
  static constexpr double kCoverBelowShare = 0.5;
  static constexpr double kCoverNodesPerBlock = 0.5;
  // The local z-buffering stages (final stage, native z-buffers); its far rays walk the octrees
  // in frames where the point pass takes leaves (only the walk skips them), else are Embree's.
  localz::LzbOptions lzb;

  // Throws InputError naming the option for out-of-range values.
  void validate() const;
  PointParams pointParams(int width, int height) const;
  nlohmann::json toJson() const;
};

class HybridRenderer : public Renderer, public FrameProbe {
 public:
  HybridRenderer(const Scene& scene, const RenderOptions& options, const HybridParams& params);

  std::string name() const override { return "hybrid"; }
  std::string decomposition() const override;
  void render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
              FrameStats& stats) override;
  FrameStats setupStats() const override;

  // Step 0 over the parts of a data-parallel scene (frame_probe.hpp).
  size_t probeRays(const Camera& camera) const override;
  std::span<const double> coarseRayDepths(const Camera& camera) override;
  ProbeCounts probe(const Camera& camera, std::span<const double> frameDepths) override;
  bool everyPixelPays(const Camera& camera, std::span<const double> frameDepths,
                      const ProbeCounts& frame, FrameStats& stats) const override;
  void setFrameWay(bool everyPixel) override { decided_ = everyPixel; }

  const localz::LzbRenderer& lzb() const { return lzb_; }

 private:
  // A frame's state for the stages, with the point pass's rule for this camera and pp.
  localz::LzbRenderer::Frame beginFrame(const Camera& camera, const WorkShare& share,
                                        const PointParams& pp);
  // Step 0 (--frame-way auto) of a frame alone: casts the coarse rays (kept for the plane),
  // probes and chooses.
  bool castEveryPixelPays(localz::LzbRenderer::Frame& f, FrameStats& stats);
  // After the plane (auto, a frame alone): whether the cost plane's estimate exceeds what
  // casting every pixel costs (kCastPixelCost).
  bool planeCostsMoreThanCasting(const Camera& camera, FrameStats& stats) const;
  // Draws the frame as raycast does (the rest of the clock's time is its "trace"), within the
  // screen cover where the frame is sparse.
  void castEveryPixelInstead(const Camera& camera, const WorkShare& share, Framebuffer& fb,
                             FrameStats& stats, Stopwatch& clock);
  // The frame's screen cover when the probe's rays (if any) say most castable pixels miss and
  // the walk stays within kCoverNodesPerBlock; none otherwise.
  std::optional<BlockCover> coverWhereSparse(const Camera& camera, FrameStats& stats) const;
  // The counts in front of the probe's plane placed from frameDepths (culls up to it).
  ProbeCounts probeCounts(localz::LzbRenderer::Frame& f, std::span<const double> frameDepths);
  // Step 2: the sampled leaves of this frame, this rank's share splatted into points_.
  void drawPoints(localz::LzbRenderer::Frame& f, const PointParams& pp, int frame,
                  FrameStats& stats);
  // Step 1 for the far pass to come: where a direct pass may pay (not lazy, a scene of at least
  // denseTriangles), first a cull up to the median coarse hit depth, kept when it already holds
  // denseTriangles with nothing sampled (then no plane beyond it costs less than casting every
  // pixel: the plane and near pass are the whole cull's); else the whole cull. Returns the
  // depth the cull stopped at, infinity for the whole frustum; *triangles: the kept cull's
  // exactlyCulledTriangles (-1 when not counted: a lazy far pass).
  double cullForFarPass(localz::LzbRenderer::Frame& f, double* triangles);
  // kDirectTrianglesPerPixel x the image's pixels.
  double denseTriangles(const Camera& camera) const;
  // The culled leaves' triangle entries, or -1 when the cull left a sampled unit out.
  double exactlyCulledTriangles() const;
  // Step 3's choice (FarPass) for this frame from the cull's exactlyCulledTriangles: direct rays
  // unless the cull left a sampled unit out (Embree's rays cannot skip it; the walk can).
  bool directRaysPay(const Camera& camera, double culledTriangles) const;
  void countPixels(const localz::LzbRenderer::Frame& f, const Framebuffer& fb,
                   FrameStats& stats) const;

  const Scene& scene_;
  RenderOptions options_;
  HybridParams params_;
  localz::LzbRenderer lzb_;
  double areasSeconds_ = 0.0;  // before areas_: its construction sets it
  LeafAreas areas_;
  KeyBuffer keys_;
  Framebuffer points_;  // this rank's samples (depth and ID)
  bool pointsDrawn_ = false;  // this frame had samples for this rank (else points_ is stale)
  std::unique_ptr<SampledLeafRule> rule_;
  std::vector<double> coarseDepths_;  // this frame's coarse rays, per ray (phase 1 or step 0)
  std::optional<bool> decided_;       // the way set by setFrameWay for the next frame
};

}  // namespace lzb::hybrid
