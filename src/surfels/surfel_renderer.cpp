#include "src/surfels/surfel_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "mpi/decomposition.hpp"
#include "src/core/error.hpp"
#include "src/core/timer.hpp"
#include "src/scene/mesh_builder.hpp"

namespace lzb::surfels {

Mesh uvSphere(int slices, int stacks) {
  Mesh mesh;
  LoadStats unused;
  MeshBuilder(mesh, unused).sphere(slices, stacks, packRgba8(200, 200, 200));
  return mesh;
}

SurfelRenderer::SurfelRenderer(const Scene& scene, const RenderOptions& options,
                               const SurfelParams& params)
    : scene_(scene),
      options_(options),
      params_(params),
      normals_(CollectorLayout::of(params.quality).normalLevels) {
  params_.validate();
  options_.threads = std::max(options_.threads, 1);
  domains_.resize(scene.nodes.size());
  meshBounds_.resize(scene.nodes.size());
  levels_.resize(scene.nodes.size());
  for (size_t n = 0; n < scene.nodes.size(); ++n) {
    if (scene.nodes[n].mesh.empty()) continue;
    domains_[n] = Domain::around(scene.nodes[n].mesh);
    for (const glm::vec3& v : scene.nodes[n].mesh.positions) meshBounds_[n].extend(glm::dvec3(v));
    levels_[n].resize(params_.grids.size());
  }
  if (params_.buildAtSetup) {
    Stopwatch clock;
    for (size_t n = 0; n < scene.nodes.size(); ++n)
      for (size_t l = 0; l < levels_[n].size(); ++l) level(uint32_t(n), int(l));
    setupBuildSeconds_ = clock.seconds();
  }
  if (params_.budgetMs > 0.0 && params_.budgetRate == 0.0) measureRate();
}

std::string SurfelRenderer::decomposition() const {
  return "every rank lists the visible objects, switches each to a surfel level or polygons and "
         "builds the surfel levels the frame needs; the objects are dealt to ranks as contiguous "
         "runs of equal estimated cost (surfels drawn, polygons at " +
         std::to_string(int(kTriangleCost)) +
         " surfels per triangle) in expanded-ID order; each rank splats its surfels and z-buffers "
         "its polygons; the root composites by (depth, id)";
}

const SurfelLevel& SurfelRenderer::level(uint32_t node, int index) {
  std::unique_ptr<SurfelLevel>& slot = levels_[node][size_t(index)];
  if (!slot) {
    SurfelizeParams p;
    p.method = params_.surfelize;
    p.quality = params_.quality;
    p.grid = params_.grids[size_t(index)];
    p.split = params_.split;
    p.threads = options_.threads;
    slot = std::make_unique<SurfelLevel>(surfelize(scene_.nodes[node].mesh, normals_, p));
  }
  return *slot;
}

void SurfelRenderer::cull(Frame& f) const {
  f.placements = visiblePlacements(scene_, domains_, meshBounds_, *f.camera, params_);
}

uint64_t SurfelRenderer::buildLevels(const Frame& f) {
  // Every rank builds every level the frame uses, in placement order: all then know each
  // placement's surfel count, which the budget and the deal need alike.
  uint64_t built = 0;
  for (const SurfelPlacement& p : f.placements)
    if (p.level != kPolygons && !levels_[p.node][size_t(p.level)]) {
      level(p.node, p.level);
      ++built;
    }
  return built;
}

void SurfelRenderer::applyBudget(Frame& f) const {
  f.work.resize(f.placements.size());
  f.selected = 0;
  for (size_t i = 0; i < f.placements.size(); ++i) {
    const SurfelPlacement& p = f.placements[i];
    f.work[i] = p.level == kPolygons ? scene_.nodes[p.node].mesh.size()
                                     : levels_[p.node][size_t(p.level)]->collector.size();
    if (p.level != kPolygons) f.selected += f.work[i];
  }
  if (params_.budgetMs <= 0.0) return;
  // The budget as a count (rate x time), then one fraction of every collector: its shuffled
  // prefix. The count, not the clock, decides, so every rank and thread draws the same surfels.
  f.budget = uint64_t(std::llround(params_.budgetMs * budgetRate()));
  const double fraction =
      f.selected > 0 ? std::min(1.0, double(f.budget) / double(f.selected)) : 1.0;
  for (size_t i = 0; i < f.placements.size(); ++i)
    if (f.placements[i].level != kPolygons)
      f.work[i] =
          std::min<uint64_t>(f.work[i], uint64_t(std::llround(fraction * double(f.work[i]))));
}

void SurfelRenderer::deal(Frame& f) const {
  f.items = {};
  for (uint32_t i = 0; i < f.placements.size(); ++i) {
    if (f.placements[i].level == kPolygons)
      f.items.addPolygons(i, f.work[i]);
    else
      f.items.addRuns(i, f.work[i]);
  }
  f.mine = dealByCost(f.items.costs, f.share);
}

void SurfelRenderer::drawPolygons(const Frame& f, Framebuffer& fb, FrameStats& stats) {
  DrawLists lists;
  uint64_t placements = 0;
  for (uint32_t k : f.mine) {
    const SurfelPlacement& p = f.placements[f.items[k].placed];
    if (p.level != kPolygons) continue;
    wholeNodes_.add(lists, p.node, p.world, p.idBase, scene_.nodes[p.node].mesh.size());
    ++placements;
  }
  if (!lists.lists.empty()) raster_.draw(scene_, *f.camera, lists, {}, options_.threads, fb);
  stats.addCount("polygon_placements_drawn", double(placements));
  stats.addCount("polygon_triangles", double(lists.triangles));
}

void SurfelRenderer::drawSurfelPass(const Frame& f, FrameStats& stats) {
  const Camera& camera = *f.camera;
  std::vector<PlacedLevel> placed;
  std::vector<SurfelJob> jobs;
  uint32_t last = ~0u;  // items of one placement are consecutive
  for (uint32_t k : f.mine) {
    const PlacementJob& item = f.items[k];
    const SurfelPlacement& p = f.placements[item.placed];
    if (p.level == kPolygons) continue;
    if (item.placed != last) {
      placed.push_back(PlacedLevel::make(*levels_[p.node][size_t(p.level)], p.world, p.idBase,
                                         camera, p.sprite, f.work[item.placed],
                                         params_.dropBackfaces));
      last = item.placed;
    }
    jobs.push_back({uint32_t(placed.size() - 1), item.begin, item.end});
  }
  keys_.reset(camera.width(), camera.height(), scene_.expandedTriangles() > 0xffffffffull,
              options_.threads);
  const DrawCounts c = drawSurfels(placed, jobs, camera, params_.disc, params_.dropBackfaces,
                                   normals_, keys_, options_.threads);
  stats.addCount("surfel_placements_drawn", double(placed.size()));
  stats.addCount("surfels_drawn", double(c.drawn));
  stats.addCount("surfels_backfacing", double(c.backfacing));
  stats.addCount("surfels_splatted", double(c.splatted));
}

void SurfelRenderer::combine(Framebuffer& fb) {
  points_.resizeUnlessSized(fb.width, fb.height);  // resolve writes every depth and ID
  keys_.resolve(points_, options_.threads);
  compositeNearer(fb, points_);
}

void SurfelRenderer::render(const Camera& camera, int frame, const WorkShare& share,
                            Framebuffer& fb, FrameStats& stats) {
  requireFrameSize(fb, camera, "surfels");
  // A measured rate is this rank's own: ranks that disagree on the budget would deal different
  // surfel runs, drawing some twice and leaving others out of the prefix.
  require(
      !(params_.budgetMs > 0.0 && params_.budgetRate == 0.0 && share.size > 1), "--budget-rate",
      "give a rate (surfels per ms) to budget on several ranks: 'auto' measures each rank's own");
  Frame f;
  f.camera = &camera;
  f.share = share;
  Stopwatch clock;
  cull(f);
  stats.addStage("cull", clock.lap());
  stats.setShared("levels_built", double(buildLevels(f)));
  stats.addStage("surfelize", clock.lap());
  applyBudget(f);
  deal(f);
  stats.addStage("deal", clock.lap());
  drawPolygons(f, fb, stats);
  stats.addStage("polygons", clock.lap());
  drawSurfelPass(f, stats);
  stats.addStage("surfels", clock.lap());
  combine(fb);
  stats.addStage("combine", clock.lap());
  report(f, stats);
  (void)frame;  // surfels draw no random numbers: every frame's choices follow from its camera
}

namespace {

// {"value": count, ...} of a histogram.
nlohmann::json histogram(const std::map<int, uint64_t>& counts) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [value, n] : counts) out[std::to_string(value)] = n;
  return out;
}

}  // namespace

