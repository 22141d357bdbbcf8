#include "raycast/raycast_method.hpp"

#include "raycast/raycast_renderer.hpp"

namespace lzb {

namespace {

class RaycastMethod : public Method {
 public:
  std::string name() const override { return "raycast"; }
  std::string summary() const override { return "exact: Embree primary rays"; }
  bool exact() const override { return true; }
  std::unique_ptr<Renderer> create(const Scene& scene, const RenderOptions& options) const override {
    return std::make_unique<RaycastRenderer>(scene, options);
  }
};

}  // namespace

std::unique_ptr<Method> makeRaycastMethod() { return std::make_unique<RaycastMethod>(); }

}  // namespace lzb
