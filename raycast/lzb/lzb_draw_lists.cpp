#include "raycast/lzb/lzb_draw_lists.hpp"

#include <algorithm>
#include <bit>

#include "raycast/lzb/lzb_triangle_set.hpp"

namespace lzb::localz {

namespace {

// Fewer placements than this are handled by the calling thread: a parallel region costs more
// than it saves, and on an oversubscribed machine it can stall for a scheduler time slice.
constexpr long kParallelPaths = 32;

// The list of one placement: the triangles collected in `set`, which take() empties for reuse.
DrawList placedList(uint32_t node, const glm::dmat4& world, uint64_t idBase, TriangleSet& set) {
  DrawList out{node, world, idBase, {}};
  set.take(out.triangles);
  return out;
}

// The non-empty lists, in their order, with their triangle total.
DrawLists nonEmpty(std::vector<DrawList>& lists) {
  DrawLists result;
  for (DrawList& l : lists)
    if (!l.triangles.empty()) {
      result.triangles += l.triangles.size();
      result.lists.push_back(std::move(l));
    }
  return result;
}

}  // namespace

DrawLists nearScene(const LzbAccel& accel, const CulledScene& culled, double zClip, int threads,
                    uint64_t* farTriangles) {
  const long paths = long(culled.paths.size());
  std::vector<DrawList> lists(culled.paths.size());
  uint64_t far = 0, nearLeaves = 0;
#pragma omp parallel num_threads(threads) reduction(+ : far, nearLeaves) \
    if (paths >= kParallelPaths)
  {
    TriangleSet nearSet;
#pragma omp for schedule(dynamic, 4)
    for (long p = 0; p < paths; ++p) {
      const CullPath& path = culled.paths[size_t(p)];
      if (path.leafDepthMin > zClip) {  // wholly far: every leaf's depthMax is past zClip too
        far += path.leafTriangles;
        continue;
      }
      const NodeAccel& a = accel.node(path.node);
      const size_t n = accel.scene().nodes[path.node].mesh.size();
      nearSet.reset(n);
      for (size_t i = path.firstLeaf; i < size_t(path.firstLeaf) + path.leafCount; ++i) {
        const CullLeaf& l = culled.leaves[i];
        if (l.depthMin < zClip) {
          ++nearLeaves;
          for (uint32_t t : a.leafTriangles(l.leaf)) nearSet.add(t);
        }
        if (l.depthMax > zClip) far += a.leafTriangles(l.leaf).size();
      }
      // Most placements of a far, instanced scene have nothing near: no list to make.
      if (nearSet.count() > 0)
        lists[size_t(p)] = placedList(path.node, path.world, path.idBase, nearSet);
    }
  }
  DrawLists result = nonEmpty(lists);
  result.leaves = nearLeaves;
  if (farTriangles) *farTriangles = far;
  return result;
}

DrawLists mergePvl(const LzbAccel& accel, std::span<const PvlPart> parts, int threads) {
  // Placements of every part, one per idBase, ascending.
  std::vector<PvlPlacement> placements;
  for (const PvlPart& part : parts)
    placements.insert(placements.end(), part.placements.begin(), part.placements.end());
  std::sort(placements.begin(), placements.end(),
            [](const PvlPlacement& a, const PvlPlacement& b) { return a.idBase < b.idBase; });
  placements.erase(std::unique(placements.begin(), placements.end(),
                               [](const PvlPlacement& a, const PvlPlacement& b) {
                                 return a.idBase == b.idBase;
                               }),
                   placements.end());
  // One bit per octree node of each placement: the union of the parts' leaves.
  std::vector<std::vector<uint64_t>> leafBits(placements.size());
  for (size_t p = 0; p < placements.size(); ++p)
    leafBits[p].assign((accel.node(placements[p].node).octree().nodeCount() + 63) / 64, 0);
  for (const PvlPart& part : parts) {
    size_t p = 0;
    uint64_t current = ~uint64_t(0);
    for (const PvlLeaf& l : part.leaves) {
      if (l.idBase != current) {  // parts are sorted by idBase: one search per placement
        current = l.idBase;
        p = size_t(
            std::lower_bound(placements.begin(), placements.end(), l.idBase,
                             [](const PvlPlacement& a, uint64_t v) { return a.idBase < v; }) -
            placements.begin());
      }
      leafBits[p][l.leaf >> 6] |= uint64_t(1) << (l.leaf & 63);
    }
  }
  std::vector<DrawList> lists(placements.size());
  std::vector<uint64_t> leafCount(placements.size(), 0);
  const long count = long(placements.size());
#pragma omp parallel num_threads(threads) if (count >= kParallelPaths)
  {
    TriangleSet set;
#pragma omp for schedule(dynamic, 4)
    for (long p = 0; p < count; ++p) {
      const PvlPlacement& pl = placements[size_t(p)];
      const NodeAccel& a = accel.node(pl.node);
      set.reset(accel.scene().nodes[pl.node].mesh.size());
      const std::vector<uint64_t>& bits = leafBits[size_t(p)];
      for (size_t w = 0; w < bits.size(); ++w)
        for (uint64_t word = bits[w]; word; word &= word - 1) {
          const uint32_t leaf = uint32_t(w * 64 + size_t(std::countr_zero(word)));
          ++leafCount[size_t(p)];
          for (uint32_t t : a.leafTriangles(leaf)) set.add(t);
        }
      lists[size_t(p)] = placedList(pl.node, pl.world, pl.idBase, set);
    }
  }
  DrawLists result = nonEmpty(lists);
  for (uint64_t n : leafCount) result.leaves += n;
  return result;
}

}  // namespace lzb::localz
