#include "src/sqrt5/sqrt5_renderer.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "mpi/decomposition.hpp"
#include "src/core/system.hpp"
#include "src/core/timer.hpp"
#include "src/splat/splatter.hpp"

namespace lzb::sqrt5 {

namespace {

// |det| of the linear part to the 2/3: how a transform scales areas (exact for similarities).
double areaScale(const glm::dmat4& m) {
  return std::pow(std::abs(glm::determinant(glm::dmat3(m))), 2.0 / 3.0);
}

}  // namespace

Sqrt5Renderer::Sqrt5Renderer(const Scene& scene, const RenderOptions& options,
                             const Sqrt5Params& params)
    : scene_(scene), options_(options), params_(params) {
  params_.validate();
  options_.threads = std::max(options_.threads, 1);
  meshBounds_.resize(scene.nodes.size());
  halton_.resize(scene.nodes.size());
  for (size_t n = 0; n < scene.nodes.size(); ++n) {
    Bounds& b = meshBounds_[n];
    for (const glm::vec3& v : scene.nodes[n].mesh.positions) b.extend(glm::dvec3(v));
    // The exact surface strays from its tessellation by a fraction of a cell: keep it in the box.
    if (scene.nodes[n].procedural && !b.empty()) {
      const double m = 0.01 * b.diagonal();
      b.lo -= glm::dvec3(m);
      b.hi += glm::dvec3(m);
    }
  }
}

std::string Sqrt5Renderer::decomposition() const {
  return "every rank lists the visible placements and plans each (the initial sqrt(5) grid of a "
         "procedural object, the Halton prefix of a mesh); the runs of grid rows and of Halton "
         "samples are dealt to ranks as contiguous runs of equal estimated cost (roots, samples) "
         "in expanded-ID order; each rank refines and splats its runs; the root composites by "
         "(depth, id)";
}

Sqrt5Renderer::Frame Sqrt5Renderer::prepare(const Camera& camera, const WorkShare& share) {
  Frame f;
  f.camera = &camera;
  f.share = share;
  f.placements = visiblePlacements(scene_, meshBounds_, camera);
  plan(f);
  deal(f);
  attachCache(f);
  return f;
}

void Sqrt5Renderer::plan(Frame& f) {
  const Camera& cam = *f.camera;
  const double scale = cam.pixelsPerUnitAt(1.0);
  f.side.assign(f.placements.size(), 0);
  f.sectors.assign(f.placements.size(), std::nullopt);
  f.halton.assign(f.placements.size(), 0);
  f.polygons.assign(f.placements.size(), 0);
  for (size_t i = 0; i < f.placements.size(); ++i) {
    const SampledPlacement& p = f.placements[i];
    const Node& node = scene_.nodes[p.node];
    if (node.procedural && node.procedural->spec.kind == ProceduralKind::kTerrain)
      f.sectors[i] = Sector::make(node.procedural->spec, p.world, cam);
    if (f.sectors[i]) {
      const double n = std::max(cam.width(), cam.height()) / (2.0 * std::sqrt(params_.amin));
      f.side[i] = std::clamp(int(std::ceil(n)), 1, kMaxInitialSide);
      continue;
    }
    if (node.procedural) {
      // eq. (3), all points assumed at the distance of the bounds' centre
      const double d = std::max({glm::length(p.bounds.center() - cam.position()),
                                 nearestDistance(p.bounds, cam.position()), cam.nearPlane()});
      f.side[i] = initialSide(node.procedural->spec.baseArea() * areaScale(p.world), d, scale,
                              params_.amin);
      continue;
    }
    // n_s = A / (d~^2 A'min), d~ the nearest distance of the placement's box (the surface's
    // area from the triangle prefix sums, built once per unique mesh; samples only on demand)
    if (!halton_[p.node]) halton_[p.node] = std::make_unique<HaltonSurface>(node.mesh);
    const double d = std::max(nearestDistance(p.bounds, cam.position()), cam.nearPlane());
    const double ns = halton_[p.node]->area() * areaScale(p.world) * scale * scale /
                      (params_.amin * d * d);
    // points buy nothing once the prefix costs as much as the triangle list: draw the triangles
    const uint64_t m = node.mesh.size();
    if (ns >= kPolygonFactor * double(m)) {
      f.polygons[i] = m;
      continue;
    }
    f.halton[i] = ns < double(kMaxHaltonSamples) ? uint64_t(std::ceil(ns)) : kMaxHaltonSamples;
  }
  // Each unique mesh's vector extended once to its longest prefix (serially, before the draw),
  // after checking that the growth fits in memory.
  std::vector<uint64_t> want(scene_.nodes.size(), 0);
  for (size_t i = 0; i < f.placements.size(); ++i)
    want[f.placements[i].node] = std::max(want[f.placements[i].node], f.halton[i]);
  uint64_t grow = 0;
  for (size_t n = 0; n < want.size(); ++n)
    if (halton_[n] && want[n] > halton_[n]->size())
      grow += (want[n] - halton_[n]->size()) * sizeof(SurfaceSample);
  requireMemory(grow, "sqrt5", "Halton sample vectors");
  for (size_t n = 0; n < want.size(); ++n)
    if (want[n] > 0) halton_[n]->reserve(want[n]);
}

void Sqrt5Renderer::deal(Frame& f) const {
  f.jobs = {};
  for (uint32_t i = 0; i < f.placements.size(); ++i) {
    if (f.side[i] > 0) {
      // runs of rows of the initial grid, each row costing its roots
      const uint64_t rows = uint64_t(f.side[i]) + 1;
      f.jobs.addRuns(i, rows, std::max<uint64_t>(1, kJobRoots / rows), rows);
    } else if (f.polygons[i] > 0) {
      f.jobs.addPolygons(i, f.polygons[i]);
    } else {
      f.jobs.addRuns(i, f.halton[i]);
    }
  }
  f.mine = dealByCost(f.jobs.costs, f.share);
}

// The cache entries of this rank's lines of cached placements (not sectors), made serially.
void Sqrt5Renderer::attachCache(Frame& f) {
  f.cached.assign(f.mine.size(), {});
  if (params_.cacheMb == 0) return;
  for (size_t k = 0; k < f.mine.size(); ++k) {
    const PlacementJob& job = f.jobs[f.mine[k]];
    const SampledPlacement& p = f.placements[job.placed];
    if (f.side[job.placed] == 0 || f.sectors[job.placed]) continue;
    for (uint64_t line = job.begin; line < job.end; ++line)
      f.cached[k].push_back(&cache_.line({p.node, p.idBase, f.side[job.placed], line}));
  }
}

template <class Splatter>
void Sqrt5Renderer::drawJob(const Frame& f, size_t k, Splatter& out, DrawCounts& counts,
                            Scratch& scratch) const {
  const PlacementJob& job = f.jobs[f.mine[k]];
  auto& stack = scratch.stack;
  auto& kids = scratch.kids;
  const SampledPlacement& p = f.placements[job.placed];
  const Node& node = scene_.nodes[p.node];
  if (f.polygons[job.placed] > 0) return;  // drawn by drawPolygons
  const auto splat = [&](const glm::dvec3& c, uint64_t id, int) {
    out.add(float(c.x), float(c.y), float(c.z), id);
  };
  if (node.procedural) {
    const Sector* sector = f.sectors[job.placed] ? &*f.sectors[job.placed] : nullptr;
    const ProceduralView view = ProceduralView::make(*node.procedural, sector, p.world, p.idBase,
                                                     *f.camera, params_.amin, params_.levels);
    const Sqrt5Lattice lattice(f.side[job.placed]);
    const int n = lattice.initialSide();
    for (uint64_t line = job.begin; line < job.end; ++line) {
      if (!f.cached[k].empty()) {
        refineCachedLine(view, lattice, int(line), *f.cached[k][line - job.begin],
                         scratch.cachedStack, kids, counts.trees, counts.cache, splat);
        continue;
      }
      if (!sector) {
        for (int i = 0; i <= n; ++i)
          refineTree(view, lattice, lattice.root(i, int(line)), stack, kids, counts.trees, splat);
        continue;
      }
      // a sector's column, front to back
      HorizonLine horizon(view, lattice);
      for (int j = 0; j <= n; ++j) {
        const glm::dvec2 root = lattice.root(int(line), j);
        if (params_.horizon && horizon.hidden(root, counts.horizon)) continue;
        refineTree(view, lattice, root, stack, kids, counts.trees, splat);
      }
    }
    return;
  }
  const HaltonSurface& h = *halton_[p.node];
  const glm::dmat4 toCamera = f.camera->view() * p.world;
  for (uint64_t k = job.begin; k < job.end; ++k) {
    const SurfaceSample& s = h[k];
    const glm::dvec3 v0(node.mesh.vertex(s.triangle, 0)), v1(node.mesh.vertex(s.triangle, 1)),
        v2(node.mesh.vertex(s.triangle, 2));
    const glm::dvec4 c = toCamera * glm::dvec4(v0 + double(s.a) * (v1 - v0) +
                                                   double(s.c) * (v2 - v0), 1.0);
    out.add(float(c.x), float(c.y), float(-c.z), p.idBase + s.triangle);
  }
  counts.haltonDrawn += job.end - job.begin;
}

template <bool kWide, bool kPixel>
Sqrt5Renderer::DrawCounts Sqrt5Renderer::drawWith(const Frame& f) {
  const SplatSetup setup = SplatSetup::from(*f.camera, params_.splat());
  DrawCounts total;
#pragma omp parallel num_threads(options_.threads)
  {
    PointSplatter<kWide, kPixel> out(setup, keys_);
    DrawCounts mine;
    Scratch scratch;
#pragma omp for schedule(dynamic, 1) nowait
    for (size_t k = 0; k < f.mine.size(); ++k) drawJob(f, k, out, mine, scratch);
    out.flush();
    mine.splatted = out.splatted();
#pragma omp critical
    total.merge(mine);
  }
  return total;
}

void Sqrt5Renderer::DrawCounts::merge(const DrawCounts& o) {
  trees.merge(o.trees);
  horizon.culledAtTop += o.horizon.culledAtTop;
  horizon.culledByReal += o.horizon.culledByReal;
  cache.hits += o.cache.hits;
  cache.misses += o.cache.misses;
  haltonDrawn += o.haltonDrawn;
  splatted += o.splatted;
}

std::pair<uint64_t, uint64_t> Sqrt5Renderer::drawPolygons(const Frame& f, Framebuffer& fb) {
  DrawLists lists;
  for (uint32_t k : f.mine) {
    const PlacementJob& job = f.jobs[k];
    if (f.polygons[job.placed] == 0) continue;
    const SampledPlacement& p = f.placements[job.placed];
    wholeNodes_.add(lists, p.node, p.world, p.idBase, scene_.nodes[p.node].mesh.size());
  }
  if (!lists.lists.empty()) raster_.draw(scene_, *f.camera, lists, {}, options_.threads, fb);
  return {lists.lists.size(), lists.triangles};
}

Sqrt5Renderer::DrawCounts Sqrt5Renderer::draw(const Frame& f) {
  const Camera& cam = *f.camera;
  const bool wide = scene_.expandedTriangles() > 0xffffffffull;
  keys_.reset(cam.width(), cam.height(), wide, options_.threads);
  return withSplatter(keys_, params_.splat(),
                      [&]<bool kWide, bool kPixel>() { return drawWith<kWide, kPixel>(f); });
}

void Sqrt5Renderer::render(const Camera& camera, int frame, const WorkShare& share,
                           Framebuffer& fb, FrameStats& stats) {
  requireFrameSize(fb, camera, "sqrt5");
  Stopwatch clock;
  const Frame f = prepare(camera, share);
  stats.addStage("plan", clock.lap());
  const DrawCounts c = draw(f);
  cache_.endFrame(params_.cacheMb << 20);
  stats.addStage("sample", clock.lap());
  const auto [polygonPlacements, triangles] = drawPolygons(f, fb);
  stats.addCount("polygon_placements_drawn", double(polygonPlacements));
  stats.addCount("triangles_drawn", double(triangles));
  stats.addStage("polygons", clock.lap());
  Framebuffer points(fb.width, fb.height);
  keys_.resolve(points, options_.threads);
  compositeNearer(fb, points);
  stats.addStage("resolve", clock.lap());
  report(f, c, stats);
  (void)frame;  // no random numbers: the lattice and the Halton sequences are deterministic
}

void Sqrt5Renderer::report(const Frame& f, const DrawCounts& c, FrameStats& stats) const {
  stats.addCount("samples_initial",
                 double(c.trees.roots + c.horizon.culledAtTop + c.horizon.culledByReal));
  stats.addCount("samples_generated", double(c.trees.generated));
  stats.addCount("samples_refined", double(c.trees.refined));
  stats.addCount("samples_drawn", double(c.trees.drawn));
  stats.addCount("samples_at_level_bound", double(c.trees.atLevelBound));
  stats.addCount("samples_culled_horizon",
                 double(c.horizon.culledAtTop + c.horizon.culledByReal));
  stats.addCount("samples_culled_horizon_at_top", double(c.horizon.culledAtTop));
  stats.addCount("halton_samples_drawn", double(c.haltonDrawn));
  stats.addCount("cache_hits", double(c.cache.hits));
  stats.addCount("cache_misses", double(c.cache.misses));
  stats.addCount("cache_bytes", double(cache_.bytes()));
  stats.addCount("cache_lines", double(cache_.lineCount()));
  stats.addCount("samples_splatted", double(c.splatted));
  uint64_t procedural = 0, halton = 0, sectors = 0, polygons = 0;
  int side = 0;
  for (size_t i = 0; i < f.placements.size(); ++i) {
    procedural += f.side[i] > 0;
    sectors += f.sectors[i].has_value();
    halton += f.halton[i];
    polygons += f.polygons[i] > 0;
    side = std::max(side, f.side[i]);
  }
  stats.setShared("placements_visible", double(f.placements.size()));
  stats.setShared("placements_procedural", double(procedural));
  stats.setShared("placements_polygons", double(polygons));
  stats.setShared("terrain_sectors", double(sectors));
  stats.setShared("halton_samples_planned", double(halton));
  stats.setShared("initial_side_max", double(side));
  stats.setShared("splat", double(params_.splat()));
  stats.setShared("halton_memory_bytes", double(haltonBytes()));
}

uint64_t Sqrt5Renderer::haltonBytes() const {
  uint64_t bytes = 0;
  for (const auto& h : halton_)
    if (h) bytes += h->bytes();
  return bytes;
}

FrameStats Sqrt5Renderer::setupStats() const {
  FrameStats s;
  s.setShared("halton_memory_bytes", double(haltonBytes()));
  return s;
}

}  // namespace lzb::sqrt5
