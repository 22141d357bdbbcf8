#include "src/rzb/fallback_pass.hpp"

#include <algorithm>
#include <map>
#include <tuple>

namespace lzb::rzb {

bool FallbackPass::draw(const Camera& camera, const std::vector<SelectedBox>& boxes,
                        const std::vector<uint32_t>& mine, Framebuffer& fb,
                        FallbackCounts& counts) {
  struct Group {
    glm::dmat4 world;
    std::vector<uint32_t> triangles;
  };
  // Keyed by (ID base, scene node): ascending keys are ascending IDs, path by path.
  std::map<std::tuple<uint64_t, uint32_t>, Group> groups;
  for (uint32_t i : mine) {
    const SelectedBox& b = boxes[i];
    if (!b.fallback) continue;
    ++counts.boxes;
    Group& g = groups[{b.idBase, b.tree->sceneNode()}];
    g.world = b.toWorld.matrix();
    b.tree->forEachEntry(b.node, b.part, [&](uint32_t r) {
      const EntryRec& e = b.tree->rec(r);
      if (!e.instance()) g.triangles.push_back(e.ref);
    });
  }
  if (groups.empty()) return false;
  if (!raster_) raster_ = std::make_unique<TriangleRasterizer>(scene_);
  raster_->begin(camera);
  for (auto& [key, g] : groups) {
    std::sort(g.triangles.begin(), g.triangles.end());
    g.triangles.erase(std::unique(g.triangles.begin(), g.triangles.end()), g.triangles.end());
    raster_->drawList(std::get<1>(key), g.world, g.triangles, std::get<0>(key));
    counts.triangles += g.triangles.size();
    ++counts.drawCalls;
  }
  raster_->end(fb);
  return true;
}

}  // namespace lzb::rzb
