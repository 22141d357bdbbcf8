#include "src/cli/methods.hpp"

#include "raycast/raycast_renderer.hpp"
#include "src/core/error.hpp"
#include "src/zbuffer/zbuffer_renderer.hpp"

namespace lzb {

const std::vector<std::string>& methodNames() {
  static const std::vector<std::string> names = {"zbuffer", "raycast"};
  return names;
}

void checkMethodName(const std::string& method, const std::string& field) {
  for (const std::string& n : methodNames())
    if (n == method) return;
  std::string known;
  for (const std::string& n : methodNames()) known += (known.empty() ? "" : ", ") + n;
  throw InputError(field + ": unknown method '" + method + "' (known: " + known + ")");
}

std::unique_ptr<Renderer> createRenderer(const std::string& method, const Scene& scene,
                                         const RenderOptions& options) {
  checkMethodName(method, "--method");
  if (method == "raycast") return std::make_unique<RaycastRenderer>(scene, options);
  return std::make_unique<ZBufferRenderer>(scene, options);
}

}  // namespace lzb
