#include "src/cli/methods.hpp"

#include <algorithm>

#include "raycast/raycast_renderer.hpp"
#include "src/core/error.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"
// Method plugins of later issues include their header here.
#include "raycast/lzb_method.hpp"
#include "src/rzb/rzb_method.hpp"

namespace lzb {

namespace {

template <typename R>
MethodPlugin exactMethod(std::string name, std::string summary) {
  return MethodPlugin{std::move(name),
                      std::move(summary),
                      [](CLI::App&) {},
                      [] {},
                      [] { return nlohmann::json::object(); },
                      [](const Scene& scene, const RenderOptions& options) -> std::unique_ptr<Renderer> {
                        return std::make_unique<R>(scene, options);
                      }};
}

}  // namespace

const std::vector<MethodPlugin>& methods() {
  static const std::vector<MethodPlugin> all = {
      exactMethod<ZBufferRenderer>("zbuffer", "exact: conventional z-buffer through OSMesa"),
      exactMethod<RaycastRenderer>("raycast", "exact: Embree primary rays"),
      // Method plugins of later issues: one line each below this comment.
      lzbMethod(),
      rzbMethod(),
  };
  return all;
}

const MethodPlugin& methodNamed(const std::string& name, const std::string& field) {
  for (const MethodPlugin& m : methods())
    if (m.name == name) return m;
  std::string known;
  for (const MethodPlugin& m : methods()) known += (known.empty() ? "" : ", ") + m.name;
  throw InputError(field + ": unknown method '" + name + "' (known: " + known + ")");
}

void checkExactMethod(const std::string& method, const std::string& field) {
  static const std::vector<std::string> exact = {"zbuffer", "raycast"};
  if (std::find(exact.begin(), exact.end(), method) != exact.end()) return;
  std::string known;
  for (const std::string& m : exact) known += (known.empty() ? "" : ", ") + m;
  throw InputError(field + ": '" + method + "' is not an exact method (exact: " + known + ")");
}

std::unique_ptr<Renderer> createRenderer(const std::string& method, const Scene& scene,
                                         const RenderOptions& options) {
  return methodNamed(method, "--method").create(scene, options);
}

}  // namespace lzb
