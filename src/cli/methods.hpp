#pragma once
// The registry of --method values.
#include <memory>
#include <string>
#include <vector>

#include "src/cli/method_plugin.hpp"
#include "src/core/renderer.hpp"

namespace lzb {

const std::vector<MethodPlugin>& methods();
const MethodPlugin& methodNamed(const std::string& name, const std::string& field);
// Throws InputError naming `field` when `method` is not an exact method (zbuffer, raycast: the
// only ones a reference may be rendered with).
void checkExactMethod(const std::string& method, const std::string& field);
// Throws InputError naming --method for an unknown name.
std::unique_ptr<Renderer> createRenderer(const std::string& method, const Scene& scene,
                                         const RenderOptions& options);

}  // namespace lzb
