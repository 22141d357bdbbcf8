#include "src/sqrt5/sqrt5_method.hpp"

#include "src/sqrt5/sqrt5_params.hpp"
#include "src/sqrt5/sqrt5_renderer.hpp"

namespace lzb {

namespace {

class Sqrt5Method : public Method {
 public:
  std::string name() const override { return "sqrt5"; }
  bool samplesProceduralObjects() const override { return true; }
  std::string summary() const override {
    return "approximate: procedural objects by sqrt(5) adaptive sampling of their (u, v) domain, "
           "meshes by Halton sample vectors, splatted (Stamminger & Drettakis)";
  }
  void addOptions(CLI::App& c) override {
    c.add_option("--amin", t_.amin,
                 "sqrt5: the sample size A'min in pixels: samples are refined until their "
                 "projected spacing is below sqrt(A'min); splats of max(1, ceil(sqrt(2 A'min))) "
                 "pixels; in [1/64, 64]")
        ->capture_default_str();
    c.add_option("--sqrt5-levels", t_.levels,
                 "sqrt5: refinement levels below the initial grid at most (each divides the "
                 "spacing by sqrt 5), in [0, 16]")
        ->capture_default_str();
    c.add_option("--horizon", t_.horizon,
                 "sqrt5: on | off: horizon occlusion culling of a terrain's initial samples, "
                 "line by line front to back in its sector (never changes the image)")
        ->capture_default_str();
    c.add_option("--sqrt5-cache-mb", t_.cacheMb,
                 "sqrt5: budget of the cache of sample forests across frames, MiB per rank (0: "
                 "none; never changes the image)")
        ->capture_default_str();
  }
  void validate() override { params_ = sqrt5::parseSqrt5Options(t_); }
  // runs/tradeoff/README.md "Presets".
  std::vector<PresetOption> preset(Quality q) const override {
    return pickPreset(q, {{"amin", "1"}}, {{"amin", "0.5"}}, {{"amin", "0.25"}});
  }
  nlohmann::json parameters() const override { return params_.toJson(); }
  std::unique_ptr<Renderer> create(const Scene& scene,
                                   const RenderOptions& options) const override {
    return std::make_unique<sqrt5::Sqrt5Renderer>(scene, options, params_);
  }

 private:
  sqrt5::Sqrt5OptionText t_;
  sqrt5::Sqrt5Params params_;
};

}  // namespace

std::unique_ptr<Method> makeSqrt5Method() {
  return std::make_unique<Sqrt5Method>();
}

}  // namespace lzb
