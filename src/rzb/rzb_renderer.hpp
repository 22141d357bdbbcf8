#pragma once
// --method rzb: the randomized z-buffer (Wand et al. 2001) with the z-buffer fallback for large
// triangles and the sample cache. Per frame:
//   select boxes (eps, or --eps auto) -> deal boxes to ranks by cost -> fallback boxes through
//   the native z-buffer (or OSMesa: --fallback-render gl) -> sample boxes splatted (drawn fresh, or from the cache) -> keys resolved to depth and
//   ID -> composited with the fallback by (depth, id); colour comes from the IDs after compositing
//   (pixel, splat), or from the Gaussian average of visible samples (gauss, done here).
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
  // Builds the distribution trees (scene: finalized, outlives the renderer). Throws InputError for
  // invalid params.
  RzbRenderer(const Scene& scene, const RenderOptions& options, const RzbParams& params);

  std::string name() const override { return "rzb"; }
  std::string decomposition() const override;
  // The stages below in order, each timed.
  void render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
              FrameStats& stats) override;

  // One frame's state as it passes through the stages.
  struct Frame {
    Frame(const Camera& c, int frame, const WorkShare& s, uint64_t seed)
        : camera(&c), share(s), stream(seed, uint64_t(frame)) {}
    const Camera* camera;
    WorkShare share;
    SampleStream stream;  // the frame's randomness, keyed by (seed, frame)
    uint64_t tick = 0;    // frames rendered so far (the cache's clock)
    CacheCounts cacheBefore;
    SelectParams select;
    double epsEvaluations = 0.0;
    Selection sel;
    std::vector<uint32_t> mine;  // this rank's boxes (indices into sel.boxes)
    FallbackCounts fallback;
    Framebuffer raster;  // the fallback boxes' triangles (when rastered)
    bool rastered = false;
    std::vector<SplatJob> jobs;
    std::vector<std::vector<CachedSample>> uncached;  // sets over the budget, this frame only
    uint64_t generatedForCache = 0;
    SplatSetup setup;
    PassCounts pass, gauss;
  };
  // 1. Box selection by eps (every rank alike).
  void select(Frame& f);
  // 2. This rank's boxes, by cost (gauss: all on rank 0).
  void deal(Frame& f);
  // 3. The fallback boxes' triangles by the exact z-buffer.
  void drawFallback(Frame& f);
  // 4. The sample boxes' jobs: drawn fresh from the frame's stream, or the cache's sets.
  void prepareFreshSamples(Frame& f);
  void prepareCachedSamples(Frame& f);
  // 5. The samples splatted into the key buffer.
  void splat(Frame& f);
  // 6. Keys to depth and ID, composited with the fallback.
  void resolve(Frame& f, Framebuffer& fb);
  // 7. gauss only: colour as the Gaussian average of visible samples (otherwise colour comes from
  // the IDs after compositing, as for every method).
  void shadeGauss(Frame& f, Framebuffer& fb);
  bool colourFromIds() const override { return params_.reconstruct != Reconstruct::kGauss; }

  const RzbParams& params() const { return params_; }
  // The distribution trees, also for dynamic updates between frames (SampleScene's API).
  SampleScene& sampleScene() { return *trees_; }
  const SampleCache* cache() const { return cache_.get(); }
  double lastEps() const { return lastEps_; }

 private:
  void checkCacheBudget(const Camera& camera) const;
  bool usesCache() const;
  void countFrame(const Frame& f, FrameStats& stats) const;

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
