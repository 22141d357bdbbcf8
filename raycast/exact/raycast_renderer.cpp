#include "raycast/exact/raycast_renderer.hpp"

#include <algorithm>
#include <vector>

#include "mpi/decomposition.hpp"
#include "src/core/shading.hpp"
#include "src/core/timer.hpp"

namespace lzb {

namespace {

EmbreeSceneOptions withThreads(EmbreeSceneOptions embree, int threads) {
  embree.threads = std::max(threads, 1);
  return embree;
}

// Traces the pixel centres of one tile into fb.
void traceTile(const EmbreeScene& embree, const Camera& camera, const TileRect& r, bool packets,
               Framebuffer& fb) {
  const glm::dvec3 eye = camera.position();
  if (!packets) {
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        const RayHit h = embree.intersect(eye, camera.pixelDirection(x + 0.5, y + 0.5),
                                          camera.nearPlane(), camera.farPlane());
        fb.depth[fb.index(x, y)] = h.hit() ? h.t : kEmptyDepth;
        fb.id[fb.index(x, y)] = h.id;
      }
    return;
  }
  // 4x4 pixel blocks in order, so that each packet of 16 (or 8) rays is coherent.
  constexpr int kMax = ScreenTiles::kDefaultSide * ScreenTiles::kDefaultSide;
  Ray rays[kMax];
  RayHit hits[kMax];
  size_t pixel[kMax];
  size_t n = 0;
  for (int by = r.y0; by < r.y1; by += 4)
    for (int bx = r.x0; bx < r.x1; bx += 4)
      for (int y = by; y < std::min(by + 4, r.y1); ++y)
        for (int x = bx; x < std::min(bx + 4, r.x1); ++x) {
          rays[n] = {eye, camera.pixelDirection(x + 0.5, y + 0.5), camera.nearPlane(),
                     camera.farPlane()};
          pixel[n++] = fb.index(x, y);
        }
  embree.intersect(std::span<const Ray>(rays, n), std::span<RayHit>(hits, n));
  for (size_t k = 0; k < n; ++k) {
    fb.depth[pixel[k]] = hits[k].hit() ? hits[k].t : kEmptyDepth;
    fb.id[pixel[k]] = hits[k].id;
  }
}

}  // namespace

RaycastRenderer::RaycastRenderer(const Scene& scene, const RenderOptions& options,
                                 const RaycastTuning& tuning)
    : scene_(scene),
      options_(options),
      tuning_(tuning),
      embree_(scene, withThreads(tuning.embree, options.threads)) {}

FrameStats RaycastRenderer::setupStats() const {
  const EmbreeBuildStats& b = embree_.buildStats();
  FrameStats s;
  s.addStage("build", b.seconds);
  s.setShared("embree_scenes", double(b.levels));
  s.setShared("embree_instances", double(b.instances));
  s.setShared("skipped_instances", double(b.skippedInstances));
  return s;
}

std::string RaycastRenderer::decomposition() const {
  return "screen tiles of " + std::to_string(ScreenTiles::kDefaultSide) + "x" +
         std::to_string(ScreenTiles::kDefaultSide) +
         " pixels dealt to ranks interleaved (tile index mod ranks == rank); each rank casts the "
         "rays of its tiles against the whole scene";
}

void RaycastRenderer::render(const Camera& camera, int frame, const WorkShare& share,
                             Framebuffer& fb, FrameStats& stats) {
  Stopwatch clock;

  const ScreenTiles tiles(fb.width, fb.height);
  const std::vector<int> mine = tiles.owned(share);
  const long count = long(mine.size());
  long rays = 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(options_.threads) reduction(+ : rays)
  for (long k = 0; k < count; ++k) {
    const TileRect r = tiles.tile(mine[size_t(k)]);
    traceTile(embree_, camera, r, tuning_.packets, fb);
    rays += r.pixels();
  }
  stats.addStage("trace", clock.lap());
  stats.addCount("rays", double(rays));
}

}  // namespace lzb
