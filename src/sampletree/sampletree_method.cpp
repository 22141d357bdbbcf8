#include "src/sampletree/sampletree_method.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "src/core/error.hpp"
#include "src/core/system.hpp"
#include "src/sampletree/node_link.hpp"
#include "src/sampletree/sampletree_renderer.hpp"
#include "src/sampletree/store_reader.hpp"
#include "src/sampletree/tree_build.hpp"
#include "src/splat/splatter.hpp"

namespace lzb {

namespace {

constexpr double kMaxCacheMb = 1099511627776.0;  // 2^40 MiB, as rzb's: its bytes fit an integer

// 1e+300 rather than 301 digits.
std::string shortNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", v);
  return text;
}

class SampleTreeMethod : public Method {
 public:
  std::string name() const override { return "sampletree"; }
  std::string summary() const override {
    return "approximate: randomized sample tree (area-drawn triangle samples per octree node, "
           "far-off splatting)";
  }
  void addOptions(CLI::App& app) override {
    app.add_option("--tree", st_.treePath,
                   "sampletree: a store written by `lzb build-tree` (default: build in memory)");
    app.add_option("--c", st_.c,
                   "sampletree (in-memory build): sample size constant, p = exp(-exp(-c)) per "
                   "stopping node")
        ->capture_default_str();
    // rzb adds --splat first (the help shows its text, which names the sample tree too).
    addSharedOption(app, "--splat", st_.splat,
                    "rzb, hybrid: splat size d (d x d pixels; d^2 fewer samples); surfels: the "
                    "largest sprite; sampletree: stop at cells of at most d^2 pixels, drawn as d x d "
                    "splats");
    app.add_option("--stop-draw", stopDraw_,
                   "sampletree: what a node where the traversal stops draws: splat (its "
                   "representative, section 4.5) | triangles (its own triangles, section 4.2)")
        ->capture_default_str();
    // rzb adds --cache-mb first; 0 means no cache for both (here: the whole store read in memory).
    addSharedOption(app, "--cache-mb", st_.cacheMb,
                    "rzb: sample cache budget in MiB (0: no cache); sampletree (with --tree): node "
                    "cache budget in MiB, rendering out of core (0: no cache, the store read whole)");
    app.add_option("--cache-levels", st_.cacheLevels,
                   "sampletree (with --tree and --cache-mb): levels below the nodes where the "
                   "traversal stopped that a background thread prefetches (0: none)")
        ->capture_default_str();
    app.add_flag("--node-server", st_.nodeServer,
                 "sampletree (with --tree, --cache-mb and >= 2 MPI ranks): the last rank reads the "
                 "store and serves node payloads to the others, which render (section 6.1)");
    app.add_option("--leaf-triangles", st_.leafTriangles,
                   "sampletree (in-memory build): octree cells with more triangles are split")
        ->capture_default_str();
  }
  void validate() override {
    validateSplat(st_.splat);
    require(stopDraw_ == "splat" || stopDraw_ == "triangles", "--stop-draw",
            "expected splat or triangles, got '" + stopDraw_ + "'");
    st_.stopDraw = stopDraw_ == "splat" ? sampletree::StopDraw::kSplat : sampletree::StopDraw::kTriangles;
    sampletree::validateParams({st_.c, 1, st_.leafTriangles});
    if (!st_.treePath.empty())
      require(std::filesystem::is_regular_file(st_.treePath), "--tree",
              st_.treePath + " is not a file");
    validateNodeServer();  // first: its message says what --node-server needs
    validateCache();
  }
  void validateCache() const {
    require(std::isfinite(st_.cacheMb) && st_.cacheMb >= 0.0 && st_.cacheMb <= kMaxCacheMb,
            "--cache-mb", "must be 0 (no cache) or a budget in MiB up to 2^40, got " + shortNumber(st_.cacheMb));
    require(st_.cacheMb == 0.0 || !st_.treePath.empty(), "--cache-mb",
            "the sample tree's node cache needs a store (--tree); a tree built in memory is "
            "resident whole");
    require(st_.cacheLevels >= 0 && st_.cacheLevels <= 2, "--cache-levels",
            "must be 0, 1 or 2 (section 6.2: j in {1, 2}), got " + std::to_string(st_.cacheLevels));
    // A budget the process cannot hold is refused now, not when the cache fills.
    requireMemory(uint64_t(st_.cacheMb * 1024.0 * 1024.0), "--cache-mb", "a node cache");
  }
  void validateNodeServer() const {
    if (!st_.nodeServer) return;
    require(!st_.treePath.empty(), "--node-server",
            "serves the nodes of a tree store: it needs --tree (a store written by lzb build-tree)");
    require(st_.cacheMb > 0.0, "--node-server",
            "the render ranks keep the served nodes in a node cache: it needs --cache-mb > 0");
    const int ranks = sampletree::worldRanks();
    require(ranks >= 2, "--node-server",
            "one rank serves the nodes and the others render: it needs at least 2 MPI ranks "
            "(mpiexec -n 2 or more), got " + std::to_string(ranks));
    // The node cache's loader thread asks the server while the frame thread composites.
    require(sampletree::threadsMayCallMpi(), "--node-server",
            "needs an MPI library that provides MPI_THREAD_MULTIPLE (this one does not)");
  }
  // runs/tradeoff/README.md "Presets".
  std::vector<PresetOption> preset(Quality q) const override {
    return pickPreset(q, {{"splat", "2"}, {"c", "0"}}, {{"splat", "1"}, {"c", "5"}},
                      {{"splat", "1"}, {"c", "0"}});
  }
  nlohmann::json parameters() const override {
    return {{"tree", st_.treePath.empty() ? "in memory" : st_.treePath},
            {"c", st_.c},
            {"splat", st_.splat},
            {"stop_draw", stopDraw_},
            {"leaf_triangles", st_.leafTriangles},
            {"cache_mb", st_.cacheMb},
            {"cache_levels", st_.cacheLevels},
            {"node_server", st_.nodeServer}};
  }
  // A store keeps the outline of the scene it was built from: no need to load the scene.
  std::optional<SceneOutline> storedOutline(const std::string& scene) const override {
    if (st_.treePath.empty()) return std::nullopt;
    const std::string where = st_.treePath + " (sample tree store)";
    SceneOutline o = parseOutline(sampletree::readStoreOutline(st_.treePath), where);
    require(namesSameScene(scene, o.source), where,
            "built from " + o.source + ", not from " + scene + " (name that scene to render it)");
    return o;
  }
  bool rendersFromStore() const override { return !st_.treePath.empty(); }
  std::unique_ptr<Renderer> create(const Scene& scene, const RenderOptions& options) const override {
    return std::make_unique<sampletree::SampleTreeRenderer>(scene, options, st_);
  }

 private:
  sampletree::SampleTreeOptions st_;
  std::string stopDraw_ = "splat";
};

}  // namespace

std::unique_ptr<Method> makeSampleTreeMethod() { return std::make_unique<SampleTreeMethod>(); }

}  // namespace lzb
