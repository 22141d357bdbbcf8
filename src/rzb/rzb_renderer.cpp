#include "src/rzb/rzb_renderer.hpp"

#include <algorithm>
#include <cmath>

#include "src/core/error.hpp"
#include "src/core/shading.hpp"
#include "src/core/timer.hpp"
#include "src/rzb/deal.hpp"
#include "src/rzb/eps_search.hpp"

namespace lzb::rzb {

namespace {

// Boxes with fewer samples than this are built as the cache's sets in one parallel loop;
// larger ones one at a time with parallel generation inside.
constexpr uint64_t kSmallSet = 1 << 16;
// A box never gets more samples than this many image-covering layers at the target density.
constexpr double kMaxBoxLayers = 16.0;

}  // namespace

RzbRenderer::RzbRenderer(const Scene& scene, const RenderOptions& options, const RzbParams& params)
    : scene_(scene),
      options_(options),
      params_(params),
      fallback_(scene, params.fallbackRender, std::max(options.threads, 1)) {
  params_.validate();
  options_.threads = std::max(options_.threads, 1);
  DistributionParams tp;
  tp.areaRatio = params_.areaRatio;
  tp.progress = !options.quiet;
  trees_ = std::make_unique<SampleScene>(scene, tp);
  if (params_.cacheMb > 0.0)
    cache_ = std::make_unique<SampleCache>(params_.cacheBytes());
}

std::string RzbRenderer::decomposition() const {
  if (params_.reconstruct == Reconstruct::kGauss)
    return "gauss reconstruction sums colours over all visible samples, which depth compositing "
           "cannot combine: rank 0 renders the whole frame, the others contribute nothing";
  return "box selection on every rank; the selected octree boxes are dealt to ranks as contiguous "
         "runs of equal estimated cost (samples, fallback triangles) in selection order; each rank "
         "splats its sample boxes and rasterizes its fallback boxes; depth compositing by "
         "(depth, id)";
}

void RzbRenderer::render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
                         FrameStats& stats) {
  Frame f(camera, frame, share, options_.seed);
  f.tick = ++frameCounter_;
  f.cacheBefore = cache_ ? cache_->counts() : CacheCounts{};
  checkCacheBudget(camera);
  Stopwatch clock;
  select(f);
  stats.addStage("select", clock.lap());
  deal(f);
  drawFallback(f);
  stats.addStage("fallback", clock.lap());
  if (usesCache()) {
    prepareCachedSamples(f);
    stats.addStage("cache_build", clock.lap());
  } else {
    prepareFreshSamples(f);
  }
  splat(f);
  stats.addStage("splat", clock.lap());
  resolve(f, fb);
  stats.addStage("resolve", clock.lap());
  if (params_.reconstruct == Reconstruct::kGauss) {
    shadeGauss(f, fb);
    stats.addStage("shade", clock.lap());
  }
  countFrame(f, stats);
}

void RzbRenderer::checkCacheBudget(const Camera& camera) const {
  if (!cache_) return;
  const uint64_t need = RzbParams::minCacheBytes(camera.width(), camera.height(), params_.splat);
  require(cache_->budget() >= need, "--cache-mb",
          "is below one box: a box covering the " + std::to_string(camera.width()) + "x" +
              std::to_string(camera.height()) + " image needs " + std::to_string(need / 1024) +
              " KiB");
}

bool RzbRenderer::usesCache() const {
  return cache_ && params_.reconstruct != Reconstruct::kGauss;
}

void RzbRenderer::select(Frame& f) {
  const Camera& camera = *f.camera;
  const double pixels = double(camera.width()) * double(camera.height());
  SelectParams& sp = f.select;
  sp.eps = params_.eps;
  sp.samplesPerPixel = params_.samplesPerPixel(pixels);
  sp.fallbackPx = params_.fallbackThreshold(pixels);
  sp.maxBoxSamples = kMaxBoxLayers * pixels * sp.samplesPerPixel;
  if (params_.autoEps) {
    const EpsSearch found = searchEps(*trees_, camera, sp, f.stream, lastEps_);
    sp.eps = found.eps;
    f.epsEvaluations = found.evaluations;
  }
  lastEps_ = sp.eps;
  f.sel = selectBoxes(*trees_, camera, sp, f.stream);
}

void RzbRenderer::deal(Frame& f) {
  // gauss sums colours over all visible samples, which depth compositing cannot combine.
  if (params_.reconstruct == Reconstruct::kGauss) {
    if (f.share.rank == 0) f.mine = dealBoxes(f.sel.boxes, WorkShare{});
  } else {
    f.mine = dealBoxes(f.sel.boxes, f.share);
  }
}

void RzbRenderer::drawFallback(Frame& f) {
  const std::vector<SelectedBox>& boxes = f.sel.boxes;
  if (std::none_of(f.mine.begin(), f.mine.end(), [&](uint32_t i) { return boxes[i].fallback; }))
    return;
  f.raster.resize(f.camera->width(), f.camera->height());
  f.rastered = fallback_.draw(*f.camera, boxes, f.mine, f.raster, f.fallback);
}

void RzbRenderer::prepareFreshSamples(Frame& f) {
  for (uint32_t i : f.mine)
    if (!f.sel.boxes[i].fallback) appendJobs(f.jobs, i, f.sel.boxes[i].samples, nullptr);
}

