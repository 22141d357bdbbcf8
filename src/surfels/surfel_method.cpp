#include "src/surfels/surfel_method.hpp"

#include "src/surfels/surfel_params.hpp"
#include "src/surfels/surfel_renderer.hpp"

namespace lzb {

namespace {

class SurfelMethod : public Method {
 public:
  std::string name() const override { return "surfels"; }
  std::string summary() const override {
    return "approximate: objects as surfel sprites from cached multi-resolution surfel collectors, "
           "near objects as polygons by the native z-buffer";
  }
  void addOptions(CLI::App& c) override {
    c.add_option("--surfelize", t_.surfelize,
                 "surfels: how objects become surfels: raster (3D rasterization into the grid) | "
                 "shots (z-buffer shots from 26 directions)")
        ->capture_default_str();
    c.add_option("--surfel-quality", t_.quality,
                 "surfels: collector layout: low (4 bytes: 256^3 positions, 11-bit normals, 9-bit "
                 "colour) | high (6 bytes: 1024^3, 15-bit normals, 18-bit colour)")
        ->capture_default_str();
    c.add_option("--surfel-grids", t_.grids,
                 "surfels: the levels of detail, cells per axis: ascending powers of two up to the "
                 "collector's lattice (256 low, 1024 high); auto: 1, 2, 4, ... up to half the "
                 "lattice (128 low, 512 high)")
        ->capture_default_str();
    addSharedOption(c, "--splat", t_.splat,
                    "rzb, hybrid: splat size d (d x d pixels; d^2 fewer samples); surfels: the "
                    "largest sprite; sampletree: stop at cells of at most d^2 pixels, drawn as d x d "
                    "splats");
    c.add_option("--sprite-shape", t_.shape, "surfels: square | disc sprites")
        ->capture_default_str();
    c.add_option("--surfel-cell", t_.cell,
                 "surfels: a level is used when its cell projects to at most this fraction of the "
                 "sprite (0.5: no holes); objects no level fits stay polygons")
        ->capture_default_str();
    c.add_option("--collisions", t_.collisions,
                 "surfels: a cell's triangles averaged into one surfel (average) or into two when "
                 "normals or colours differ too much (split)")
        ->capture_default_str();
    addSharedOption(c, "--backfaces", t_.backfaces,
                    "rzb, hybrid, surfels: drop | keep samples (surfels) on back faces");
    c.add_option("--budget-ms", t_.budgetMs,
                 "surfels: time budget of the surfel pass in ms (0: none): the surfels it buys at "
                 "--budget-rate, drawn in each collector's shuffled order")
        ->capture_default_str();
    c.add_option("--budget-rate", t_.budgetRate,
                 "surfels: surfels per ms the budget converts with: auto (measured at set-up: the "
                 "image then depends on this run's timing; one rank only) or a rate (the same "
                 "image anywhere)")
        ->capture_default_str();
    c.add_option(
         "--surfel-build", t_.build,
         "surfels: lazy (a level is built when a frame first needs it, then cached) | setup "
         "(every level of every object before the first frame)")
        ->capture_default_str();
  }
  void validate() override { params_ = surfels::parseSurfelOptions(t_); }
  // runs/tradeoff/README.md "Presets": the sprite size is the trade; grids up to 64 cells were
  // both faster and more accurate than finer ones (objects no level fits stay polygons), so
  // balanced and exact agree.
  std::vector<PresetOption> preset(Quality q) const override {
    const PresetOption grids{"surfel-grids", "1,2,4,8,16,32,64"};
    return pickPreset(q, {{"splat", "2"}, grids}, {{"splat", "1"}, grids}, {{"splat", "1"}, grids});
  }
  nlohmann::json parameters() const override { return params_.toJson(); }
  std::unique_ptr<Renderer> create(const Scene& scene,
                                   const RenderOptions& options) const override {
    return std::make_unique<surfels::SurfelRenderer>(scene, options, params_);
  }

 private:
  surfels::SurfelOptionText t_;
  surfels::SurfelParams params_;
};

}  // namespace

std::unique_ptr<Method> makeSurfelMethod() {
  return std::make_unique<SurfelMethod>();
}

}  // namespace lzb
