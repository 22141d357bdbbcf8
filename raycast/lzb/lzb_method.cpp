#include "raycast/lzb/lzb_method.hpp"

#include <string>

#include "raycast/lzb/lzb_options.hpp"
#include "raycast/lzb/lzb_renderer.hpp"

namespace lzb::localz {

namespace {

class LzbMethod : public Method {
 public:
  std::string name() const override { return "lzb"; }
  std::string summary() const override {
    return "exact*: local z-buffering (near z-buffer, far PVL by lazy/selective/object-oriented "
           "ray casting)";
  }
  void addOptions(CLI::App& c) override;
  void validate() override;
  nlohmann::json parameters() const override;
  std::unique_ptr<Renderer> create(const Scene& scene,
                                   const RenderOptions& options) const override {
    return std::make_unique<LzbRenderer>(scene, options, options_);
  }

 private:
  // The option values as typed, and the validated settings.
  std::string stage_ = "final";
  std::string plane_ = "cost";
  std::string occluderMode_ = "dynamic";
  std::string walk_;  // empty: the stage's own
  std::string nearRender_ = "native";
  std::string pvlRender_ = "native";
  std::string farRays_ = "embree";
  std::string tileDeal_ = "interleaved";
  LzbOptions options_;
};

void LzbMethod::addOptions(CLI::App& c) {
  LzbOptions& o = options_;
  c.add_option("--lzb-stage", stage_,
               "lzb: far-scene stage: naive | lazy | selective | oor | final")
      ->capture_default_str();
  addSharedOption(
      c, "--plane", plane_,
      "lzb, hybrid: partition plane: auto (coarse ray casting, mean depth), cost "
      "(coarse ray casting, cost model) or a fraction F in (0, 1) of the frustum depth");
  c.add_option("--plane-grid", o.planeGrid,
               "lzb: coarse rays of the dynamic planes (auto, cost): N x N pixels")
      ->capture_default_str();
  c.add_option("--plane-reuse", o.planeReuse,
               "lzb: frames a dynamic plane may be reused while still valid (0: never)")
      ->capture_default_str();
  c.add_option("--occluders", o.occluders, "lzb: K static local occluders per octree leaf")
      ->capture_default_str();
  c.add_option("--occluder-mode", occluderMode_,
               "lzb: local occluder selection: static | dynamic | hybrid")
      ->capture_default_str();
  c.add_option("--lzb-rays", farRays_,
               "lzb: who casts the far rays of the PVL stages: embree (each hit recorded as the "
               "octree leaves around it) | walk (the paper's octree walk, with its occluders)")
      ->capture_default_str();
  addTileDealOption(c, tileDeal_);
  c.add_option("--lzb-walk", walk_,
               "lzb: ray-octree walk: topdown | coherent (default: coherent for final, else "
               "topdown)");
  c.add_option("--near-render", nearRender_,
               "lzb: how the near scene is z-buffered: native (multithreaded) | gl (OSMesa)")
      ->capture_default_str();
  c.add_option("--pvl-render", pvlRender_,
               "lzb: how the PVL is z-buffered: native (multithreaded, only at the unfinished "
               "pixels) | gl (OSMesa; into the near pass's z-buffer when that is gl too)")
      ->capture_default_str();
  c.add_option("--lzb-depth-complexity", o.depthComplexityGrid,
               "lzb diagnostic: count every surface along N x N rays per frame (reported as "
               "depth_complexity, timed as stage 'diagnostics'; 0: off)")
      ->capture_default_str();
  c.add_option("--lzb-leaf", o.leafEntries, "lzb: octree leaf limit (triangles)")
      ->capture_default_str();
  c.add_option("--lzb-instance-leaf", o.instanceLeafEntries,
               "lzb: octree leaf limit for nodes with at least as many instances as triangles")
      ->capture_default_str();
}

void LzbMethod::validate() {
  LzbOptions& o = options_;
  o.stage = parseLzbStage(stage_, "--lzb-stage");
  parsePlane(plane_, "--plane", o);
  o.occluderMode = parseOccluderMode(occluderMode_, "--occluder-mode");
  o.walkOverride = !walk_.empty();
  if (o.walkOverride) o.walk = parseOctreeWalk(walk_, "--lzb-walk");
  o.nearRender = parseZBufferKind(nearRender_, "--near-render");
  o.pvlRender = parseZBufferKind(pvlRender_, "--pvl-render");
  o.farRays = parseFarRays(farRays_, "--lzb-rays");
  o.tileDeal = parseTileDeal(tileDeal_, "--tile-deal");
  localz::validate(o);
}

nlohmann::json LzbMethod::parameters() const {
  const LzbOptions& o = options_;
  nlohmann::json j = {{"stage", toString(o.stage)},
                      {"plane", o.dynamicPlane() ? nlohmann::json(o.costPlane ? "cost" : "auto")
                                                 : nlohmann::json(o.planeFraction)},
                      {"leaf_entries", o.leafEntries},
                      {"instance_leaf_entries", o.instanceLeafEntries}};
  if (o.dynamicPlane()) {
    j["plane_grid"] = o.planeGrid;
    j["plane_reuse"] = o.planeReuse;
  }
  j["near_render"] = toString(o.nearRender);
  if (o.usesPvl()) {
    j["pvl_render"] = toString(o.pvlRender);
    j["far_rays"] = toString(o.farRays);
    j["tile_deal"] = toString(o.tileDeal);
  }
  if (o.usesWalk()) j["octree_walk"] = toString(o.octreeWalk());
  if (o.usesWalk() && o.usesOccluders()) {
    j["occluders"] = o.occluders;
    j["occluder_mode"] = toString(o.occluderMode);
  }
  return j;
}

}  // namespace

void addTileDealOption(CLI::App& c, std::string& value) {
  addSharedOption(c, "--tile-deal", value,
                  "lzb, hybrid: how the far rays' screen tiles go to ranks: interleaved (tile mod "
                  "ranks) | cost (contiguous runs of equal ray count)");
}

std::unique_ptr<Method> makeLzbMethod() { return std::make_unique<LzbMethod>(); }

}  // namespace lzb::localz
