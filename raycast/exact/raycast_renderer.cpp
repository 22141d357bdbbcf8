#include "raycast/exact/raycast_renderer.hpp"

#include <algorithm>

#include "mpi/decomposition.hpp"
#include "raycast/exact/pixel_cast.hpp"
#include "src/core/timer.hpp"

namespace lzb {

RaycastRenderer::RaycastRenderer(const Scene& scene, const RenderOptions& options,
                                 const RaycastTuning& tuning)
    : scene_(scene),
      options_(options),
      tuning_(tuning),
      embree_(scene, withRenderOptions(tuning.embree, options)) {}

FrameStats RaycastRenderer::setupStats() const {
  const EmbreeBuildStats& b = embree_.buildStats();
  FrameStats s;
  s.addStage("build", b.seconds);
  s.setShared("embree_scenes", double(b.levels));
  s.setShared("embree_instances", double(b.instances));
  s.setShared("skipped_instances", double(b.skippedInstances));
  addEmbreeMemory(b, s);
  return s;
}

std::string RaycastRenderer::decomposition() const {
  return "screen tiles of " + std::to_string(ScreenTiles::kDefaultSide) + "x" +
         std::to_string(ScreenTiles::kDefaultSide) +
         " pixels dealt to ranks interleaved (tile index mod ranks == rank); each rank casts the "
         "rays of its tiles against the whole scene";
}

void RaycastRenderer::render(const Camera& camera, int, const WorkShare& share, Framebuffer& fb,
                             FrameStats& stats) {
  Stopwatch clock;
  const uint64_t rays = castEveryPixel(embree_, camera, share, fb, stats.touchedTiles,
                                       options_.threads, tuning_.packets);
  stats.addStage("trace", clock.lap());
  stats.addCount("rays", double(rays));
}

}  // namespace lzb