void SurfelRenderer::report(const Frame& f, FrameStats& stats) const {
  std::map<int, uint64_t> byGrid, bySprite;
  std::set<uint32_t> surfelObjects, polygonObjects;
  std::map<std::string, std::set<int>> objectGrids;
  uint64_t polygons = 0, drawn = 0;
  for (size_t i = 0; i < f.placements.size(); ++i) {
    const SurfelPlacement& p = f.placements[i];
    const std::string& name = scene_.nodes[p.node].name;
    if (p.level == kPolygons) {
      ++polygons;
      polygonObjects.insert(p.node);
      objectGrids[name].insert(0);
    } else {
      ++byGrid[params_.grids[size_t(p.level)]];
      ++bySprite[p.sprite];
      surfelObjects.insert(p.node);
      objectGrids[name].insert(params_.grids[size_t(p.level)]);
      drawn += f.work[i];
    }
  }
  stats.setShared("placements_visible", double(f.placements.size()));
  stats.setShared("placements_polygons", double(polygons));
  stats.setShared("placements_surfels", double(f.placements.size() - polygons));
  stats.setShared("objects_polygons", double(polygonObjects.size()));
  stats.setShared("objects_surfels", double(surfelObjects.size()));
  stats.shared["grid_placements"] = histogram(byGrid);
  stats.shared["sprite_placements"] = histogram(bySprite);  // the paper's per-object sprite size
  // Per object, the grids its placements used (0: polygons); listed for scenes of few objects.
  constexpr size_t kListedObjects = 32;
  if (objectGrids.size() <= kListedObjects) {
    nlohmann::json per = nlohmann::json::object();
    for (const auto& [name, set] : objectGrids)
      per[name] = std::vector<int>(set.begin(), set.end());
    stats.shared["object_grids"] = per;
  }
  stats.setShared("surfels_selected", double(f.selected));
  stats.setShared("surfels_to_draw", double(drawn));
  if (params_.budgetMs > 0.0) {
    stats.setShared("budget_surfels", double(f.budget));
    stats.setShared("budget_rate_per_ms", budgetRate());
    stats.setShared("budget_fraction", f.selected > 0 ? double(drawn) / double(f.selected) : 1.0);
  }
  reportMemory(stats);
}

