#pragma once
// --method rzb: the randomized z-buffer (Wand et al. 2001) with the z-buffer fallback for large
// triangles and the sample cache. Per frame:
//   select boxes (eps, or --eps auto) -> deal boxes to ranks by cost -> fallback boxes through
//   OSMesa -> sample boxes splatted (drawn fresh, or from the cache) -> keys resolved to depth and
//   ID -> composited with the fallback by (depth, id) -> coloured by shadeFromIds (pixel, splat)
//   or by the Gaussian average of visible samples (gauss).
// The same seed gives the same image for any thread count and any number of ranks.
#include <memory>
#include <string>

#include "src/core/renderer.hpp"
#include "src/rzb/fallback_pass.hpp"
#include "src/rzb/point_pass.hpp"
#include "src/rzb/rzb_params.hpp"
#include "src/rzb/sample_cache.hpp"
#include "src/rzb/sample_scene.hpp"

namespace lzb::rzb {

class RzbRenderer : public Renderer {
 public:
  // Builds the sample trees (scene: finalized, outlives the renderer). Throws InputError for
  // invalid params.
  RzbRenderer(const Scene& scene, const RenderOptions& options, const RzbParams& params);

  std::string name() const override { return "rzb"; }
  std::string decomposition() const override;
  void render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
              FrameStats& stats) override;

  const RzbParams& params() const { return params_; }
  // The sample trees, also for dynamic updates between frames (SampleScene's API).
  SampleScene& sampleScene() { return *trees_; }
  const SampleCache* cache() const { return cache_.get(); }
  double lastEps() const { return lastEps_; }

 private:
  const Scene& scene_;
  RenderOptions options_;
  RzbParams params_;
  std::unique_ptr<SampleScene> trees_;
  std::unique_ptr<SampleCache> cache_;
  FallbackPass fallback_;
  KeyBuffer keys_;
  double lastEps_ = 0.0;
  uint64_t frameCounter_ = 0;
};

}  // namespace lzb::rzb
