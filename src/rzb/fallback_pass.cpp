#include "src/rzb/fallback_pass.hpp"

#include <algorithm>
#include <map>
#include <tuple>

namespace lzb::rzb {

void ascendingOnce(std::vector<uint32_t>& triangles, uint32_t meshSize) {
  if (uint64_t(triangles.size()) * 16 < meshSize) {
    std::sort(triangles.begin(), triangles.end());
    triangles.erase(std::unique(triangles.begin(), triangles.end()), triangles.end());
    return;
  }
  std::vector<uint64_t> present((size_t(meshSize) + 63) / 64, 0);
  for (const uint32_t t : triangles) present[t >> 6] |= uint64_t(1) << (t & 63);
  triangles.clear();
  for (size_t w = 0; w < present.size(); ++w)
    for (uint64_t bits = present[w]; bits; bits &= bits - 1)
      triangles.push_back(uint32_t(w * 64 + size_t(__builtin_ctzll(bits))));
}

DrawLists fallbackLists(const std::vector<SelectedBox>& boxes, const std::vector<uint32_t>& mine,
                        int threads) {
  // Keyed by (ID base, scene node): ascending keys are ascending IDs, path by path.
  struct Group {
    DrawList list;
    uint32_t meshSize = 0;
  };
  std::map<std::tuple<uint64_t, uint32_t>, Group> groups;
  for (uint32_t i : mine) {
    const SelectedBox& b = boxes[i];
    if (!b.fallback) continue;
    Group& group = groups[{b.idBase, b.tree->sceneNode()}];
    group.meshSize = uint32_t(b.tree->mesh().size());
    DrawList& g = group.list;
    g.node = b.tree->sceneNode();
    g.idBase = b.idBase;
    g.world = b.toWorld.matrix();
    b.tree->forEachEntry(b.node, b.part, [&](uint32_t r) {
      const EntryRec& e = b.tree->rec(r);
      if (!e.instance()) g.triangles.push_back(e.ref);
    });
  }
  std::vector<Group> sorted;
  sorted.reserve(groups.size());
  for (auto& [key, g] : groups) sorted.push_back(std::move(g));
  const long n = long(sorted.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (long k = 0; k < n; ++k)
    ascendingOnce(sorted[size_t(k)].list.triangles, sorted[size_t(k)].meshSize);
  DrawLists lists;
  lists.lists.reserve(sorted.size());
  for (Group& g : sorted) {
    lists.triangles += g.list.triangles.size();
    lists.lists.push_back(std::move(g.list));
  }
  return lists;
}

bool FallbackPass::draw(const Camera& camera, const std::vector<SelectedBox>& boxes,
                        const std::vector<uint32_t>& mine, Framebuffer& fb,
                        FallbackCounts& counts) {
  for (uint32_t i : mine) counts.boxes += boxes[i].fallback;
  const DrawLists lists = fallbackLists(boxes, mine, threads_);
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
