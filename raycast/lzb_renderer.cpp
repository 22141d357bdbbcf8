#include "raycast/lzb_renderer.hpp"

#include <omp.h>

#include <algorithm>
#include <stdexcept>

#include "raycast/lzb_cull.hpp"
#include "raycast/lzb_oor.hpp"
#include "raycast/lzb_tile_cast.hpp"
#include "raycast/screen_tiles.hpp"
#include "src/core/shading.hpp"
#include "src/core/timer.hpp"

namespace lzb {

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

}  // namespace

LzbRenderer::LzbRenderer(const Scene& scene, const RenderOptions& options, const LzbOptions& lzb)
    : scene_(scene), options_(options), lzb_(lzb), plane_(lzb) {
  validate(lzb_);
  options_.threads = std::max(options_.threads, 1);
  accel_ = std::make_unique<LzbAccel>(scene, accelParams(lzb_));
  EmbreeSceneOptions eo;
  eo.threads = options_.threads;
  embree_ = std::make_unique<EmbreeScene>(scene, eo);
  raster_ = std::make_unique<TriangleRasterizer>(scene);
  for (int t = 0; t < options_.threads; ++t)
    walkers_.emplace_back(*accel_, leafTestFor(lzb_), lzb_.octreeWalk());
}

LzbRenderer::~LzbRenderer() = default;

std::string LzbRenderer::decomposition() const {
  return "every rank renders the near pass (z-buffer up to the partition plane, computed alike "
         "on every rank) to know the unfinished pixels; screen tiles of " +
         std::to_string(ScreenTiles::kDefaultSide) + "x" +
         std::to_string(ScreenTiles::kDefaultSide) +
         " pixels are dealt to ranks interleaved (tile index mod ranks == rank); each rank casts "
         "the rays of its tiles and z-buffers its own PVL part; the root composites by (depth, "
         "id)";
}

