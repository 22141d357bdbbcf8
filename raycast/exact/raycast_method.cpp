#include "raycast/exact/raycast_method.hpp"

#include "raycast/exact/raycast_renderer.hpp"

namespace lzb {

std::unique_ptr<Method> makeRaycastMethod() {
  return std::make_unique<PlainMethod<RaycastRenderer>>("raycast", "exact: Embree primary rays",
                                                       /*exact=*/true);
}

}  // namespace lzb