void SurfelRenderer::reportMemory(FrameStats& stats) const {
  uint64_t surfels = 0, entries = 0, index = 0, ids = 0, levels = 0;
  for (const auto& node : levels_)
    for (const auto& l : node)
      if (l) {
        ++levels;
        surfels += l->collector.size();
        entries += l->collector.entryBytes();
        index += l->collector.indexBytes();
        ids += l->collector.triangleTableBytes();
      }
  const double n = double(std::max<uint64_t>(surfels, 1));
  stats.setShared("levels_cached", double(levels));
  stats.setShared("surfels_cached", double(surfels));
  stats.setShared("surfel_memory_bytes", double(entries + index + ids));
  stats.setShared("collector_bytes_per_surfel", double(entries) / n);
  stats.setShared("index_bytes_per_surfel", double(index) / n);
  stats.setShared("id_bytes_per_surfel", double(ids) / n);
  stats.setShared("bytes_per_surfel", double(entries + index + ids) / n);
}

FrameStats SurfelRenderer::setupStats() const {
  FrameStats s;
  s.addStage("surfelize", setupBuildSeconds_);
  if (rateSeconds_ > 0.0) {
    s.addStage("budget_rate", rateSeconds_);
    s.setShared("budget_rate_measured_per_ms", measuredRate_);
  }
  reportMemory(s);
  return s;
}

// The splat rate on this machine, threads and sprite size: a 256^3 unit sphere filling half of a
// 512 x 512 frame, drawn three times. It makes the budget's count depend on this run's timing;
// --budget-rate gives a rate and with it the same image on any machine, rank and thread count.
void SurfelRenderer::measureRate() {
  Stopwatch clock;
  const Mesh sphere = uvSphere(48, 24);
  SurfelizeParams sp;
  sp.quality = params_.quality;
  sp.grid = std::min<int>(256, int(CollectorLayout::of(params_.quality).lattice()));
  sp.threads = options_.threads;
  const SurfelLevel level = surfelize(sphere, normals_, sp);
  CameraSpec spec;
  spec.position = {0.0, 0.0, 4.0};
  spec.nearPlane = 0.1;
  spec.farPlane = 100.0;
  const Camera camera(spec, 512, 512);
  const PlacedLevel placed = PlacedLevel::make(level, glm::dmat4(1.0), 0, camera, params_.sprite,
                                               level.collector.size(), params_.dropBackfaces);
  const uint32_t one = 0;
  const std::vector<SurfelJob> jobs = makeJobs({&placed, 1}, {&one, 1}, kJobPoints);
  KeyBuffer keys;
  double seconds = 0.0;
  constexpr int kRounds = 3;
  for (int r = 0; r < kRounds; ++r) {
    keys.reset(512, 512, false, options_.threads);
    Stopwatch draw;
    drawSurfels({&placed, 1}, jobs, camera, params_.disc, params_.dropBackfaces, normals_, keys,
                options_.threads);
    seconds += draw.seconds();
  }
  measuredRate_ =
      double(kRounds) * double(level.collector.size()) / (1000.0 * std::max(seconds, 1e-9));
  rateSeconds_ = clock.seconds();
}

}  // namespace lzb::surfels
