#include "src/zbuffer/draw_lists.hpp"

#include <algorithm>
#include <numeric>

namespace lzb {

bool DrawLists::contains(uint64_t id) const {
  auto it = std::upper_bound(lists.begin(), lists.end(), id,
                             [](uint64_t v, const DrawList& l) { return v < l.idBase; });
  if (it == lists.begin()) return false;
  --it;
  if (id - it->idBase > 0xffffffffull) return false;
  return std::binary_search(it->triangles.begin(), it->triangles.end(), uint32_t(id - it->idBase));
}

void WholeNodeLists::add(DrawLists& lists, uint32_t node, const glm::dmat4& world, uint64_t idBase,
                         size_t triangles) {
  if (all_.size() <= node) all_.resize(size_t(node) + 1);
  std::vector<uint32_t>& all = all_[node];
  if (all.empty()) {
    all.resize(triangles);
    std::iota(all.begin(), all.end(), 0u);
  }
  lists.lists.push_back({node, world, idBase, all});
  lists.triangles += all.size();
}

}  // namespace lzb
