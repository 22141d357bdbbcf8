#include "src/zbuffer/zbuffer_method.hpp"

#include "src/zbuffer/zbuffer_renderer.hpp"

namespace lzb {

namespace {

class ZBufferMethod : public Method {
 public:
  std::string name() const override { return "zbuffer"; }
  std::string summary() const override { return "exact: conventional z-buffer through OSMesa"; }
  bool exact() const override { return true; }
  std::unique_ptr<Renderer> create(const Scene& scene, const RenderOptions& options) const override {
    return std::make_unique<ZBufferRenderer>(scene, options);
  }
};

}  // namespace

std::unique_ptr<Method> makeZBufferMethod() { return std::make_unique<ZBufferMethod>(); }

}  // namespace lzb
