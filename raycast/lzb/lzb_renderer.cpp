#include "raycast/lzb/lzb_renderer.hpp"

#include <omp.h>

#include <algorithm>
#include <bit>
#include <cstring>

#include "mpi/decomposition.hpp"
#include "raycast/lzb/lzb_cull.hpp"
#include "raycast/lzb/lzb_oor.hpp"
#include "src/core/shading.hpp"
#include "src/core/timer.hpp"

namespace lzb::localz {

namespace {

LzbAccelParams accelParams(const LzbOptions& o) {
  LzbAccelParams p;
  p.leafEntries = uint32_t(o.leafEntries);
  p.instanceLeafEntries = uint32_t(o.instanceLeafEntries);
  p.occluders = o.occluders;
  return p;
}

// llvmpipe's indexed draws cost about 7.5 us per call plus 0.7 ns per vertex of the index range
// (measured on the 2-core machine), so a sorted list is cut where it skips more than this many
// triangles (2.1 k vertices ~ one call): sparse lists then process much smaller ranges.
constexpr uint32_t kListGap = 4096;
// A pass of ~100 K triangles does not fill llvmpipe's bins, so without a flush its rasterizer
// threads would only start in end(); flushing every this many triangles lets them rasterize
// while this thread goes on with vertices and binning (PVL pass ~20 % faster, measured).
constexpr uint64_t kFlushTriangles = 25000;

void drawLists(TriangleRasterizer& raster, const Scene& scene, const DrawLists& lists) {
  uint64_t unflushed = 0;
  for (const DrawList& l : lists.lists) {
    const std::vector<uint32_t>& t = l.triangles;
    if (t.size() == scene.nodes[l.node].mesh.size()) {
      // A whole mesh (sorted, unique, so [0, n)) draws as a range: no index list to upload.
      raster.drawRange(l.node, l.world, 0, t.size(), l.idBase);
    } else {
      // Ascending pieces, drawn in order: the same order (and depth-tie winners) as one list.
      size_t begin = 0;
      for (size_t i = 1; i <= t.size(); ++i)
        if (i == t.size() || t[i] - t[i - 1] > kListGap) {
          raster.drawList(l.node, l.world, std::span<const uint32_t>(t.data() + begin, i - begin),
                          l.idBase);
          begin = i;
        }
    }
    unflushed += t.size();
    if (unflushed >= kFlushTriangles) {
      raster.flush();
      unflushed = 0;
    }
  }
}

// Rays start a hair before the plane: the near pass kept fragments up to z_clip exactly.
double rayStart(const Camera& camera, double zClip) {
  return std::max(camera.nearPlane(), zClip * (1.0 - 1e-7));
}

}  // namespace

LzbRenderer::LzbRenderer(const Scene& scene, const RenderOptions& options, const LzbOptions& lzb)
    : scene_(scene), options_(options), lzb_(lzb), plane_(lzb) {
  validate(lzb_);
  options_.threads = std::max(options_.threads, 1);
  // Embree first: its build's transient memory (~30 bytes a triangle) then comes before the
  // octrees are held, not on top of them.
  embree_ = std::make_unique<EmbreeScene>(scene, withRenderOptions({}, options_));
  accel_ = std::make_unique<LzbAccel>(scene, accelParams(lzb_));
  raster_ = std::make_unique<TriangleRasterizer>(scene);
  for (int t = 0; t < options_.threads; ++t) {
    walkers_.emplace_back(*accel_, leafTestFor(lzb_), lzb_.octreeWalk());
    recorders_.emplace_back(*accel_);
  }
}

LzbRenderer::~LzbRenderer() = default;

std::string LzbRenderer::nearPassText() const {
  if (lzb_.nearRender == ZBufferKind::kGl)
    return "every rank renders the near pass (z-buffer up to the partition plane, placed alike "
           "on every rank) to know the unfinished pixels";
  return "the ranks split the near pass (z-buffer up to the partition plane, placed alike on "
         "every rank) by triangle ranges and OR their covered pixels to know the unfinished ones";
}

std::string LzbRenderer::decomposition() const {
  return nearPassText() + "; screen tiles of " +
         std::to_string(ScreenTiles::kDefaultSide) + "x" +
         std::to_string(ScreenTiles::kDefaultSide) +
         " pixels are dealt to ranks " + tileDealText(lzb_.tileDeal) +
         "; each rank casts the rays of its tiles and z-buffers its own PVL part; the root "
         "composites by (depth, id)";
}

FrameStats LzbRenderer::setupStats() const {
  FrameStats s;
  s.addStage("build", accel_->stats().seconds + embree_->buildStats().seconds);
  s.setShared("octrees", double(accel_->stats().octrees));
  s.setShared("octree_nodes", double(accel_->stats().octreeNodes));
  s.setShared("static_occluders", double(accel_->stats().occluders));
  addEmbreeMemory(embree_->buildStats(), s);
  return s;
}

void LzbRenderer::render(const Camera& camera, int /*frame*/, const WorkShare& share,
                         Framebuffer& fb, FrameStats& stats) {
  requireFrameSize(fb, camera, "lzb");
  Frame f;
  f.camera = &camera;
  f.share = share;
  Stopwatch clock;
  cull(f);
  stats.addStage("cull", clock.lap());
  placePlane(f);
  stats.addStage("plane", clock.lap());
  drawNearPass(f, fb);
  stats.addStage("near", clock.lap());
  markUnfinished(f, fb);
  stats.addStage("unfinished", clock.lap());
  if (lzb_.usesOor() && f.unfinished > 0) {
    projectFarObjects(f);
    stats.addStage("oor_project", clock.lap());
  }
  castFarRays(f);
  stats.addStage(lzb_.usesPvl() ? "pvl_find" : "raycast", clock.lap());
  if (lzb_.usesPvl()) {
    renderPvl(f, fb);
    stats.addStage("pvl_render", clock.lap());
  }
  if (f.farApart) {
    combine(f, fb);
    stats.addStage("combine", clock.lap());
  }
  if (share.rank == 0 && lzb_.depthComplexityGrid > 0) {
    measureDepthComplexity(camera, stats);  // a diagnostic after the frame's work
    stats.addStage("diagnostics", clock.lap());
  }
  countFrame(f, stats);
}

void LzbRenderer::cull(Frame& f, double farDepth, uint64_t triangleBudget) {
  cullScene(*accel_, *f.camera, culled_, options_.threads, f.leafFilter, farDepth,
            triangleBudget);
}

double LzbRenderer::medianCoarseHit(Frame& f) const {
  if (!f.coarse)
    f.coarse = PartitionPlane::coarseHitsOf(
        PartitionPlane::coarseRayDepths(*embree_, *f.camera, lzb_.planeGrid, options_.threads),
        *f.camera);
  const CoarseHits& cast = *f.coarse;
  if (cast.depths.empty()) return f.camera->farPlane();
  std::vector<double> hits = cast.depths;  // reordered below; the plane gets them as cast
  const auto mid = hits.begin() + std::ptrdiff_t(hits.size() / 2);
  std::nth_element(hits.begin(), mid, hits.end());
  return *mid;
}

void LzbRenderer::placePlane(Frame& f) {
  std::span<const LeafLoad> loads;
  if (plane_.needsLoads(*f.camera)) {
    loads_.resize(culled_.leaves.size());  // kept from frame to frame: no fresh pages
    const long paths = long(culled_.paths.size());
#pragma omp parallel for schedule(dynamic, 16) num_threads(options_.threads) if (paths > 64)
    for (long p = 0; p < paths; ++p) {
      const CullPath& path = culled_.paths[size_t(p)];
      const NodeAccel& a = accel_->node(path.node);
      for (uint32_t i = path.firstLeaf; i < path.firstLeaf + path.leafCount; ++i)
        loads_[i] = {culled_.leaves[i].depthMin,
                     uint32_t(a.leafTriangles(culled_.leaves[i].leaf).size())};
    }
    loads = loads_;
  }
  last_.plane = plane_.place(*embree_, *f.camera, loads, options_.threads, directRays(f),
                             f.coarse ? &*f.coarse : nullptr);
  f.zClip = last_.plane.depth;
}

void LzbRenderer::drawNearPass(Frame& f, Framebuffer& fb) {
  const Camera& camera = *f.camera;
  // The far scene's size is counted alongside.
  f.nearLists = nearScene(*accel_, culled_, f.zClip, options_.threads, &f.farTriangles);
  // fb comes cleared (the Renderer contract): a second clear cost 1-2 ms a 1080p frame.
  // With a GL PVL to come after a GL near pass, the pass set stays open: the PVL is drawn into
  // the same z-buffer.
  const bool glPvl = !directRays(f) && lzb_.pvlRender == ZBufferKind::kGl;
  if (f.nearLists.triangles > 0 && f.zClip > camera.nearPlane()) {
    f.nearDrawn = f.nearLists.triangles;
    if (lzb_.nearRender == ZBufferKind::kNative) {
      // Ranks rendering at once split the near scene by triangle ranges (markUnfinished then
      // ORs their coverage): cheaper than every rank drawing it (hybrid, city 1080p, 2 ranks x
      // 1 thread, 4 A/B pairs: near 1.7-2.1 -> 0.9-1.1 ms, unfinished with the exchange
      // 1.7-2.0 -> 2.2-2.7 ms, frame 2.7 ms faster in the median pair).
      f.nearSplit = bool(f.share.orWords);
      const IdRange part =
          f.nearSplit ? shareRange(f.nearLists.triangles, f.share) : IdRange{0, f.nearDrawn};
      f.nearDrawn = part.end - part.begin;
      native_.draw(scene_, camera, f.nearLists, {}, options_.threads, fb, f.zClip, part);
    } else {
      raster_->begin(camera, f.zClip);
      drawLists(*raster_, scene_, f.nearLists);
      if (glPvl) {
        raster_->read(fb);
        f.glPassOpen = true;
      } else {
        raster_->end(fb);
      }
    }
  }
  if (keepNearPass_) last_.nearPass = fb;
}

void LzbRenderer::markUnfinished(Frame& f, const Framebuffer& fb) {
  const long pixels = long(fb.size());
  open_.resize(fb.size());
  uint64_t unfinished = 0;
#pragma omp parallel for schedule(static) num_threads(options_.threads) reduction(+ : unfinished)
  for (long i = 0; i < pixels; ++i) {
    const uint8_t empty = fb.depth[size_t(i)] == kEmptyDepth;  // (framebuffer.hpp)
    open_[size_t(i)] = empty;
    unfinished += empty;
  }
  if (f.nearSplit) unfinished -= closeCoveredElsewhere(f.share);
  f.unfinished = unfinished;
  plane_.observe(unfinished);
}

namespace {

// The covered pixels (open 0) among open[64 w, 64 w + 64) as bits.
uint64_t coveredBits(const std::vector<uint8_t>& open, size_t w) {
  const size_t begin = 64 * w, n = std::min<size_t>(64, open.size() - begin);
  uint64_t openBits = 0;
  if (n == 64) {
    for (size_t k = 0; k < 8; ++k) {
      uint64_t bytes;  // eight 0/1 bytes; the product gathers byte i's bit at bit 56 + i
      std::memcpy(&bytes, open.data() + begin + 8 * k, 8);
      openBits |= (bytes * 0x0102040810204080ull) >> 56 << (8 * k);
    }
    return ~openBits;
  }
  for (size_t b = 0; b < n; ++b) openBits |= uint64_t(open[begin + b]) << b;
  return ~openBits & ((uint64_t(1) << n) - 1);
}

}  // namespace

uint64_t LzbRenderer::closeCoveredElsewhere(const WorkShare& share) {
  const long words = long((open_.size() + 63) / 64);
  mine_.resize(size_t(words));
  covered_.resize(size_t(words));
#pragma omp parallel for schedule(static) num_threads(options_.threads)
  for (long w = 0; w < words; ++w)
    covered_[size_t(w)] = mine_[size_t(w)] = coveredBits(open_, size_t(w));
  share.orWords(covered_);
  uint64_t closed = 0;
#pragma omp parallel for schedule(static) num_threads(options_.threads) reduction(+ : closed)
  for (long w = 0; w < words; ++w) {
    uint64_t elsewhere = covered_[size_t(w)] & ~mine_[size_t(w)];
    closed += uint64_t(std::popcount(elsewhere));
    for (; elsewhere; elsewhere &= elsewhere - 1)
      open_[64 * size_t(w) + size_t(std::countr_zero(elsewhere))] = 0;
  }
  return closed;
}

void LzbRenderer::projectFarObjects(Frame& f) {
  const Camera& camera = *f.camera;
  if (!oor_) oor_ = std::make_unique<OorObjects>();
  oor_->build(*accel_, culled_, camera, rayStart(camera, f.zClip),
              ScreenTiles(camera.width(), camera.height()), options_.threads);
  f.oor = oor_.get();
}

void LzbRenderer::castFarRays(Frame& f) {
  // This frame's cast pixels and walk counts only (the hybrid calls the stages one by one).
  last_.castPixels.clear();
  last_.walk = {};
  last_.hitLeaves = {};
  const Camera& camera = *f.camera;
  const TileCastInput input{&camera, open_.data(), rayStart(camera, f.zClip), camera.farPlane(),
                            f.oor};
  f.tiles = dealTiles(f, input);
  const long count = f.unfinished > 0 ? long(f.tiles.size()) : 0;
  std::vector<std::vector<uint32_t>> tilePixels(static_cast<size_t>(count));
  if (directRays(f)) {
    castNaiveRays(f, input, tilePixels);
  } else {
    // The walk alone skips what a composing method draws elsewhere (its LeafFilter).
    f.walked = lzb_.usesWalk() || f.leafFilter;
    if (parts_.size() < size_t(count)) parts_.resize(size_t(count));
    for (long k = 0; k < count; ++k) parts_[size_t(k)].clear();
    if (f.walked)
      findPvlByWalk(f, input, tilePixels);
    else
      findPvlByEmbree(f, input, tilePixels);
    last_.pvl = mergePvl(*accel_, std::span<const PvlPart>(parts_.data(), size_t(count)),
                         options_.threads);
  }
  for (auto& p : tilePixels) last_.castPixels.insert(last_.castPixels.end(), p.begin(), p.end());
}

std::vector<int> LzbRenderer::dealTiles(const Frame& f, const TileCastInput& input) const {
  const ScreenTiles tiles(f.camera->width(), f.camera->height());
  if (lzb_.tileDeal == TileDeal::kInterleaved || f.share.size == 1 || f.unfinished == 0)
    return tiles.owned(f.share);
  // Every rank counts every tile's rays alike (the mask and OOR objects are replicated).
  std::vector<double> costs(size_t(tiles.count()));
#pragma omp parallel num_threads(options_.threads)
  {
    TileScratch scratch;
    TileCastCounts ignored;
#pragma omp for schedule(dynamic, 16)
    for (int t = 0; t < tiles.count(); ++t)
      costs[size_t(t)] = double(countTileRays(tiles.tile(t), t, input, scratch, ignored));
  }
  return tiles.ownedByCost(costs, f.share);
}

template <typename CastTile>
void LzbRenderer::forOwnedTiles(Frame& f, std::vector<std::vector<uint32_t>>& tilePixels,
                                CastTile castTile) {
  const ScreenTiles tiles(f.camera->width(), f.camera->height());
  const long count = long(tilePixels.size());
#pragma omp parallel num_threads(options_.threads)
  {
    TileScratch scratch;
    TileCastCounts local;
    const size_t thread = size_t(omp_get_thread_num());
#pragma omp for schedule(dynamic, 1)
    for (long k = 0; k < count; ++k) {
      const int t = f.tiles[size_t(k)];
      castTile(thread, tiles.tile(t), t, size_t(k), scratch, local, &tilePixels[size_t(k)]);
    }
#pragma omp critical
    f.tileCounts.add(local);
  }
}

void LzbRenderer::castNaiveRays(Frame& f, const TileCastInput& input,
                                std::vector<std::vector<uint32_t>>& tilePixels) {
  farPass_.resize(f.camera->width(), f.camera->height());  // and clears
  f.farApart = true;
  forOwnedTiles(f, tilePixels,
                [&](size_t, const TileRect& r, int t, size_t, TileScratch& scratch,
                    TileCastCounts& local, std::vector<uint32_t>* cast) {
                  castTileEmbree(*embree_, r, t, input, scratch, farPass_, local, cast);
                });
  last_.pvl = {};
}

void LzbRenderer::findPvlByWalk(Frame& f, const TileCastInput& input,
                                std::vector<std::vector<uint32_t>>& tilePixels) {
  const Camera& camera = *f.camera;
  for (RayWalker& w : walkers_) {
    w.setPixelScale(camera.pixelsPerUnitAt(1.0));
    w.setLeafFilter(f.leafFilter, camera.position(), camera.forward());
  }
  forOwnedTiles(f, tilePixels,
                [&](size_t thread, const TileRect& r, int t, size_t k, TileScratch& scratch,
                    TileCastCounts& local, std::vector<uint32_t>* cast) {
                  castTilePvl(walkers_[thread], r, t, input, scratch, parts_[k], local, cast);
                  parts_[k].finish();
                });
  for (RayWalker& w : walkers_) {
    last_.walk.add(w.counts);
    w.counts = {};
  }
}

void LzbRenderer::findPvlByEmbree(Frame& f, const TileCastInput& input,
                                  std::vector<std::vector<uint32_t>>& tilePixels) {
  for (HitLeafRecorder& r : recorders_) r.setPixelScale(f.camera->pixelsPerUnitAt(1.0));
  forOwnedTiles(f, tilePixels,
                [&](size_t thread, const TileRect& r, int t, size_t k, TileScratch& scratch,
                    TileCastCounts& local, std::vector<uint32_t>* cast) {
                  castTileHits(*embree_, recorders_[thread], r, t, input, scratch, parts_[k],
                               local, cast);
                  parts_[k].finish();
                });
  for (HitLeafRecorder& r : recorders_) {
    last_.hitLeaves.add(r.counts);
    r.counts = {};
  }
}

void LzbRenderer::renderPvl(Frame& f, Framebuffer& fb) {
  const DrawLists& pvl = last_.pvl;
  if (pvl.triangles == 0) return;  // (a GL pass set left open is dropped: begin() starts afresh)
  const Camera& camera = *f.camera;
  if (lzb_.pvlRender == ZBufferKind::kNative) {
    // Only the unfinished pixels can change (the near pass is exact where it drew), and a PVL
    // triangle covers an unfinished pixel only where a ray was cast (OOR polygons hold the
    // projections of the far content boxes). Every rank draws its PVL part at every unfinished
    // pixel, so the ranks' composite is the 1-rank image.
    native_.draw(scene_, camera, pvl, open_, options_.threads, fb);
    f.nativePvl = true;
  } else if (f.glPassOpen) {
    // Unclipped into the open GL pass of a GL near pass: one target to clear, finish and read.
    raster_->setFarClip(0.0);
    drawLists(*raster_, scene_, pvl);
    raster_->end(fb);
  } else {
    // After a native near pass: a GL pass of its own, composited by (depth, ID) in shade().
    raster_->begin(camera, 0.0);
    drawLists(*raster_, scene_, pvl);
    raster_->end(farPass_);
    f.farApart = true;
  }
}

void LzbRenderer::combine(Frame& f, Framebuffer& fb) {
  if (f.farApart) compositeNearer(fb, farPass_);
}

void LzbRenderer::measureDepthComplexity(const Camera& camera, FrameStats& stats) {
  const int g = lzb_.depthComplexityGrid;
  uint64_t surfaces = 0, covered = 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(options_.threads) reduction(+ : surfaces, covered)
  for (int j = 0; j < g; ++j) {
    RayWalker& w = walkers_[size_t(omp_get_thread_num())];
    for (int i = 0; i < g; ++i) {
      const double px = (i + 0.5) * camera.width() / g, py = (j + 0.5) * camera.height() / g;
      const uint64_t n = w.countSurfaces(camera.position(), camera.pixelDirection(px, py),
                                         camera.nearPlane(), camera.farPlane());
      surfaces += n;
      covered += n > 0;
    }
  }
  stats.setShared("depth_complexity", double(surfaces) / double(g * g));
  stats.setShared("depth_complexity_covered", covered ? double(surfaces) / double(covered) : 0.0);
}

void LzbRenderer::countFrame(const Frame& f, FrameStats& stats) const {
  const Camera& camera = *f.camera;
  // Every rank computes the plane, the cull and the near scene's lists alike.
  stats.setShared("plane_depth", f.zClip);
  stats.setShared("plane_fraction",
                  (f.zClip - camera.nearPlane()) / (camera.farPlane() - camera.nearPlane()));
  stats.setShared("plane_reused", last_.plane.reused ? 1.0 : 0.0);
  if (last_.plane.cost >= 0.0) stats.setShared("plane_cost", last_.plane.cost);
  stats.setShared("coarse_rays", double(last_.plane.coarseRays));
  stats.setShared("culled_leaves", double(culled_.leaves.size()));
  stats.setShared("near_leaves", double(f.nearLists.leaves));
  stats.setShared("near_triangles", double(f.nearLists.triangles));
  stats.setShared("far_triangles", double(f.farTriangles));
  stats.setShared("unfinished_pixels", double(f.unfinished));
  if (f.oor) stats.setShared("oor_objects", double(f.oor->size()));
  // This rank's share.
  stats.addCount("near_triangles_drawn", double(f.nearDrawn));
  stats.addCount("rays_cast", double(f.tileCounts.cast));
  if (f.oor) stats.addCount("oor_polygon_rows", double(f.tileCounts.polygonRows));
  if (f.walked) {
    const RayWalkCounts& w = last_.walk;
    stats.addCount("octree_nodes_visited", double(w.nodesVisited));
    stats.addCount("octree_leaves_visited", double(w.leavesVisited));
    stats.addCount("ray_triangle_tests", double(w.triangleTests));
    stats.addCount("visibility_tests", double(w.visibilityTests));
    stats.addCount("instance_walks", double(w.instanceWalks));
    stats.addCount("rays_hit", double(w.hits));
  } else if (!directRays(f)) {
    const HitLeafCounts& h = last_.hitLeaves;
    stats.addCount("octree_nodes_visited", double(h.nodesVisited));
    stats.addCount("rays_hit", double(h.hits));
    stats.addCount("hit_placements_resolved", double(h.resolves));
  }
  if (!directRays(f)) {
    stats.addCount("pvl_size", double(last_.pvl.triangles));
    stats.addCount("pvl_leaves", double(last_.pvl.leaves));
    // Triangles (pieces, after clipping) that may cover a pixel centre of the image.
    if (f.nativePvl) stats.addCount("pvl_raster_triangles", double(native_.counts().setUp));
  }
}

}  // namespace lzb::localz
