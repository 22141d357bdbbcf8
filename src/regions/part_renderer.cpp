#include "src/regions/part_renderer.hpp"

#include <algorithm>
#include <array>
#include <limits>

#include "mpi/decomposition.hpp"
#include "mpi/frame_tiles.hpp"
#include "src/core/frame_probe.hpp"
#include "src/core/shading.hpp"
#include "src/core/timer.hpp"

namespace lzb::regions {

namespace {

class PartRenderer : public Renderer {
 public:
  PartRenderer(const HeldShare& held, std::vector<std::unique_ptr<Renderer>> inner,
               std::string method)
      : held_(held), inner_(std::move(inner)), method_(std::move(method)) {
    for (const ScenePart& part : held_.parts) boxes_.push_back(heldBox(part.scene));
  }

  std::string name() const override {
    for (const auto& r : inner_)
      if (r) return r->name();
    return method_;
  }
  std::string decomposition() const override {
    return std::string(
               "data-parallel (--distribute data): each rank holds the scene's regions "
               "dealt to it and renders the whole frame of them") +
           (held_.layout == Parts::kOne ? "" : ", each region apart, composited by depth") +
           "; frames composited by depth with their colour";
  }

  // Every rank renders its whole parts: the regions are the share.
  void render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
              FrameStats& stats) override {
    probeTogether(camera, share, stats);
    if (inner_.size() == 1) {
      if (inner_[0]) renderOnePart(camera, frame, fb, stats);
      return;
    }
    const ScreenTiles tiles(fb.width, fb.height);
    owner_.resize(fb.size());
    local_.resize(fb.size());
    std::vector<uint8_t> all(size_t(tiles.count()), 0);  // the tiles some part covered
    // Nearest part first, each told what the ones before drew: its rays stop there.
    WorkShare alone{0, 1};
    alone.drawnDepth = &fb.depth;
    for (uint32_t p : nearestFirst(camera.position())) {
      Framebuffer& into = scratch(fb, inner_[p]->colourFromIds());
      FrameStats own;
      inner_[p]->render(camera, frame, alone, into, own);
      addStagesAndCounts(own, stats);
      Stopwatch clock;
      const std::vector<uint8_t> touched = takeTouchedTiles(into, tiles, own);
      for (uint32_t i : tilePixels(fb, tiles, newTiles(touched, all))) owner_[i] = kNoOwner;
      keepNearerOfPart(p, into, fb, tilePixels(into, tiles, touched));
      stats.addStage("composite regions", clock.seconds());
    }
    Stopwatch clock;
    shadeWinners(camera, tilePixels(fb, tiles, all), fb);
    stats.addStage("shade", clock.seconds());
    stats.touchedTiles = std::move(all);
  }

  bool colourFromIds() const override { return false; }
  // The parts' colour lies where they cover unless a part brings colour of its own.
  bool colourOnlyWhereCovered() const override {
    return std::all_of(inner_.begin(), inner_.end(),
                       [](const auto& r) { return !r || r->colourOnlyWhereCovered(); });
  }

  FrameStats setupStats() const override {
    FrameStats stats;
    for (const auto& r : inner_) {
      if (!r) continue;
      const FrameStats own = r->setupStats();
      addStagesAndCounts(own, stats);
      if (held_.layout == Parts::kOne) stats.shared = own.shared;  // one part: the rank's figures
    }
    stats.addCount("held_regions", double(held_.mine.size()));
    for (const char* count : {"held_units", "held_triangles", "held_unique_triangles"})
      stats.addCount(count, 0.0);  // a rank holding no region says so too
    for (const ScenePart& part : held_.parts) {
      stats.addCount("held_units", double(part.units));
      stats.addCount("held_triangles", double(part.scene.expandedTriangles()));
      stats.addCount("held_unique_triangles", double(part.scene.uniqueTriangles()));
    }
    if (held_.bytesRead) stats.addCount("bytes_read", double(*held_.bytesRead));
    stats.setShared("regions", double(held_.regions));
    stats.setShared("units", double(held_.units));
    return stats;
  }

