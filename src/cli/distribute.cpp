#include "src/cli/distribute.hpp"

#include <algorithm>

#include "mpi/decomposition.hpp"
#include "src/core/error.hpp"
#include "src/core/shading.hpp"
#include "src/core/timer.hpp"

namespace lzb {

Distribution parseDistribution(const std::string& text, const std::string& field) {
  if (text == "replicate") return Distribution::kReplicate;
  if (text == "data") return Distribution::kData;
  throw InputError(field + ": unknown distribution '" + text + "' (replicate | data)");
}

uint32_t defaultRegions(uint64_t uniqueTriangles) {
  return uint32_t(std::clamp<uint64_t>(uniqueTriangles >> 16, 16, 4096));
}

bool rendersParts(const std::string& method) {
  return method == "zbuffer" || method == "raycast";
}

std::vector<bool> keepOfRank(std::span<const glm::dvec3> centres,
                             std::span<const uint64_t> triangles, HeldShare& held,
                             const WorkShare& share) {
  const std::vector<uint32_t> regionOf = splitIntoRegions(centres, triangles, held.regions);
  std::vector<uint64_t> regionTriangles(held.regions, 0);
  for (size_t u = 0; u < regionOf.size(); ++u)
    regionTriangles[regionOf[u]] += triangles.empty() ? 1 : triangles[u];
  held.mine = regionsOfRank(regionTriangles, share);
  std::vector<bool> mineRegion(held.regions, false);
  for (uint32_t r : held.mine) mineRegion[r] = true;
  std::vector<bool> keep(regionOf.size());
  for (size_t u = 0; u < regionOf.size(); ++u) keep[u] = mineRegion[regionOf[u]];
  return keep;
}

HeldShare holdShare(const Scene& whole, uint32_t regions, const WorkShare& share) {
  HeldShare held;
  held.regions = regions ? regions : defaultRegions(whole.uniqueTriangles());
  const SceneUnits units = sceneUnits(whole, held.regions);
  held.units = units.size();
  std::vector<bool> keep;
  {
    std::vector<glm::dvec3> centres(units.size());
    for (size_t u = 0; u < units.size(); ++u) centres[u] = units.centre(whole, u);
    // Only the main mesh's triangles: one each, cut by count (none of the halving's selections).
    std::vector<uint64_t> triangles;
    if (!units.opened.empty())
      for (size_t u = 0; u < units.size(); ++u) triangles.push_back(units.triangles(u));
    keep = keepOfRank(centres, triangles, held, share);
  }
  held.part = std::make_unique<ScenePart>(cutScene(whole, units, keep));
  return held;
}

namespace {

class PartRenderer : public Renderer {
 public:
  PartRenderer(const HeldShare& held, std::unique_ptr<Renderer> inner, std::string method)
      : held_(held), inner_(std::move(inner)), method_(std::move(method)) {}

  std::string name() const override { return inner_ ? inner_->name() : method_; }
  std::string decomposition() const override {
    return "data-parallel (--distribute data): each rank holds the scene's regions dealt to it "
           "and renders the whole frame of them; frames composited by depth with their colour";
  }

  void render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
              FrameStats& stats) override {
    (void)share;          // every rank renders its whole part: the regions are the share
    if (!inner_) return;  // nothing held: an empty frame
    inner_->render(camera, frame, WorkShare{0, 1}, fb, stats);
    Stopwatch clock;
    const Scene& scene = held_.part->scene;
    // The part's IDs name its own triangles: shade first, then renumber.
    if (inner_->colourFromIds()) shadeFromIds(scene, camera, fb);
    const IdMap& ids = held_.part->ids;
    const long n = long(fb.id.size());
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) fb.id[size_t(i)] = ids.global(fb.id[size_t(i)]);
    stats.addStage("shade", clock.seconds());
  }

  bool colourFromIds() const override { return false; }

  FrameStats setupStats() const override {
    FrameStats stats = inner_ ? inner_->setupStats() : FrameStats{};
    stats.addCount("held_regions", double(held_.mine.size()));
    stats.addCount("held_units", double(held_.part->units));
    stats.addCount("held_triangles", double(held_.part->scene.expandedTriangles()));
    stats.addCount("held_unique_triangles", double(held_.part->scene.uniqueTriangles()));
    stats.setShared("regions", double(held_.regions));
    stats.setShared("units", double(held_.units));
    return stats;
  }

 private:
  const HeldShare& held_;
  std::unique_ptr<Renderer> inner_;
  std::string method_;
};

}  // namespace

std::unique_ptr<Renderer> makePartRenderer(const HeldShare& held, std::unique_ptr<Renderer> inner,
                                           const std::string& method) {
  return std::make_unique<PartRenderer>(held, std::move(inner), method);
}

}  // namespace lzb