void LzbRenderer::render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
                         FrameStats& stats) {
  if (fb.width != camera.width() || fb.height != camera.height())
    throw std::invalid_argument("lzb: framebuffer and camera sizes differ");
  const bool root = share.rank == 0;  // counts every rank shares are reported once
  const int threads = options_.threads;
  if (!buildReported_) {
    stats.addStage("build", accel_->stats().seconds + embree_->buildStats().seconds);
    stats.addCount("octrees", double(accel_->stats().octrees));
    stats.addCount("octree_nodes", double(accel_->stats().octreeNodes));
    stats.addCount("static_occluders", double(accel_->stats().occluders));
    buildReported_ = true;
  }
  Stopwatch clock;
  last_.castPixels.clear();
  last_.walk = {};

  // 1. Hierarchical view-frustum culling.
  cullScene(*accel_, camera, culled_, threads);
  const CulledScene& culled = culled_;
  stats.addStage("cull", clock.lap());

  // 2. The partition plane.
  std::vector<LeafLoad> loads;
  if (lzb_.costPlane) {
    loads.reserve(culled.leaves.size());
    for (const CullLeaf& l : culled.leaves)
      loads.push_back(
          {l.depthMin,
           uint32_t(accel_->node(culled.paths[l.path].node).leafTriangles(l.leaf).size())});
  }
  last_.plane = plane_.place(*embree_, camera, loads, threads);
  const double zClip = last_.plane.depth;
  stats.addStage("plane", clock.lap());

  // 3. Near scene by z-buffer, clipped at the plane (the far scene's size counted alongside).
  uint64_t farTriangles = 0;
  const DrawLists nearLists = nearScene(*accel_, culled, zClip, threads, &farTriangles);
  // The near pass goes straight into fb; later passes add to it (a copy stays only on request).
  fb.clear();
  // With a GL PVL to come after a GL near pass, the pass set stays open: the PVL is drawn into
  // the same z-buffer.
  bool passOpen = false;
  const bool glPvl = lzb_.usesPvl() && lzb_.pvlRender == ZBufferKind::kGl;
  if (nearLists.triangles > 0 && zClip > camera.nearPlane()) {
    if (lzb_.nearRender == ZBufferKind::kNative) {
      native_.draw(scene_, camera, nearLists, {}, threads, fb, zClip);
    } else {
      raster_->begin(camera, zClip);
      drawLists(*raster_, scene_, nearLists);
      if (glPvl) {
        raster_->read(fb);
        passOpen = true;
      } else {
        raster_->end(fb);
      }
    }
  }
  if (keepNearPass_) last_.nearPass = fb;
  stats.addStage("near", clock.lap());

  // 4. Unfinished pixels.
  uint64_t unfinished = 0;
  const bool nativePvl = lzb_.usesPvl() && !glPvl;
  open_.resize(fb.size());
  const long pixels = long(fb.size());
#pragma omp parallel for schedule(static) num_threads(threads) reduction(+ : unfinished)
  for (long i = 0; i < pixels; ++i) {
    const bool empty = fb.id[size_t(i)] == kNoId;
    open_[size_t(i)] = empty;
    unfinished += empty;
  }
  plane_.observe(unfinished);
  stats.addStage("unfinished", clock.lap());

  // 5. Far scene from the unfinished pixels of this rank's tiles.
  const ScreenTiles tiles(fb.width, fb.height);
  const std::vector<int> mine = tiles.owned(share);
  // Rays start a hair before the plane: the near pass kept fragments up to z_clip exactly.
  const double tMin = std::max(camera.nearPlane(), zClip * (1.0 - 1e-7));
  const OorObjects* oor = nullptr;
  if (lzb_.usesOor() && unfinished > 0) {
    if (!oor_) oor_ = std::make_unique<OorObjects>();
    oor_->build(*accel_, culled, camera, tMin, tiles, threads);
    oor = oor_.get();
    stats.addStage("oor_project", clock.lap());
  }
  const TileCastInput input{&camera, open_.data(), tMin, camera.farPlane(), oor};
  Framebuffer& farFb = farPass_;
  bool nativeDrawn = false;  // the native z-buffer drew the PVL
  bool farApart = false;     // farFb holds the far scene, to be composited with the near pass
  TileCastCounts tileCounts;
  const long count = unfinished > 0 ? long(mine.size()) : 0;
  std::vector<std::vector<uint32_t>> tilePixels;
  tilePixels.resize(size_t(count));
  if (!lzb_.usesPvl()) {
    farFb.resize(fb.width, fb.height);  // and clears
    farApart = true;
#pragma omp parallel num_threads(threads)
    {
      TileScratch scratch;
      TileCastCounts local;
#pragma omp for schedule(dynamic, 1)
      for (long k = 0; k < count; ++k) {
        const int t = mine[size_t(k)];
        castTileEmbree(*embree_, tiles.tile(t), t, input, scratch, farFb, local,
                       &tilePixels[size_t(k)]);
      }
#pragma omp critical
      tileCounts.add(local);
    }
    stats.addStage("raycast", clock.lap());
  } else {
    if (parts_.size() < size_t(count)) parts_.resize(size_t(count));
    for (RayWalker& w : walkers_) w.setPixelScale(camera.pixelsPerUnitAt(1.0));
    for (long k = 0; k < count; ++k) parts_[size_t(k)].clear();
#pragma omp parallel num_threads(threads)
    {
      TileScratch scratch;
      TileCastCounts local;
      RayWalker& walker = walkers_[size_t(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 1)
      for (long k = 0; k < count; ++k) {
        const int t = mine[size_t(k)];
        castTilePvl(walker, tiles.tile(t), t, input, scratch, parts_[size_t(k)], local,
                    &tilePixels[size_t(k)]);
        parts_[size_t(k)].finish();
      }
#pragma omp critical
      tileCounts.add(local);
    }
    for (RayWalker& w : walkers_) {
      last_.walk.add(w.counts);
      w.counts = {};
    }
    last_.pvl = mergePvl(*accel_, std::span<const PvlPart>(parts_.data(), size_t(count)), threads);
    stats.addStage("pvl_find", clock.lap());

    // The PVL by z-buffer, unclipped, on top of the near pass in fb: natively, or by OSMesa
    // into the open GL pass of a GL near pass (one target to clear, finish and read), else by
    // OSMesa into a pass of its own composited below. (A pass set left open without a PVL is
    // dropped: the next begin() starts afresh.)
    if (last_.pvl.triangles > 0 && nativePvl) {
      // Native: only the unfinished pixels can change (the near pass is exact where it drew),
      // and a PVL triangle covers an unfinished pixel only where a ray was cast (OOR polygons
      // hold the projections of the far content boxes). Every rank draws its PVL part at every
      // unfinished pixel, so the ranks' composite is the 1-rank image.
      native_.draw(scene_, camera, last_.pvl, open_, threads, fb);
      nativeDrawn = true;
    } else if (last_.pvl.triangles > 0 && passOpen) {
      raster_->setFarClip(0.0);
      drawLists(*raster_, scene_, last_.pvl);
      raster_->end(fb);
    } else if (last_.pvl.triangles > 0) {  // a pass of its own, composited below
      raster_->begin(camera, 0.0);
      drawLists(*raster_, scene_, last_.pvl);
      raster_->end(farFb);
      farApart = true;
    }
    stats.addStage("pvl_render", clock.lap());
  }
  if (!lzb_.usesPvl()) last_.pvl = {};
  for (auto& p : tilePixels) last_.castPixels.insert(last_.castPixels.end(), p.begin(), p.end());

  // Combine the passes (naive: min over (depth, id)) and shade from the IDs.
  if (farApart) compositeNearer(fb, farFb);
  shadeFromIds(scene_, camera, fb);
  stats.addStage("shade", clock.lap());

  if (root && lzb_.depthComplexityGrid > 0) {
    // Diagnostic (its own stage, after the frame's work): surfaces along a uniform ray grid.
    const int g = lzb_.depthComplexityGrid;
    uint64_t surfaces = 0, covered = 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) reduction(+ : surfaces, covered)
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
    stats.addCount("depth_complexity", double(surfaces) / double(g * g));
    stats.addCount("depth_complexity_covered", covered ? double(surfaces) / double(covered) : 0.0);
    stats.addStage("diagnostics", clock.lap());
  }
  if (root) {
    stats.addCount("plane_depth", zClip);
    stats.addCount("plane_fraction",
                   (zClip - camera.nearPlane()) / (camera.farPlane() - camera.nearPlane()));
    stats.addCount("plane_reused", last_.plane.reused ? 1.0 : 0.0);
    stats.addCount("coarse_rays", double(last_.plane.coarseRays));
    stats.addCount("culled_leaves", double(culled.leaves.size()));
    stats.addCount("near_leaves", double(nearLists.leaves));
    stats.addCount("near_triangles", double(nearLists.triangles));
    stats.addCount("far_triangles", double(farTriangles));
    stats.addCount("unfinished_pixels", double(unfinished));
    if (oor) stats.addCount("oor_objects", double(oor->size()));
  }
  stats.addCount("rays_cast", double(tileCounts.cast));
  if (oor) stats.addCount("oor_polygon_tests", double(tileCounts.polygonTests));
  if (lzb_.usesPvl()) {
    const RayWalkCounts& w = last_.walk;
    stats.addCount("octree_nodes_visited", double(w.nodesVisited));
    stats.addCount("octree_leaves_visited", double(w.leavesVisited));
    stats.addCount("ray_triangle_tests", double(w.triangleTests));
    stats.addCount("visibility_tests", double(w.visibilityTests));
    stats.addCount("instance_walks", double(w.instanceWalks));
    stats.addCount("rays_hit", double(w.hits));
    stats.addCount("pvl_size", double(last_.pvl.triangles));
    stats.addCount("pvl_leaves", double(last_.pvl.leaves));
    // Triangles (pieces, after clipping) that may cover a pixel centre of the image.
    if (nativeDrawn)
      stats.addCount("pvl_raster_triangles", double(native_.counts().setUp));
  }
  (void)frame;
}

}  // namespace lzb
