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
    : scene_(scene), options_(options), params_(params), fallback_(scene) {
  params_.validate();
  TreeParams tp;
  tp.areaRatio = params_.areaRatio;
  tp.progress = !options.quiet;
  trees_ = std::make_unique<SampleScene>(scene, tp);
  if (params_.cacheMb > 0.0)
    cache_ = std::make_unique<SampleCache>(uint64_t(params_.cacheMb * 1024.0 * 1024.0));
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
  const int threads = std::max(options_.threads, 1);
  const uint64_t frameTick = ++frameCounter_;
  const CacheCounts cacheBefore = cache_ ? cache_->counts() : CacheCounts{};
  const double pixels = double(camera.width()) * double(camera.height());
  if (cache_)
    require(cache_->budget() >= RzbParams::minCacheBytes(camera.width(), camera.height(),
                                                         params_.splat),
            "--cache-mb",
            "is below one box: a box covering the " + std::to_string(camera.width()) + "x" +
                std::to_string(camera.height()) + " image needs " +
                std::to_string(RzbParams::minCacheBytes(camera.width(), camera.height(),
                                                        params_.splat) /
                               1024) +
                " KiB");
  Stopwatch clock;

  // 1. Box selection (every rank, the same result).
  SelectParams sp;
  sp.eps = params_.eps;
  sp.samplesPerPixel = params_.samplesPerPixel(pixels);
  sp.fallbackPx = params_.fallbackThreshold(pixels);
  sp.maxBoxSamples = kMaxBoxLayers * pixels * sp.samplesPerPixel;
  const SampleStream stream(options_.seed, uint64_t(frame));
  if (params_.autoEps) {
    const EpsSearch found = searchEps(*trees_, camera, sp, stream, lastEps_);
    sp.eps = found.eps;
    stats.addCount("eps_evaluations", found.evaluations);
  }
  lastEps_ = sp.eps;
  const Selection sel = selectBoxes(*trees_, camera, sp, stream);
  stats.addStage("select", clock.lap());

  // 2. This rank's boxes (gauss: all on rank 0).
  std::vector<uint32_t> mine;
  if (params_.reconstruct == Reconstruct::kGauss) {
    if (share.rank == 0) mine = dealBoxes(sel.boxes, WorkShare{});
  } else {
    mine = dealBoxes(sel.boxes, share);
  }

  // 3. Fallback boxes through the exact z-buffer.
  FallbackCounts fc;
  Framebuffer raster;
  bool rastered = false;
  if (std::any_of(mine.begin(), mine.end(), [&](uint32_t i) { return sel.boxes[i].fallback; })) {
    raster.resize(camera.width(), camera.height());
    rastered = fallback_.draw(camera, sel.boxes, mine, raster, fc);
  }
  stats.addStage("fallback", clock.lap());

  // 4. Sample boxes: fresh from the frame's stream, or the cache's sets.
  std::vector<SplatJob> jobs;
  std::vector<std::vector<CachedSample>> uncached;  // sets over the budget, this frame only
  uint64_t generatedForCache = 0;
  const SampleStream* splatStream = &stream;
  if (cache_ && params_.reconstruct != Reconstruct::kGauss) {
    struct Want {
      uint32_t box;
      int level;
      const std::vector<CachedSample>* set;
    };
    std::vector<Want> wants;
    for (uint32_t i : mine) {
      const SelectedBox& b = sel.boxes[i];
      if (b.fallback) continue;
      const int level = cacheLevel(b.ppu);
      wants.push_back({i, level, cache_->lookup(b.key, level, frameTick)});
    }
    std::vector<size_t> small, large;
    for (size_t k = 0; k < wants.size(); ++k) {
      if (wants[k].set) continue;
      const SelectedBox& b = sel.boxes[wants[k].box];
      const double expected = b.area * std::ldexp(1.0, wants[k].level) * sp.samplesPerPixel;
      (expected < double(kSmallSet) ? small : large).push_back(k);
    }
    std::vector<std::vector<CachedSample>> built(wants.size());
    uncached.reserve(wants.size());  // pointers into it must stay valid
    std::vector<uint64_t> drawn(wants.size(), 0);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (size_t s = 0; s < small.size(); ++s) {
      const size_t k = small[s];
      built[k] = buildSampleSet(sel.boxes[wants[k].box], wants[k].level, options_.seed,
                                sp.samplesPerPixel, params_.splat, 1, &drawn[k]);
    }
    for (size_t k : large)
      built[k] = buildSampleSet(sel.boxes[wants[k].box], wants[k].level, options_.seed,
                                sp.samplesPerPixel, params_.splat, threads, &drawn[k]);
    for (size_t k = 0; k < wants.size(); ++k) {
      if (wants[k].set) continue;
      generatedForCache += drawn[k];
      const std::vector<CachedSample>* stored =
          cache_->store(sel.boxes[wants[k].box].key, wants[k].level, std::move(built[k]), frameTick);
      if (!stored) {
        // Over budget: use it this frame only (the same samples a cached set would give).
        uncached.push_back(std::move(built[k]));
        stored = &uncached.back();
      }
      wants[k].set = stored;
    }
    for (const Want& w : wants)
      appendJobs(jobs, w.box, w.set->size(), w.set->data());
    stats.addStage("cache_build", clock.lap());
  } else {
    for (uint32_t i : mine)
      if (!sel.boxes[i].fallback) appendJobs(jobs, i, sel.boxes[i].samples, nullptr);
  }

  // 5. Splat, resolve, composite with the fallback.
  const SplatSetup setup = SplatSetup::from(camera, params_.splat);
  keys_.reset(camera.width(), camera.height(), scene_.expandedTriangles() > 0xffffffffull, threads);
  const PassCounts pc = splatJobs(jobs, sel.boxes, *splatStream, setup, params_.dropBackfaces, keys_, threads);
  stats.addStage("splat", clock.lap());
  keys_.resolve(fb, threads);
  if (rastered) compositeNearer(fb, raster);
  stats.addStage("resolve", clock.lap());

  // 6. Colour: the one shading rule from the IDs; gauss: the average of visible samples.
  shadeFromIds(scene_, camera, fb);
  if (params_.reconstruct == Reconstruct::kGauss && !mine.empty()) {
    std::vector<uint64_t> accum;
    const PassCounts gc =
        gaussAccumulate(jobs, sel.boxes, *splatStream, setup, params_.dropBackfaces, fb.depth, scene_, accum, threads);
    const long n = long(fb.size());
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long i = 0; i < n; ++i) {
      const uint64_t* a = accum.data() + 4 * size_t(i);
      if (!a[3]) continue;
      auto avg = [&](int k) { return uint8_t((a[k] + a[3] / 2) / a[3]); };
      fb.color[size_t(i)] = packRgba8(avg(0), avg(1), avg(2));
    }
    stats.addCount("gauss_visible_samples", double(gc.splatted));
  }
  stats.addStage("shade", clock.lap());

  // Report.
  uint64_t sampleBoxes = 0, fallbackBoxes = 0;
  for (uint32_t i : mine) (sel.boxes[i].fallback ? fallbackBoxes : sampleBoxes) += 1;
  stats.addCount("eps", share.rank == 0 ? sp.eps : 0.0);
  stats.addCount("nodes_visited", share.rank == 0 ? double(sel.nodesVisited) : 0.0);
  stats.addCount("boxes_selected", double(mine.size()));
  stats.addCount("sample_boxes", double(sampleBoxes));
  stats.addCount("samples_drawn", double(pc.drawn));
  stats.addCount("samples_splatted", double(pc.splatted));
  stats.addCount("samples_backfacing", double(pc.backfacing));
  double projected = 0.0;
  for (uint32_t i : mine)
    if (!sel.boxes[i].fallback) projected += sel.boxes[i].area * sel.boxes[i].ppu * sel.boxes[i].ppu;
  stats.addCount("projected_area_px", projected);
  if (share.size == 1) {
    stats.addCount("samples_per_pixel_of_projected_area", projected > 0 ? double(pc.drawn) / projected : 0.0);
    const double covered = double(fb.coveredCount());
    stats.addCount("samples_per_covered_pixel", covered > 0 ? double(pc.splatted) / covered : 0.0);
  }
  stats.addCount("capped_boxes", share.rank == 0 ? double(sel.cappedBoxes) : 0.0);
  stats.addCount("fallback_boxes", double(fallbackBoxes));
  stats.addCount("fallback_triangles", double(fc.triangles));
  if (cache_) {
    const CacheCounts& cc = cache_->counts();
    stats.addCount("cache_hits", double(cc.hits - cacheBefore.hits));
    stats.addCount("cache_misses", double(cc.misses - cacheBefore.misses));
    stats.addCount("cache_evictions", double(cc.evictions - cacheBefore.evictions));
    stats.addCount("cache_uncached", double(cc.uncached - cacheBefore.uncached));
    stats.addCount("cache_bytes", double(cache_->bytes()));
    stats.addCount("cache_samples_generated", double(generatedForCache));
  }
}

}  // namespace lzb::rzb
