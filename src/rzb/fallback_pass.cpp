#include "src/rzb/fallback_pass.hpp"

#include <algorithm>
#include <map>
#include <tuple>

namespace lzb::rzb {

DrawLists fallbackLists(const std::vector<SelectedBox>& boxes, const std::vector<uint32_t>& mine) {
  // Keyed by (ID base, scene node): ascending keys are ascending IDs, path by path.
  std::map<std::tuple<uint64_t, uint32_t>, DrawList> groups;
  for (uint32_t i : mine) {
    const SelectedBox& b = boxes[i];
    if (!b.fallback) continue;
    DrawList& g = groups[{b.idBase, b.tree->sceneNode()}];
    g.node = b.tree->sceneNode();
    g.idBase = b.idBase;
    g.world = b.toWorld.matrix();
    b.tree->forEachEntry(b.node, b.part, [&](uint32_t r) {
      const EntryRec& e = b.tree->rec(r);
      if (!e.instance()) g.triangles.push_back(e.ref);
    });
  }
  DrawLists lists;
  lists.lists.reserve(groups.size());
  for (auto& [key, g] : groups) {
    std::sort(g.triangles.begin(), g.triangles.end());
    g.triangles.erase(std::unique(g.triangles.begin(), g.triangles.end()), g.triangles.end());
    lists.triangles += g.triangles.size();
    lists.lists.push_back(std::move(g));
  }
  return lists;
}

bool FallbackPass::draw(const Camera& camera, const std::vector<SelectedBox>& boxes,
                        const std::vector<uint32_t>& mine, Framebuffer& fb,
                        FallbackCounts& counts) {
  for (uint32_t i : mine) counts.boxes += boxes[i].fallback;
  const DrawLists lists = fallbackLists(boxes, mine);
  if (lists.lists.empty()) return false;
  if (render_ == FallbackRender::kNative)
    drawNative(camera, lists, fb);
  else
    drawGl(camera, lists, fb);
  counts.triangles += lists.triangles;
  counts.drawCalls += lists.lists.size();
  return true;
}

void FallbackPass::drawNative(const Camera& camera, const DrawLists& lists, Framebuffer& fb) {
  native_.draw(scene_, camera, lists, {}, threads_, fb);
}

void FallbackPass::drawGl(const Camera& camera, const DrawLists& lists, Framebuffer& fb) {
  if (!gl_) gl_ = std::make_unique<TriangleRasterizer>(scene_);
  gl_->begin(camera);
  for (const DrawList& l : lists.lists) gl_->drawList(l.node, l.world, l.triangles, l.idBase);
  gl_->end(fb);
}

}  // namespace lzb::rzb
