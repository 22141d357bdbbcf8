#pragma once
// --method raycast: the exact Embree reference, every frame cast by castEveryPixel
// (pixel_cast.hpp), colour from the IDs through shadeFromIds.
#include <string>

#include "raycast/exact/embree_scene.hpp"
#include "src/core/renderer.hpp"

namespace lzb {

struct RaycastTuning {
  bool packets = true;  // Embree ray packets of 4x4 pixels rather than rtcIntersect1 per pixel
  EmbreeSceneOptions embree;  // threads (and --bvh compact) are taken from RenderOptions
};

class RaycastRenderer : public Renderer {
 public:
  // Builds the Embree scene (its time is setupStats()'s stage "build").
  RaycastRenderer(const Scene& scene, const RenderOptions& options,
                  const RaycastTuning& tuning = {});

  std::string name() const override { return "raycast"; }
  std::string decomposition() const override;
  void render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
              FrameStats& stats) override;
  FrameStats setupStats() const override;

  const EmbreeScene& embreeScene() const { return embree_; }

 private:
  const Scene& scene_;
  RenderOptions options_;
  RaycastTuning tuning_;
  EmbreeScene embree_;
};

}  // namespace lzb
