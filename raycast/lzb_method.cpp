#include "raycast/lzb_method.hpp"

#include <string>

#include "raycast/lzb_options.hpp"
#include "raycast/lzb_renderer.hpp"

namespace lzb {

namespace {

// The option values as typed, and the validated settings (owned by the plugin).
struct LzbArgs {
  std::string stage = "final";
  std::string plane = "cost";
  std::string occluderMode = "dynamic";
  std::string walk;  // empty: the stage's own
  std::string nearRender = "native";
  std::string pvlRender = "native";
  LzbOptions options;
};

LzbArgs& args() {
  static LzbArgs a;
  return a;
}

void addOptions(CLI::App& c) {
  LzbArgs& a = args();
  LzbOptions& o = a.options;
  c.add_option("--lzb-stage", a.stage,
               "lzb: far-scene stage: naive | lazy | selective | oor | final")
      ->capture_default_str();
  c.add_option("--plane", a.plane,
               "lzb: partition plane: auto (coarse ray casting, mean depth), cost (coarse ray "
               "casting, cost model) or a fraction F in (0, 1) of the frustum depth")
      ->capture_default_str();
  c.add_option("--plane-grid", o.planeGrid,
               "lzb: coarse rays of the dynamic planes (auto, cost): N x N pixels")
      ->capture_default_str();
  c.add_option("--plane-reuse", o.planeReuse,
               "lzb: frames a dynamic plane may be reused while still valid (0: never)")
      ->capture_default_str();
  c.add_option("--occluders", o.occluders, "lzb: K static local occluders per octree leaf")
      ->capture_default_str();
  c.add_option("--occluder-mode", a.occluderMode,
               "lzb: local occluder selection: static | dynamic | hybrid")
      ->capture_default_str();
  c.add_option("--lzb-walk", a.walk,
               "lzb: ray-octree walk: topdown | coherent (default: coherent for final, else "
               "topdown)");
  c.add_option("--near-render", a.nearRender,
               "lzb: how the near scene is z-buffered: native (multithreaded) | gl (OSMesa)")
      ->capture_default_str();
  c.add_option("--pvl-render", a.pvlRender,
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

void validateArgs() {
  LzbArgs& a = args();
  LzbOptions& o = a.options;
  o.stage = parseLzbStage(a.stage, "--lzb-stage");
  parsePlane(a.plane, "--plane", o);
  o.occluderMode = parseOccluderMode(a.occluderMode, "--occluder-mode");
  o.walkOverride = !a.walk.empty();
  if (o.walkOverride) o.walk = parseOctreeWalk(a.walk, "--lzb-walk");
  o.nearRender = parseZBufferKind(a.nearRender, "--near-render");
  o.pvlRender = parseZBufferKind(a.pvlRender, "--pvl-render");
  validate(o);
}

nlohmann::json parameters() {
  const LzbOptions& o = args().options;
  nlohmann::json j = {{"stage", toString(o.stage)},
                      {"plane", o.dynamicPlane() ? nlohmann::json(o.costPlane ? "cost" : "auto")
                                                 : nlohmann::json(o.planeFraction)},
                      {"octree_walk", toString(o.octreeWalk())},
                      {"leaf_entries", o.leafEntries},
                      {"instance_leaf_entries", o.instanceLeafEntries}};
  if (o.dynamicPlane()) {
    j["plane_grid"] = o.planeGrid;
    j["plane_reuse"] = o.planeReuse;
  }
  j["near_render"] = toString(o.nearRender);
  if (o.usesPvl()) j["pvl_render"] = toString(o.pvlRender);
  if (o.usesOccluders()) {
    j["occluders"] = o.occluders;
    j["occluder_mode"] = toString(o.occluderMode);
  }
  return j;
}

}  // namespace

MethodPlugin lzbMethod() {
  return MethodPlugin{
      "lzb",
      "exact*: local z-buffering (near z-buffer, far PVL by lazy/selective/object-oriented ray "
      "casting)",
      addOptions,
      validateArgs,
      parameters,
      [](const Scene& scene, const RenderOptions& options) -> std::unique_ptr<Renderer> {
        return std::make_unique<LzbRenderer>(scene, options, args().options);
      }};
}

}  // namespace lzb
