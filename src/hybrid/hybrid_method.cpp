#include "src/hybrid/hybrid_method.hpp"

#include <string>

#include "raycast/lzb/lzb_method.hpp"
#include "src/core/error.hpp"
#include "src/hybrid/hybrid_renderer.hpp"

namespace lzb {

namespace {

class HybridMethod : public Method {
 public:
  std::string name() const override { return "hybrid"; }
  std::string summary() const override {
    return "approximate: near scene by z-buffer; behind the partition plane, sub-pixel octree "
           "leaves by the randomized point pass, the rest by lazy ray casting -> PVL -> z-buffer";
  }
  void addOptions(CLI::App& c) override {
    addSharedOption(c, "--oversample", oversample_,
                    "rzb, hybrid: scales the ln(pixels) samples per pixel of projected area");
    addSharedOption(c, "--splat", params_.splat,
                    "rzb, hybrid: splat size d (d x d pixels; d^2 fewer samples); surfels: the "
                    "largest sprite; sampletree: stop at cells of at most d^2 pixels, drawn as d x d "
                    "splats");
    addSharedOption(c, "--fallback", fallback_,
                    "rzb, hybrid: boxes (hybrid: octree leaves) whose triangles project above this "
                    "many pixels are drawn exactly (rzb: z-buffer; hybrid: lazy ray casting + "
                    "PVL): auto (rzb: d^2 / ln pixels; hybrid: d^2 / 10^4), off (rzb only), or a "
                    "number");
    addSharedOption(c, "--backfaces", backfaces_, "rzb, hybrid, surfels: drop | keep samples (surfels) on back faces");
    addSharedOption(c, "--plane", plane_,
                    "lzb, hybrid: partition plane: auto (coarse ray casting, mean depth), cost "
                    "(coarse ray casting, cost model) or a fraction F in (0, 1) of the frustum "
                    "depth");
    localz::addTileDealOption(c, tileDeal_);
    c.add_option("--far-pass", farPass_,
                 "hybrid: the exact far scene by lazy ray casting -> PVL -> z-buffer (lazy), by "
                 "each unfinished pixel's Embree hit (direct), or auto: direct from 16 culled "
                 "triangles per pixel; lazy wherever a mesh or subtree is sampled whole (a direct "
                 "frame samples nothing)")
        ->capture_default_str();
    c.add_option("--frame-way", frameWay_,
                 "hybrid: draw each frame by local z-buffering with the point pass (local), by "
                 "casting every pixel as --method raycast does (rays), or auto: rays when the "
                 "frame's probe finds as many triangles in front of its nearest coarse hits as "
                 "covered pixels")
        ->capture_default_str();
  }
  void validate() override {
    params_.oversample = oversample_;
    params_.fallbackPx = 0.0;
    if (fallback_ != "auto") {
      const std::string expected = "'auto' or a pixel area > 0 for the hybrid";
      params_.fallbackPx = parseNumber(fallback_, "--fallback", expected);
      require(params_.fallbackPx > 0.0, "--fallback", "expected " + expected + ", got '" + fallback_ + "'");
    }
    require(backfaces_ == "drop" || backfaces_ == "keep", "--backfaces",
            "expected drop or keep, got '" + backfaces_ + "'");
    params_.dropBackfaces = backfaces_ == "drop";
    localz::parsePlane(plane_, "--plane", params_.lzb);
    params_.lzb.tileDeal = parseTileDeal(tileDeal_, "--tile-deal");
    params_.farPass = hybrid::parseFarPass(farPass_, "--far-pass");
    params_.frameWay = hybrid::parseFrameWay(frameWay_, "--frame-way");
    params_.validate();
  }
  // runs/tradeoff/README.md "Presets".
  std::vector<PresetOption> preset(Quality q) const override {
    return pickPreset(q, {{"splat", "2"}, {"oversample", "0.5"}},
                      {{"splat", "1"}, {"oversample", "1"}},
                      {{"splat", "1"}, {"oversample", "2"}});
  }
  nlohmann::json parameters() const override { return params_.toJson(); }
  std::unique_ptr<Renderer> create(const Scene& scene, const RenderOptions& options) const override {
    return std::make_unique<hybrid::HybridRenderer>(scene, options, params_);
  }

 private:
  double oversample_ = 1.0;
  std::string fallback_ = "auto", backfaces_ = "drop", plane_ = "cost", tileDeal_ = "interleaved",
              farPass_ = "auto", frameWay_ = "auto";
  hybrid::HybridParams params_;
};

}  // namespace

std::unique_ptr<Method> makeHybridMethod() { return std::make_unique<HybridMethod>(); }

}  // namespace lzb