void RzbRenderer::prepareCachedSamples(Frame& f) {
  const int threads = options_.threads;
  const std::vector<SelectedBox>& boxes = f.sel.boxes;
  struct Want {
    uint32_t box;
    int level;
    const std::vector<CachedSample>* set;
  };
  std::vector<Want> wants;
  for (uint32_t i : f.mine) {
    const SelectedBox& b = boxes[i];
    if (b.fallback) continue;
    const int level = cacheLevel(b.ppu);
    wants.push_back({i, level, cache_->lookup(b.key, level, f.tick)});
  }
  std::vector<size_t> small, large;
  for (size_t k = 0; k < wants.size(); ++k) {
    if (wants[k].set) continue;
    const SelectedBox& b = boxes[wants[k].box];
    const double expected = b.area * std::ldexp(1.0, wants[k].level) * f.select.samplesPerPixel;
    (expected < double(kSmallSet) ? small : large).push_back(k);
  }
  std::vector<std::vector<CachedSample>> built(wants.size());
  f.uncached.reserve(wants.size());  // pointers into it must stay valid
  std::vector<uint64_t> drawn(wants.size(), 0);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (size_t s = 0; s < small.size(); ++s) {
    const size_t k = small[s];
    built[k] = buildSampleSet(boxes[wants[k].box], wants[k].level, options_.seed,
                              f.select.samplesPerPixel, params_.splat, 1, &drawn[k]);
  }
  for (size_t k : large)
    built[k] = buildSampleSet(boxes[wants[k].box], wants[k].level, options_.seed,
                              f.select.samplesPerPixel, params_.splat, threads, &drawn[k]);
  for (size_t k = 0; k < wants.size(); ++k) {
    if (wants[k].set) continue;
    f.generatedForCache += drawn[k];
    const std::vector<CachedSample>* stored =
        cache_->store(boxes[wants[k].box].key, wants[k].level, std::move(built[k]), f.tick);
    if (!stored) {
      // Over budget: use it this frame only (the same samples a cached set would give).
      f.uncached.push_back(std::move(built[k]));
      stored = &f.uncached.back();
    }
    wants[k].set = stored;
  }
  for (const Want& w : wants) appendJobs(f.jobs, w.box, w.set->size(), w.set->data());
}

void RzbRenderer::splat(Frame& f) {
  const Camera& camera = *f.camera;
  f.setup = SplatSetup::from(camera, params_.splat);
  keys_.reset(camera.width(), camera.height(), scene_.expandedTriangles() > 0xffffffffull,
              options_.threads);
  f.pass = splatJobs(f.jobs, f.sel.boxes, f.stream, f.setup, params_.dropBackfaces, keys_,
                     options_.threads);
}

void RzbRenderer::resolve(Frame& f, Framebuffer& fb) {
  keys_.resolve(fb, options_.threads);
  if (f.rastered) compositeNearer(fb, f.raster);
}

void RzbRenderer::shadeGauss(Frame& f, Framebuffer& fb) {
  shadeFromIds(scene_, *f.camera, fb);  // pixels no visible sample reaches keep this colour
  if (f.mine.empty()) return;
  std::vector<uint64_t> accum;
  f.gauss = gaussAccumulate(f.jobs, f.sel.boxes, f.stream, f.setup, params_.dropBackfaces,
                            fb.depth, scene_, accum, options_.threads);
  const long n = long(fb.size());
#pragma omp parallel for schedule(static) num_threads(options_.threads)
  for (long i = 0; i < n; ++i) {
    const uint64_t* a = accum.data() + 4 * size_t(i);
    if (!a[3]) continue;
    auto avg = [&](int k) { return uint8_t((a[k] + a[3] / 2) / a[3]); };
    fb.color[size_t(i)] = packRgba8(avg(0), avg(1), avg(2));
  }
}

void RzbRenderer::countFrame(const Frame& f, FrameStats& stats) const {
  const std::vector<SelectedBox>& boxes = f.sel.boxes;
  // Box selection runs alike on every rank.
  stats.setShared("eps", f.select.eps);
  if (params_.autoEps) stats.setShared("eps_evaluations", f.epsEvaluations);
  stats.setShared("nodes_visited", double(f.sel.nodesVisited));
  stats.setShared("capped_boxes", double(f.sel.cappedBoxes));
  // This rank's boxes.
  uint64_t sampleBoxes = 0, fallbackBoxes = 0;
  double projected = 0.0;
  for (uint32_t i : f.mine) {
    const SelectedBox& b = boxes[i];
    (b.fallback ? fallbackBoxes : sampleBoxes) += 1;
    if (!b.fallback) projected += b.area * b.ppu * b.ppu;
  }
  stats.addCount("boxes_selected", double(f.mine.size()));
  stats.addCount("sample_boxes", double(sampleBoxes));
  stats.addCount("samples_drawn", double(f.pass.drawn));
  stats.addCount("samples_splatted", double(f.pass.splatted));
  stats.addCount("samples_backfacing", double(f.pass.backfacing));
  stats.addCount("projected_area_px", projected);
  stats.addCount("fallback_boxes", double(fallbackBoxes));
  stats.addCount("fallback_triangles", double(f.fallback.triangles));
  if (params_.reconstruct == Reconstruct::kGauss)
    stats.addCount("gauss_visible_samples", double(f.gauss.splatted));
  if (cache_) {
    const CacheCounts& cc = cache_->counts();
    stats.addCount("cache_hits", double(cc.hits - f.cacheBefore.hits));
    stats.addCount("cache_misses", double(cc.misses - f.cacheBefore.misses));
    stats.addCount("cache_evictions", double(cc.evictions - f.cacheBefore.evictions));
    stats.addCount("cache_uncached", double(cc.uncached - f.cacheBefore.uncached));
    stats.addCount("cache_bytes", double(cache_->bytes()));
    stats.addCount("cache_samples_generated", double(f.generatedForCache));
  }
}

}  // namespace lzb::rzb
