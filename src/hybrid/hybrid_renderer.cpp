#include "src/hybrid/hybrid_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mpi/decomposition.hpp"
#include "raycast/exact/pixel_cast.hpp"
#include "src/core/error.hpp"
#include "src/core/timer.hpp"
#include "src/hybrid/screen_cover.hpp"
#include "src/splat/splatter.hpp"

namespace lzb::hybrid {

void HybridParams::validate() const {
  require(oversample > 0.0 && oversample <= 1000.0, "--oversample", "must be in (0, 1000]");
  validateSplat(splat);
  require(fallbackPx >= 0.0 && std::isfinite(fallbackPx), "--fallback",
          "must be 'auto' or a pixel area > 0 for the hybrid");
  localz::validate(lzb);
}

FarPass parseFarPass(const std::string& text, const std::string& field) {
  if (text == "auto") return FarPass::kAuto;
  if (text == "lazy") return FarPass::kLazy;
  if (text == "direct") return FarPass::kDirect;
  throw InputError(field + ": expected auto, lazy or direct, got '" + text + "'");
}

std::string toString(FarPass p) {
  return p == FarPass::kAuto ? "auto" : p == FarPass::kLazy ? "lazy" : "direct";
}

FrameWay parseFrameWay(const std::string& text, const std::string& field) {
  if (text == "auto") return FrameWay::kAuto;
  if (text == "local") return FrameWay::kLocal;
  if (text == "rays") return FrameWay::kRays;
  throw InputError(field + ": expected auto, local or rays, got '" + text + "'");
}

std::string toString(FrameWay w) {
  return w == FrameWay::kAuto ? "auto" : w == FrameWay::kLocal ? "local" : "rays";
}

PointParams HybridParams::pointParams(int width, int height) const {
  const double lnPixels = std::log(double(width) * double(height));
  PointParams p;
  p.splat = splat;
  p.samplesPerPixel = oversample * lnPixels / double(splat * splat);
  p.thresholdPx = fallbackPx > 0.0 ? fallbackPx : kAutoFallbackPx * double(splat * splat);
  p.dropBackfaces = dropBackfaces;
  return p;
}

nlohmann::json HybridParams::toJson() const {
  return {{"oversample", oversample},
          {"splat", splat},
          {"fallback", fallbackPx > 0.0 ? nlohmann::json(fallbackPx) : nlohmann::json("auto")},
          {"backfaces", dropBackfaces ? "drop" : "keep"},
          {"plane", lzb.dynamicPlane() ? nlohmann::json(lzb.costPlane ? "cost" : "auto")
                                       : nlohmann::json(lzb.planeFraction)},
          {"far_pass", toString(farPass)},
          {"frame_way", toString(frameWay)},
          {"lzb_stage", toString(lzb.stage)},
          {"tile_deal", toString(lzb.tileDeal)}};
}

namespace {

LeafAreas timedAreas(const localz::LzbAccel& accel, double& seconds) {
  Stopwatch clock;
  LeafAreas areas(accel);
  seconds = clock.seconds();
  return areas;
}

}  // namespace

HybridRenderer::HybridRenderer(const Scene& scene, const RenderOptions& options,
                               const HybridParams& params)
    : scene_(scene),
      options_(options),
      params_(params),
      lzb_(scene, options, params.lzb),
      areas_(timedAreas(lzb_.accel(), areasSeconds_)) {
  params_.validate();
  options_.threads = std::max(options_.threads, 1);
}

std::string HybridRenderer::decomposition() const {
  return lzb_.nearPassText() +
         "; the octree leaves behind the plane that are point-sampled are dealt to ranks as "
         "contiguous runs of equal sample count in cull order; screen tiles of " +
         std::to_string(ScreenTiles::kDefaultSide) + "x" +
         std::to_string(ScreenTiles::kDefaultSide) +
         " pixels are dealt for the rays " + tileDealText(params_.lzb.tileDeal) +
         " and each rank z-buffers its own PVL part; "
         "the root composites by (depth, id)";
}

FrameStats HybridRenderer::setupStats() const {
  FrameStats s = lzb_.setupStats();
  s.addStage("leaf_areas", areasSeconds_);
  s.setShared("leaf_area_bytes", double(areas_.memoryBytes()));
  return s;
}

localz::LzbRenderer::Frame HybridRenderer::beginFrame(const Camera& camera, const WorkShare& share,
                                                      const PointParams& pp) {
  localz::LzbRenderer::Frame f;
  f.camera = &camera;
  f.share = share;
  rule_ = std::make_unique<SampledLeafRule>(lzb_.accel(), areas_, camera.pixelsPerUnitAt(1.0),
                                            pp.thresholdPx);
  f.leafFilter = rule_.get();  // the cull leaves wholly sampled nodes out
  return f;
}

void HybridRenderer::render(const Camera& camera, int frame, const WorkShare& share,
                            Framebuffer& fb, FrameStats& stats) {
  requireFrameSize(fb, camera, "hybrid");
  const PointParams pp = params_.pointParams(camera.width(), camera.height());
  localz::LzbRenderer::Frame f = beginFrame(camera, share, pp);
  Stopwatch clock;
  bool everyPixel = params_.frameWay == FrameWay::kRays;
  const bool byParts = decided_.has_value();
  if (byParts) {  // the parts' probe chose (phase 3); the plane gets this part's coarse rays
    everyPixel = *decided_;
    decided_.reset();
    f.coarse = localz::PartitionPlane::coarseHitsOf(coarseDepths_, camera);
  } else if (params_.frameWay == FrameWay::kAuto) {
    everyPixel = castEveryPixelPays(f, stats);
    stats.addStage("probe", clock.lap());
  }
  if (everyPixel) return castEveryPixelInstead(camera, share, fb, stats, clock);
  double culledTriangles = -1.0;
  const double cullDepth = cullForFarPass(f, &culledTriangles);
  f.directRays = directRaysPay(camera, culledTriangles);
  stats.addStage("cull", clock.lap());
  lzb_.placePlane(f);
  f.zClip = std::min(f.zClip, cullDepth);  // a reused plane may lie beyond a partial cull
  rule_->setPlane(f.zClip);
  stats.addStage("plane", clock.lap());
  if (params_.frameWay == FrameWay::kAuto && !byParts && planeCostsMoreThanCasting(camera, stats))
    return castEveryPixelInstead(camera, share, fb, stats, clock);
  stats.setShared("every_pixel_cast", 0.0);
  lzb_.drawNearPass(f, fb);
  stats.addStage("near", clock.lap());
  lzb_.markUnfinished(f, fb);
  stats.addStage("unfinished", clock.lap());
  drawPoints(f, pp, frame, stats);
  stats.addStage("points", clock.lap());
  if (f.directRays) {
    lzb_.castFarRays(f);
    stats.addStage("raycast", clock.lap());
  } else {
    if (f.unfinished > 0) {
      lzb_.projectFarObjects(f);
      stats.addStage("oor_project", clock.lap());
    }
    lzb_.castFarRays(f);
    stats.addStage("pvl_find", clock.lap());
    lzb_.renderPvl(f, fb);
    stats.addStage("pvl_render", clock.lap());
  }
  lzb_.combine(f, fb);  // direct rays' hits (no samples with them) before the pixel count
  countPixels(f, fb, stats);
  if (pointsDrawn_) compositeNearer(fb, points_);
  stats.addStage("combine", clock.lap());
  lzb_.countFrame(f, stats);
  if (cullDepth < camera.farPlane()) stats.setShared("cull_depth", cullDepth);
}

size_t HybridRenderer::probeRays(const Camera& camera) const {
  if (params_.frameWay != FrameWay::kAuto) return 0;
  const auto [gx, gy] = localz::PartitionPlane::coarseGrid(camera, lzb_.options().planeGrid);
  return size_t(gx) * size_t(gy);
}

std::span<const double> HybridRenderer::coarseRayDepths(const Camera& camera) {
  coarseDepths_ = localz::PartitionPlane::coarseRayDepths(
      lzb_.embree(), camera, lzb_.options().planeGrid, options_.threads);
  return coarseDepths_;
}

ProbeCounts HybridRenderer::probe(const Camera& camera, std::span<const double> frameDepths) {
  localz::LzbRenderer::Frame f =
      beginFrame(camera, WorkShare{}, params_.pointParams(camera.width(), camera.height()));
  return probeCounts(f, frameDepths);
}

namespace {

// The probe's plane: the coarse hit with kProbeQuantile of the hits in front of it, and the
// pixels a near pass up to it would finish. None without a hit.
struct ProbePlane {
  double depth = 0.0, finished = 0.0;
};

std::optional<ProbePlane> probePlane(const Camera& camera, std::span<const double> perRay) {
  std::vector<double> hits;
  for (double t : perRay)
    if (std::isfinite(t)) hits.push_back(t);
  if (hits.empty()) return std::nullopt;
  const size_t k = size_t(double(hits.size() - 1) * HybridParams::kProbeQuantile);
  std::nth_element(hits.begin(), hits.begin() + std::ptrdiff_t(k), hits.end());
  const double pixelsPerRay =
      double(camera.width()) * double(camera.height()) / double(perRay.size());
  return ProbePlane{hits[k], double(k + 1) * pixelsPerRay};
}

}  // namespace

ProbeCounts HybridRenderer::probeCounts(localz::LzbRenderer::Frame& f,
                                        std::span<const double> frameDepths) {
  ProbeCounts c;
  c.sceneTriangles = scene_.expandedTriangles();
  const std::optional<ProbePlane> plane = probePlane(*f.camera, frameDepths);
  if (!plane) return c;
  // The choice asks whether the triangles reach the finished pixels (or a share of them), so the
  // cull may stop there, and the count is capped there: the same count whatever the threads.
  const uint64_t budget = uint64_t(std::ceil(plane->finished));
  lzb_.cull(f, plane->depth, budget);
  for (const localz::CullPath& p : lzb_.culled().paths) {
    if (p.drawnElsewhere || p.subtree) ++c.sampledUnits;
    c.triangles += p.leafTriangles;
  }
  // Past the budget the walk's order decides what was listed: say only that it was reached.
  if (c.triangles >= budget) c.triangles = budget, c.sampledUnits = 0;
  c.sampledUnits = std::min<uint64_t>(c.sampledUnits, 1);
  return c;
}

bool HybridRenderer::everyPixelPays(const Camera& camera, std::span<const double> frameDepths,
                                    const ProbeCounts& frame, FrameStats& stats) const {
  const std::optional<ProbePlane> plane = probePlane(camera, frameDepths);
  if (!plane) return true;  // nothing met: no near pass would finish a pixel
  const double nearCost = double(frame.sceneTriangles) >= denseTriangles(camera)
                              ? HybridParams::kDenseNearTriangleCost
                              : 1.0;
  stats.setShared("probe_depth", plane->depth);
  stats.setShared("probe_finished_pixels", plane->finished);
  stats.setShared("probe_near_triangle_cost", nearCost);
  stats.setShared("probe_triangles", double(frame.triangles));
  stats.setShared("probe_sampled_units", double(frame.sampledUnits));
  // A unit the point pass takes whole sends the far rays through the octree walk, which loses
  // to Embree's (the chessboard: 540 against 112 ms a frame, runs/peers).
  if (frame.sampledUnits > 0) return true;
  // The cost plane's comparison (lzb_plane.hpp) of the probe's plane with casting every pixel:
  // triangles shrink on screen with depth, so the nearest covered pixels are the cheapest a near
  // pass finishes, and no plane beyond pays when this one does not.
  return nearCost * double(frame.triangles) >= plane->finished;
}

void HybridRenderer::castEveryPixelInstead(const Camera& camera, const WorkShare& share,
                                           Framebuffer& fb, FrameStats& stats, Stopwatch& clock) {
  stats.setShared("every_pixel_cast", 1.0);
  const std::optional<BlockCover> cover = coverWhereSparse(camera, stats);
  stats.addStage("cover", clock.lap());
  stats.addCount("rays_cast",
                 double(castEveryPixel(lzb_.embree(), camera, share, fb, stats.touchedTiles,
                                       options_.threads, true, cover ? &*cover : nullptr)));
  stats.addStage("trace", clock.lap());
}

std::optional<BlockCover> HybridRenderer::coverWhereSparse(const Camera& camera,
                                                           FrameStats& stats) const {
  const double castable = double(castablePixels(lzb_.embree(), camera));
  if (!coarseDepths_.empty()) {  // the probe's rays: cover only where most castable pixels miss
    const double hits = double(std::count_if(coarseDepths_.begin(), coarseDepths_.end(),
                                             [](double t) { return std::isfinite(t); }));
    const double covered =
        hits / double(coarseDepths_.size()) * double(camera.width()) * double(camera.height());
    if (covered >= HybridParams::kCoverBelowShare * castable) return std::nullopt;
  }
  const uint64_t budget = uint64_t(castable / double(BlockCover::kSide * BlockCover::kSide) *
                                   HybridParams::kCoverNodesPerBlock);
  std::optional<BlockCover> cover = screenCover(lzb_.accel(), camera, budget);
  stats.setShared("cover_blocks", cover ? double(cover->blocks()) : -1.0);
  return cover;
}

bool HybridRenderer::planeCostsMoreThanCasting(const Camera& camera, FrameStats& stats) const {
  const double cost = lzb_.lastFrame().plane.cost;
  if (cost < 0.0) return false;  // a static or reused plane: no estimate
  const double castable = double(castablePixels(lzb_.embree(), camera));
  stats.setShared("castable_pixels", castable);
  return cost > HybridParams::kCastPixelCost * castable;
}

bool HybridRenderer::castEveryPixelPays(localz::LzbRenderer::Frame& f, FrameStats& stats) {
  const Camera& camera = *f.camera;
  coarseRayDepths(camera);
  f.coarse = localz::PartitionPlane::coarseHitsOf(coarseDepths_, camera);
  return everyPixelPays(camera, coarseDepths_, probeCounts(f, coarseDepths_), stats);
}

double HybridRenderer::cullForFarPass(localz::LzbRenderer::Frame& f, double* triangles) {
  const Camera& camera = *f.camera;
  const double dense = denseTriangles(camera);
  const bool mayGoDirect = params_.farPass != FarPass::kLazy;
  if (mayGoDirect && double(scene_.expandedTriangles()) >= dense) {
    const double depth = lzb_.medianCoarseHit(f);
    if (depth < camera.farPlane()) {
      lzb_.cull(f, depth);
      *triangles = exactlyCulledTriangles();
      if (*triangles >= dense) return depth;
    }
  }
  lzb_.cull(f);
  *triangles = mayGoDirect ? exactlyCulledTriangles() : -1.0;
  return std::numeric_limits<double>::infinity();
}

void HybridRenderer::drawPoints(localz::LzbRenderer::Frame& f, const PointParams& pp, int frame,
                                FrameStats& stats) {
  const Camera& camera = *f.camera;
  const SampleStream stream(options_.seed, uint64_t(frame));
  const bool prepared = areas_.samplingPrepared();
  // A direct frame samples nothing: each pixel's Embree hit is exact at any triangle size.
  const SampledUnits units =
      f.directRays ? SampledUnits{}
                   : sampledLeaves(lzb_.accel(), areas_, lzb_.culled(), *rule_, camera, pp, stream);
  if (!prepared && areas_.samplingPrepared()) {  // this frame sampled first: it built the sums
    stats.setShared("leaf_area_bytes", double(areas_.memoryBytes()));
    stats.setShared("leaf_area_seconds", areas_.samplingSeconds());
  }
  const std::vector<SampledLeaf>& leaves = units.leaves;
  // Nothing the rays could meet is sampled (the rays stay in the culled frustum): they walk
  // unfiltered, which is much cheaper through instances (city 1080p: pvl_find 64 -> ~50 ms).
  // Otherwise the rays must walk, skipping the sampled units.
  if (units.accepted == 0) f.leafFilter = nullptr;
  std::vector<double> costs(leaves.size());
  double total = 0.0;
  for (size_t i = 0; i < leaves.size(); ++i) total += costs[i] = double(leaves[i].samples);
  const std::vector<uint32_t> mine = dealByCost(costs, f.share);
  PointCounts pc;
  pointsDrawn_ = !mine.empty();
  if (pointsDrawn_) {  // no key buffer to clear, resolve and composite for a rank without samples
    keys_.reset(camera.width(), camera.height(), scene_.expandedTriangles() > 0xffffffffull,
                options_.threads);
    pc = splatLeaves(lzb_.accel(), areas_, lzb_.culled(), leaves, mine, camera, pp, stream, keys_,
                     options_.threads);
    // resolve writes every depth and ID; colour stays the background (a clear: 33 MB at 1080p).
    points_.resizeUnlessSized(camera.width(), camera.height());
    keys_.resolve(points_, options_.threads);
  }
  stats.setShared("sampled_leaves", double(leaves.size()));
  stats.setShared("samples_expected", total);
  stats.setShared("fallback_px", pp.thresholdPx);
  stats.addCount("sampled_leaves_drawn", double(mine.size()));
  stats.addCount("samples_drawn", double(pc.drawn));
  stats.addCount("samples_backfacing", double(pc.backfacing));
  stats.addCount("samples_splatted", double(pc.splatted));
}

double HybridRenderer::denseTriangles(const Camera& camera) const {
  return HybridParams::kDirectTrianglesPerPixel * double(camera.width()) * camera.height();
}

double HybridRenderer::exactlyCulledTriangles() const {
  uint64_t triangles = 0;
  for (const localz::CullPath& p : lzb_.culled().paths) {
    if (p.drawnElsewhere || p.subtree) return -1.0;
    triangles += p.leafTriangles;
  }
  return double(triangles);
}

bool HybridRenderer::directRaysPay(const Camera& camera, double culledTriangles) const {
  if (params_.farPass == FarPass::kLazy) return false;
  return culledTriangles >= 0.0 &&
         (params_.farPass == FarPass::kDirect || culledTriangles >= denseTriangles(camera));
}

// Which pass finished each pixel of this rank's tiles: the near pass (shared), the samples or
// the PVL (or the direct rays), counted before compositing with the other ranks, whose samples
// may still win.
void HybridRenderer::countPixels(const localz::LzbRenderer::Frame& f, const Framebuffer& fb,
                                 FrameStats& stats) const {
  const ScreenTiles tiles(fb.width, fb.height);
  const std::vector<uint8_t>& open = lzb_.unfinishedMask();
  const std::vector<int>& mine = f.tiles;
  uint64_t samplePixels = 0, pvlPixels = 0;
#pragma omp parallel for schedule(static) num_threads(options_.threads) reduction(+ : samplePixels, pvlPixels)
  for (size_t k = 0; k < mine.size(); ++k) {
    const TileRect r = tiles.tile(mine[k]);
    for (int y = r.y0; y < r.y1; ++y) {
      if (!pointsDrawn_) {  // no samples: the PVL drew every covered unfinished pixel
        const size_t row = fb.index(r.x0, y);
        const uint8_t* o = open.data() + row;
        const float* depth = fb.depth.data() + row;  // covered <=> a depth (framebuffer.hpp)
        uint32_t n = 0;  // branch-free, so it vectorizes (the branchy loop: 4 ms at 1080p)
        for (int x = 0; x < r.x1 - r.x0; ++x) n += o[x] & uint8_t(depth[x] != kEmptyDepth);
        pvlPixels += n;
        continue;
      }
      for (int x = r.x0; x < r.x1; ++x) {
        const size_t i = fb.index(x, y);
        if (!open[i]) continue;
        if (points_.covered(i) && nearer(points_.depth[i], points_.id[i], fb.depth[i], fb.id[i]))
          ++samplePixels;
        else if (fb.covered(i))
          ++pvlPixels;
      }
    }
  }
  stats.setShared("near_pixels", double(fb.size() - f.unfinished));
  stats.addCount("sample_pixels", double(samplePixels));
  stats.addCount(f.directRays ? "ray_pixels" : "pvl_pixels", double(pvlPixels));
}

}  // namespace lzb::hybrid
