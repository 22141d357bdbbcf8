#pragma once
// The interface every rendering method implements.
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/core/scene.hpp"

namespace lzb {

// Which part of a frame's work this rank does: rank r of size ranks. A method must split its
// work so that compositing every rank's framebuffer by the compositing key (depth_key.hpp) gives
// the same image as size == 1, and must never key randomness by rank or thread.
struct WorkShare {
  int rank = 0;
  int size = 1;
  // Set by the frame driver, whose ranks render a frame at the same time: ORs `words` over the
  // ranks in place (every rank calls it at the same step). Unset (shares rendered one after
  // another in one process, and one rank): a method replicates the step that would need it.
  std::function<void(std::span<uint64_t>)> orWords = {};
  // Set alike: the minimum of `values` and the sum of `words` over the ranks, in place.
  std::function<void(std::span<double>)> minDoubles = {};
  std::function<void(std::span<uint64_t>)> sumWords = {};
  // Set by a driver that draws several shares into one frame one after another (a rank's
  // regions, nearest first): per pixel, the depth already drawn there (kEmptyDepth: none). A hit
  // beyond it loses the composite, so a method may skip looking for it; one at that depth may
  // still win on its ID and must be kept. Null: no bound.
  const std::vector<float>* drawnDepth = nullptr;
};

struct RenderOptions {
  std::string method = "zbuffer";
  int threads = 1;     // per rank, already resolved (> 0)
  uint64_t seed = 1;   // randomness is keyed by (seed, frame, node, sample)
  bool quiet = false;
  int frameGroups = 1;  // --frame-groups: the ranks cut into groups that render frames apart
  bool compactBvh =
      false;  // --bvh compact: Embree's leaves index the vertices (about half the memory)
};

// Measurements a method reports per frame (and once for its set-up): stage times in order, the
// counts of this rank's share of the work (summed over ranks in the report), and figures every
// rank computes alike (the plane depth, eps: reported once, from the root).
struct FrameStats {
  std::vector<std::pair<std::string, double>> stageSeconds;
  nlohmann::json counts = nlohmann::json::object();
  nlohmann::json shared = nlohmann::json::object();
  // Set by a renderer that knows them: 1 for each tile of ScreenTiles' default grid
  // (mpi/decomposition.hpp) where it covered a pixel of fb. Empty: the frame driver finds them
  // from the depths.
  std::vector<uint8_t> touchedTiles;

  void addStage(const std::string& name, double seconds) {
    for (auto& [n, s] : stageSeconds)
      if (n == name) {
        s += seconds;
        return;
      }
    stageSeconds.emplace_back(name, seconds);
  }
  void addCount(const std::string& name, double value) {
    counts[name] = counts.value(name, 0.0) + value;
  }
  void setShared(const std::string& name, double value) { shared[name] = value; }
};

class Renderer {
 public:
  virtual ~Renderer() = default;
  virtual std::string name() const = 0;
  // One sentence for the report: how this method splits a frame across ranks.
  virtual std::string decomposition() const = 0;
  // Renders the depth and ID of this rank's share of frame `frame` into fb (already sized and
  // cleared). Colour is shaded from the IDs by the frame driver (src/core/shading.hpp, over the
  // tiles the frame touched, mpi/frame_driver.hpp); a renderer whose colour is not a function of
  // the IDs fills it in too and says so with colourFromIds().
  virtual void render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
                      FrameStats& stats) = 0;
  virtual bool colourFromIds() const { return true; }
  // Whether fb's colour is the background wherever fb covers no pixel (so the frame driver clears
  // only the tiles a frame covered): colour shaded from the IDs is.
  virtual bool colourOnlyWhereCovered() const { return colourFromIds(); }
  // What building the method's structures took (stages) and made (shared counts), reported once.
  virtual FrameStats setupStats() const { return {}; }
};

// render()'s precondition: fb is the camera's size. Throws std::invalid_argument naming
// `renderer` otherwise (a caller's bug, not bad input).
void requireFrameSize(const Framebuffer& fb, const Camera& camera, const std::string& renderer);

}  // namespace lzb
