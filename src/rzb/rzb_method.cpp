#include "src/rzb/rzb_method.hpp"

#include <memory>

#include "src/core/error.hpp"
#include "src/core/system.hpp"
#include "src/rzb/rzb_renderer.hpp"

namespace lzb {

namespace rzb {

RzbParams parseRzbOptions(const std::string& eps, double oversample, int splat,
                          const std::string& fallback, const std::string& reconstruct,
                          double areaRatio, double cacheMb, const std::string& backfaces,
                          const std::string& fallbackRender) {
  RzbParams p;
  if (eps == "auto") {
    p.autoEps = true;
  } else {
    p.eps = parseNumber(eps, "--eps", "a number > 1 or 'auto'");
  }
  p.oversample = oversample;
  p.splat = splat;
  if (fallback == "off") {
    p.fallback = false;
  } else if (fallback != "auto") {
    p.fallbackPx = parseNumber(fallback, "--fallback", "'auto', 'off' or a pixel area > 0");
    require(p.fallbackPx > 0.0, "--fallback", "must be > 0 pixels, got '" + fallback + "'");
  }
  require(fallbackRender == "native" || fallbackRender == "gl", "--fallback-render",
          "expected native or gl, got '" + fallbackRender + "'");
  p.fallbackRender = fallbackRender == "native" ? FallbackRender::kNative : FallbackRender::kGl;
  if (reconstruct == "auto") {
    p.reconstruct = splat > 1 ? Reconstruct::kSplat : Reconstruct::kPixel;
  } else if (reconstruct == "pixel") {
    p.reconstruct = Reconstruct::kPixel;
  } else if (reconstruct == "splat") {
    p.reconstruct = Reconstruct::kSplat;
  } else if (reconstruct == "gauss") {
    p.reconstruct = Reconstruct::kGauss;
  } else {
    throw InputError("--reconstruct: expected pixel, splat, gauss or auto, got '" + reconstruct + "'");
  }
  p.areaRatio = areaRatio;
  p.cacheMb = cacheMb;
  require(backfaces == "drop" || backfaces == "keep", "--backfaces",
          "expected drop or keep, got '" + backfaces + "'");
  p.dropBackfaces = backfaces == "drop";
  p.validate();
  return p;
}

}  // namespace rzb

namespace {

class RzbMethod : public Method {
 public:
  std::string name() const override { return "rzb"; }
  std::string summary() const override {
    return "approximate: randomized z-buffer point pass with z-buffer fallback and sample cache";
  }
  void addOptions(CLI::App& app) override {
    app.add_option("--eps", eps_,
                   "rzb: depth accuracy eps > 1 (a box is selected when (zmax/zmin)^2 <= eps), or "
                   "'auto' (least modelled cost per frame)")
        ->capture_default_str();
    addSharedOption(app, "--oversample", oversample_,
                    "rzb, hybrid: scales the ln(pixels) samples per pixel of projected area");
    addSharedOption(app, "--splat", splat_,
                    "rzb, hybrid: splat size d (d x d pixels; d^2 fewer samples); surfels: the "
                    "largest sprite; sampletree: stop at cells of at most d^2 pixels, drawn as d x d "
                    "splats");
    addSharedOption(app, "--fallback", fallback_,
                    "rzb, hybrid: boxes (hybrid: octree leaves) whose triangles project above this "
                    "many pixels are drawn exactly (rzb: z-buffer; hybrid: lazy ray casting + "
                    "PVL): auto (d^2 / ln pixels), off (rzb only), or a number");
    app.add_option("--fallback-render", fallbackRender_,
                   "rzb: how the fallback's triangles are z-buffered: native (multithreaded) | gl "
                   "(OSMesa)")
        ->capture_default_str();
    app.add_option("--reconstruct", reconstruct_,
                   "rzb: pixel | splat | gauss (Gaussian average of visible samples, 10x samples) "
                   "| auto (pixel for d = 1, else splat)")
        ->capture_default_str();
    app.add_option("--area-ratio", areaRatio_, "rzb: area class width, 2..64")->capture_default_str();
    // The help names the sample tree too, which shares --cache-mb (0: no cache there as well).
    addSharedOption(app, "--cache-mb", cacheMb_,
                    "rzb: sample cache budget in MiB (0: no cache); sampletree (with --tree): node "
                    "cache budget in MiB, rendering out of core (0: no cache, the store read whole)");
    addSharedOption(app, "--backfaces", backfaces_, "rzb, hybrid, surfels: drop | keep samples (surfels) on back faces");
  }
  void validate() override {
    params_ = rzb::parseRzbOptions(eps_, oversample_, splat_, fallback_, reconstruct_, areaRatio_,
                                   cacheMb_, backfaces_, fallbackRender_);
    // A budget the process cannot hold is refused now, not when the cache fills.
    requireMemory(params_.cacheBytes(), "--cache-mb", "a sample cache");
  }
  // runs/tradeoff/README.md "Presets": splat and oversampling moved accuracy; eps and a fixed
  // fallback threshold did not beat their defaults on every scene.
  std::vector<PresetOption> preset(Quality q) const override {
    return pickPreset(q, {{"splat", "2"}, {"oversample", "0.5"}},
                      {{"splat", "1"}, {"oversample", "1"}},
                      {{"splat", "1"}, {"oversample", "2"}, {"eps", "1.2"}});
  }
  nlohmann::json parameters() const override { return params_.toJson(); }
  std::unique_ptr<Renderer> create(const Scene& scene, const RenderOptions& options) const override {
    return std::make_unique<rzb::RzbRenderer>(scene, options, params_);
  }

 private:
  std::string eps_ = "1.5", fallback_ = "auto", reconstruct_ = "auto", backfaces_ = "drop",
              fallbackRender_ = "native";
  double oversample_ = 1.0, areaRatio_ = 4.0, cacheMb_ = 0.0;
  int splat_ = 1;
  rzb::RzbParams params_;
};

}  // namespace

std::unique_ptr<Method> makeRzbMethod() { return std::make_unique<RzbMethod>(); }

}  // namespace lzb
