#include "src/sampletree/cell_octree.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "src/core/bounds.hpp"

namespace lzb::sampletree {

namespace {

struct Builder {
  const TriangleInput& in;
  const std::vector<double>& areas;
  uint32_t leafTriangles;
  CellOctree& tree;
  std::vector<int8_t> octant;      // per triangle of the cell being split
  std::vector<uint32_t> scratch;  // the cell's triangles regrouped by octant
  std::vector<glm::dvec3> centroids;  // per input triangle: found once, used on every level

  int childOf(uint32_t t, const glm::dvec3& centre, double childSize) const {
    return childOctant(centroids[t], glm::dvec3(in.vertex(t, 0)), glm::dvec3(in.vertex(t, 1)),
                       glm::dvec3(in.vertex(t, 2)), centre, childSize);
  }

  // Regroups tris stably as [staying | octant 0 | ... | octant 7] in place (one index array for
  // the whole subtree instead of nine lists per cell); returns each group's start, then the end.
  std::array<size_t, 10> split(std::span<uint32_t> tris, const glm::dvec3& centre,
                               double childSize) {
    octant.resize(tris.size());
    std::array<size_t, 10> start{};
    for (size_t k = 0; k < tris.size(); ++k) {
      octant[k] = int8_t(childOf(tris[k], centre, childSize));
      ++start[size_t(octant[k] + 2)];
    }
    for (size_t g = 1; g < start.size(); ++g) start[g] += start[g - 1];
    scratch.resize(tris.size());
    std::array<size_t, 10> next = start;
    for (size_t k = 0; k < tris.size(); ++k) scratch[next[size_t(octant[k] + 1)]++] = tris[k];
    std::copy(scratch.begin(), scratch.end(), tris.begin());
    return start;
  }

  // Appends the cell (level, cell) holding `tris` and its subtree; returns its index.
  int32_t build(uint8_t level, const uint32_t (&cell)[3], std::span<uint32_t> tris) {
    const int32_t index = int32_t(tree.nodes.size());
    tree.nodes.emplace_back();
    {
      BuildNode& n = tree.nodes.back();
      std::copy(cell, cell + 3, n.cell);
      n.level = level;
      n.subtreeTriangles = tris.size();
      for (uint32_t t : tris) n.subtreeArea += areas[t];
    }
    if (tris.size() <= leafTriangles || level == kMaxLevel) {
      tree.nodes[size_t(index)].own.assign(tris.begin(), tris.end());
      return index;
    }
    const glm::dvec3 centre = tree.cellCentre(tree.nodes[size_t(index)]);
    const double childSize = 0.5 * tree.size / double(uint64_t(1) << level);
    const std::array<size_t, 10> at = split(tris, centre, childSize);
    tree.nodes[size_t(index)].own.assign(tris.begin(), tris.begin() + ptrdiff_t(at[1]));
    for (int o = 0; o < 8; ++o) {
      const size_t first = at[size_t(o) + 1], end = at[size_t(o) + 2];
      const std::span<uint32_t> part = tris.subspan(first, end - first);
      if (part.empty()) continue;
      const uint32_t sub[3] = {2 * cell[0] + uint32_t(o & 1), 2 * cell[1] + uint32_t(o >> 1 & 1),
                               2 * cell[2] + uint32_t(o >> 2 & 1)};
      const int32_t c = build(uint8_t(level + 1), sub, part);
      tree.nodes[size_t(index)].child[size_t(o)] = c;
    }
    return index;
  }
};

}  // namespace

glm::dvec3 centroidOf(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return (a + b + c) / 3.0;
}

int childOctant(const glm::dvec3& centroid, const glm::dvec3& a, const glm::dvec3& b,
                const glm::dvec3& c, const glm::dvec3& centre, double childSize) {
  const int o = int(centroid.x >= centre.x) | int(centroid.y >= centre.y) << 1 |
                int(centroid.z >= centre.z) << 2;
  const glm::dvec3 childCentre =
      centre + 0.5 * childSize * glm::dvec3(o & 1 ? 1 : -1, o & 2 ? 1 : -1, o & 4 ? 1 : -1);
  const double r2 = 0.75 * childSize * childSize;  // (half diagonal)^2
  const auto inside = [&](const glm::dvec3& v) {
    const glm::dvec3 d = v - childCentre;
    return !(glm::dot(d, d) > r2);  // not <=: a NaN distance does not reject, as before
  };
  return inside(a) && inside(b) && inside(c) ? o : -1;
}

int childOctant(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                const glm::dvec3& centre, double childSize) {
  return childOctant(centroidOf(a, b, c), a, b, c, centre, childSize);
}

bool BuildNode::leaf() const {
  return std::all_of(child.begin(), child.end(), [](int32_t c) { return c == kNoChild; });
}

glm::dvec3 CellOctree::cellCentre(const BuildNode& n) const {
  const double s = cellSize(n);
  return origin + s * (glm::dvec3(n.cell[0], n.cell[1], n.cell[2]) + 0.5);
}

void fitRootCube(CellOctree& tree, const Bounds& b) {
  const glm::dvec3 e = b.extent();
  tree.size = std::max({e.x, e.y, e.z}) * (1.0 + 1e-6) + 1e-30;
  tree.origin = b.center() - glm::dvec3(0.5 * tree.size);
}

void buildCellSubtree(CellOctree& frame, const TriangleInput& in, const std::vector<double>& areas,
                      uint32_t leafTriangles, uint8_t level, const uint32_t (&cell)[3]) {
  std::vector<uint32_t> all(in.size());
  for (uint32_t t = 0; t < all.size(); ++t) all[t] = t;
  Builder b{in, areas, leafTriangles, frame, {}, {}, std::vector<glm::dvec3>(in.size())};
  for (uint32_t t = 0; t < all.size(); ++t)
    b.centroids[t] = centroidOf(glm::dvec3(in.vertex(t, 0)), glm::dvec3(in.vertex(t, 1)),
                                glm::dvec3(in.vertex(t, 2)));
  b.build(level, cell, all);
}

CellOctree buildCellOctree(const TriangleInput& in, const std::vector<double>& areas,
                           uint32_t leafTriangles) {
  CellOctree tree;
  if (in.size() == 0) return tree;
  Bounds b;
  for (const glm::vec3& p : in.positions) b.extend(glm::dvec3(p));
  fitRootCube(tree, b);
  const uint32_t root[3] = {0, 0, 0};
  buildCellSubtree(tree, in, areas, leafTriangles, 0, root);
  return tree;
}

}  // namespace lzb::sampletree
