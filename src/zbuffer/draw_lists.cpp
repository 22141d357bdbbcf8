#include "src/zbuffer/draw_lists.hpp"

#include <algorithm>

namespace lzb {

bool DrawLists::contains(uint64_t id) const {
  auto it = std::upper_bound(lists.begin(), lists.end(), id,
                             [](uint64_t v, const DrawList& l) { return v < l.idBase; });
  if (it == lists.begin()) return false;
  --it;
  if (id - it->idBase > 0xffffffffull) return false;
  return std::binary_search(it->triangles.begin(), it->triangles.end(), uint32_t(id - it->idBase));
}

}  // namespace lzb
