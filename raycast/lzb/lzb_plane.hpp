#pragma once
// LZB step 2: the partition plane z = z_clip (view depth) that splits the scene into the near
// scene (z-buffer) and the far scene (rays -> PVL) (paper, section II.B).
//
// - Static: z_clip = near + F (far - near), F in (0, 1) (the paper suggests 0.15-0.30).
// - Dynamic: coarse ray casting (Embree) from a uniform G x G grid of pixel positions; z_clip is
//   the mean depth of the nearest surfaces hit (rays that hit nothing do not count; with no hit
//   at all the whole frustum is near). Every rank casts the same grid, so all agree.
// - Cost (our extension, --plane cost): the same coarse rays, but z_clip minimises an estimate
//   of the frame's work instead of sitting at the mean depth:
//     cost(z) = (triangles of culled leaves starting before z)
//             + kRayCost x (pixels whose coarse ray hit a surface beyond z),
//   a near triangle costing 1 and an unfinished covered pixel kRayCost (its ray walk plus its
//   share of the PVL drawn; kNaiveRayCost for naive's Embree rays). Candidates: the near plane
//   and every coarse hit depth. With no coarse hit (sparse or sub-pixel geometry between the
//   rays), all the culled triangles against a ray for every pixel: all near or all far.
// - Frame coherence (dynamic only): a plane is reused by later frames while all of these hold
//   (otherwise it is recomputed), so the plane is always one computed from a similar view:
//     1. fewer than `planeReuse` frames have used it since it was computed;
//     2. same image size and field of view (the depth is kept inside the new clip planes);
//     3. the camera moved at most kReuseMove x z_clip;
//     4. the view direction turned at most fovy x kReuseTurn;
//     5. the last frame's near pass left at most kReuseGrowth x the unfinished pixels of the
//        frame that computed it, plus kReuseSlack of the image (the plane still works).
//   Every input is the same on every rank (each rank renders every frame's near pass).
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "raycast/exact/embree_scene.hpp"
#include "raycast/lzb/lzb_options.hpp"
#include "src/core/camera.hpp"

namespace lzb::localz {

// A culled leaf's load for the cost plane: where it starts (view depth) and its triangles.
struct LeafLoad {
  double depthMin;
  uint32_t triangles;
};

struct PlaneDecision {
  double depth = 0.0;  // z_clip, view depth in [near, far]
  bool reused = false;
  uint64_t coarseRays = 0, coarseHits = 0;  // this frame's (0 when reused or static)
  double cost = -1.0;  // the cost plane's estimate of the frame there, in near triangles (-1: none)
};

// The coarse grid's rays of one camera, cast once before the plane (a composing method that
// needs them first): the mean-depth decision and every hit depth.
struct CoarseHits {
  PlaneDecision mean;
  std::vector<double> depths;
};

class PartitionPlane {
 public:
  static constexpr double kReuseMove = 0.05;
  static constexpr double kReuseTurn = 1.0 / 16.0;
  static constexpr double kReuseGrowth = 1.5;
  static constexpr double kReuseSlack = 0.01;
  // Cost plane: one unfinished covered pixel costs this many near triangles (measured on the
  // 2-core llvmpipe machine: ~140 ns per near triangle, ~1.5-2 us per cast ray with its PVL;
  // an Embree ray of the naive stage ~0.1 us).
  static constexpr double kRayCost = 12.0;
  static constexpr double kNaiveRayCost = 1.0;

  explicit PartitionPlane(const LzbOptions& options) : options_(options) {}

  // This frame's plane. embree: the whole scene (coarse rays), unused for a static plane;
  // loads: the culled leaves (used by the cost plane only); the coarse rays go on `threads`;
  // directRays: the far pass is Embree's hits without a PVL (as the naive stage's), whose
  // pixels the cost plane weighs at kNaiveRayCost; cast: this camera's coarse rays when already
  // cast (else place() casts them when it computes a plane).
  PlaneDecision place(const EmbreeScene& embree, const Camera& camera,
                      std::span<const LeafLoad> loads = {}, int threads = 1,
                      bool directRays = false, const CoarseHits* cast = nullptr);
  // Whether place() for this camera reads the leaves' loads (a cost plane to compute, not reused).
  bool needsLoads(const Camera& camera) const {
    return options_.dynamicPlane() && options_.costPlane && !stillValid(camera);
  }
  // After the near pass: how many pixels it left unfinished (feeds reuse rule 5).
  void observe(uint64_t unfinished);

  // The coarse grid's columns and rows for this camera: `grid` each way, at most a ray a pixel.
  static std::pair<int, int> coarseGrid(const Camera& camera, int grid);
  // The coarse grid's nearest hit depth per ray, row by row (infinity: no hit).
  static std::vector<double> coarseRayDepths(const EmbreeScene& embree, const Camera& camera,
                                             int grid, int threads = 1);
  // The mean decision and the hit depths (in ray order) of the rays' depths.
  static CoarseHits coarseHitsOf(std::span<const double> perRay, const Camera& camera);
  // Mean nearest-hit depth over the coarse grid (0 hits: camera far); exposed for tests. The
  // hit depths go to *hits when given.
  static PlaneDecision coarseRayCast(const EmbreeScene& embree, const Camera& camera, int grid,
                                     std::vector<double>* hits = nullptr, int threads = 1);
  // The cost plane from the coarse hit depths of `rays` rays and the culled leaves' loads, one
  // ray-cast pixel costing rayCost near triangles; the loads are binned on `threads` threads
  // (integer counts: the same plane for any thread count). *cost: the estimate there.
  static double costPlane(std::vector<double> hits, uint64_t rays, const Camera& camera,
                          std::span<const LeafLoad> loads, double rayCost, int threads = 1,
                          double* cost = nullptr);

 private:
  bool stillValid(const Camera& camera) const;

  LzbOptions options_;
  bool have_ = false;
  Camera at_;  // the camera of the frame that computed the plane
  double depth_ = 0.0;
  int uses_ = 0;  // frames that used it so far
  uint64_t unfinishedAtCompute_ = 0, lastUnfinished_ = 0;
  bool observed_ = false;
};

}  // namespace lzb::localz