 private:
  // The world box of what a part holds (its root's own triangles and placed subtrees; the
  // root's node box is the whole scene's).
  static Bounds heldBox(const Scene& scene) {
    const Node& root = scene.rootNode();
    Bounds box = root.ownBounds();
    for (const Instance& inst : root.instances)
      if (scene.expandedCount[inst.node])
        box.extend(scene.nodeBounds[inst.node].transformed(inst.transform));
    return box;
  }
  // The parts, nearest box to the eye first (ties in part order).
  std::vector<uint32_t> nearestFirst(const glm::dvec3& eye) const {
    std::vector<std::pair<double, uint32_t>> order;
    for (uint32_t p = 0; p < inner_.size(); ++p)
      if (inner_[p])
        order.push_back({boxes_[p].empty()
                             ? std::numeric_limits<double>::infinity()
                             : glm::length(glm::clamp(eye, boxes_[p].lo, boxes_[p].hi) - eye),
                         p});
    std::sort(order.begin(), order.end());
    std::vector<uint32_t> parts;
    for (const auto& [distance, p] : order) parts.push_back(p);
    return parts;
  }
  // A probing method's step 0 over every part of every rank (src/core/frame_probe.hpp). Every
  // rank takes part in the reductions, one holding no part too.
  void probeTogether(const Camera& camera, const WorkShare& share, FrameStats& stats) {
    std::vector<FrameProbe*> probes;
    size_t rays = 0;
    for (const auto& r : inner_)
      if (auto* p = dynamic_cast<FrameProbe*>(r.get()); p && p->probeRays(camera) > 0) {
        probes.push_back(p);
        rays = p->probeRays(camera);
      }
    double most = -double(rays);  // the ray count, known on every rank
    if (share.minDoubles) share.minDoubles({&most, 1});
    if (most == 0.0) return;
    Stopwatch clock;
    std::vector<double> depths(size_t(-most), std::numeric_limits<double>::infinity());
    for (FrameProbe* p : probes) {
      const std::span<const double> own = p->coarseRayDepths(camera);
      for (size_t k = 0; k < depths.size(); ++k) depths[k] = std::min(depths[k], own[k]);
    }
    if (share.minDoubles) share.minDoubles(depths);
    std::array<uint64_t, 3> sums{};
    for (FrameProbe* p : probes) {
      const ProbeCounts c = p->probe(camera, depths);
      sums[0] += c.triangles, sums[1] += c.sampledUnits, sums[2] += c.sceneTriangles;
    }
    if (share.sumWords) share.sumWords(sums);
    if (!probes.empty()) {
      const bool everyPixel = probes.front()->everyPixelPays(
          camera, depths, ProbeCounts{sums[0], sums[1], sums[2]}, stats);
      for (FrameProbe* p : probes) p->setFrameWay(everyPixel);
      stats.setShared("every_pixel_cast", everyPixel ? 1.0 : 0.0);
    }
    stats.addStage("probe", clock.seconds());
  }
  // A rank's one part draws into its frame. Its IDs name its own triangles: shade first, then
  // renumber, both over the tiles it covered alone.
  void renderOnePart(const Camera& camera, int frame, Framebuffer& fb, FrameStats& stats) {
    FrameStats own;
    inner_[0]->render(camera, frame, WorkShare{0, 1}, fb, own);
    addStagesAndCounts(own, stats);
    // One part of all the rank's regions: its figures are the frame's.
    if (held_.layout == Parts::kOne) stats.shared = own.shared;
    Stopwatch clock;
    const ScreenTiles tiles(fb.width, fb.height);
    std::vector<uint8_t> touched = takeTouchedTiles(fb, tiles, own);
    const std::vector<uint32_t> pixels = tilePixels(fb, tiles, touched);
    if (inner_[0]->colourFromIds())
      shadePixels(held_.parts[0].scene, camera, pixels, fb.id, fb.color);
    const IdMap& ids = held_.parts[0].ids;
    const long n = long(pixels.size());
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) fb.id[pixels[size_t(k)]] = ids.global(fb.id[pixels[size_t(k)]]);
    stats.addStage("shade", clock.seconds());
    stats.touchedTiles = std::move(touched);
  }
  // The tiles of `touched` not yet in `all`, now added to it.
  static std::vector<uint8_t> newTiles(const std::vector<uint8_t>& touched,
                                       std::vector<uint8_t>& all) {
    std::vector<uint8_t> fresh(touched.size(), 0);
    for (size_t t = 0; t < touched.size(); ++t)
      if (touched[t] && !all[t]) fresh[t] = 1, all[t] = 1;
    return fresh;
  }
  // Part p's frame composited into the rank's by the whole scene's IDs; the winner's part and
  // own ID are kept for shading once at the end (not every part's whole frame). `pixels` are
  // those of the tiles the part covered; each covered one is emptied on the way, so the scratch
  // frame is left cleared for the next part.
  void keepNearerOfPart(uint32_t p, Framebuffer& into, Framebuffer& fb,
                        const std::vector<uint32_t>& pixels) {
    const IdMap& ids = held_.parts[p].ids;
    const long n = long(pixels.size());
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      const size_t i = pixels[size_t(k)];
      if (!into.covered(i) && into.depth[i] == kEmptyDepth) continue;
      const uint64_t id = ids.global(into.id[i]);
      if (into.covered(i) && nearer(into.depth[i], id, fb.depth[i], fb.id[i])) {
        fb.depth[i] = into.depth[i];
        fb.id[i] = id;
        fb.color[i] = into.color[i];
        owner_[i] = p;
        local_[i] = into.id[i];
      }
      into.depth[i] = kEmptyDepth, into.id[i] = kNoId, into.color[i] = kBackground;
    }
    // A part bringing its own colour may have coloured empty pixels too.
    scratchClear_ = inner_[p]->colourFromIds();
  }
  // Each pixel shaded by the part that won it (parts bringing their own colour keep it).
  void shadeWinners(const Camera& camera, const std::vector<uint32_t>& covered, Framebuffer& fb) {
    std::vector<uint32_t> start(inner_.size() + 1, 0);
    for (uint32_t i : covered)
      if (owner_[i] != kNoOwner) ++start[owner_[i] + 1];
    for (size_t p = 0; p < inner_.size(); ++p) start[p + 1] += start[p];
    pixels_.resize(start.back());
    std::vector<uint32_t> next(start.begin(), start.end() - 1);
    for (uint32_t i : covered)
      if (owner_[i] != kNoOwner) pixels_[next[owner_[i]]++] = i;
    for (size_t p = 0; p < inner_.size(); ++p)
      if (inner_[p] && inner_[p]->colourFromIds())
        shadePixels(held_.parts[p].scene, camera,
                    std::span(pixels_).subspan(start[p], start[p + 1] - start[p]), local_,
                    fb.color);
  }
  static void addStagesAndCounts(const FrameStats& from, FrameStats& to) {
    for (const auto& [name, seconds] : from.stageSeconds) to.addStage(name, seconds);
    for (const auto& [name, value] : from.counts.items()) to.addCount(name, value.get<double>());
  }
  // The frame a part renders into, cleared (the Renderer contract): the last part's
  // composite emptied it unless that part brought its own colour or this one does (its colour
  // must start from the background everywhere).
  Framebuffer& scratch(const Framebuffer& like, bool colourFromIds) {
    if (scratch_.width != like.width || scratch_.height != like.height)
      scratch_.resize(like.width, like.height);
    else if (!scratchClear_ || !colourFromIds)
      scratch_.clear();
    return scratch_;
  }

  static constexpr uint32_t kNoOwner = ~uint32_t(0);

  const HeldShare& held_;
  std::vector<std::unique_ptr<Renderer>> inner_;
  std::string method_;
  std::vector<Bounds> boxes_;  // per part, heldBox
  Framebuffer scratch_;
  bool scratchClear_ = false;     // every pixel of scratch_ empty, its colour the background
  std::vector<uint32_t> owner_;   // the part that won each pixel
  std::vector<uint64_t> local_;   // that part's own ID there
  std::vector<uint32_t> pixels_;  // the pixels grouped by owner
};

}  // namespace

std::unique_ptr<Renderer> makePartRenderer(const HeldShare& held,
                                           std::vector<std::unique_ptr<Renderer>> inner,
                                           const std::string& method) {
  return std::make_unique<PartRenderer>(held, std::move(inner), method);
}

}  // namespace lzb::regions
