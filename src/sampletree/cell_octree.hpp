#pragma once
// The octree a sample tree is built from (section 4.1): a triangle goes to the child cell holding
// its centroid when it lies wholly inside that child's bounding sphere, else it stays in the
// parent. So small triangles on cell borders sink to the leaves instead of crowding the top
// levels, and every triangle of a cell lies in the cell's bounding sphere.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "src/core/bounds.hpp"
#include "src/sampletree/tree_input.hpp"

namespace lzb::sampletree {

constexpr int kMaxLevel = 20;  // cells of 2^-20 of the root: coordinates fit 32 bits
constexpr int32_t kNoChild = -1;

struct BuildNode {
  uint32_t cell[3] = {0, 0, 0};
  uint8_t level = 0;
  std::array<int32_t, 8> child;  // octant o: bit 0 x, bit 1 y, bit 2 z; kNoChild when empty
  std::vector<uint32_t> own;     // triangles stored here (indices into the input)
  double subtreeArea = 0.0;      // A(P(u))
  uint64_t subtreeTriangles = 0;  // |P(u)|
  uint32_t draws = 0;
  BuildNode() { child.fill(kNoChild); }
  bool leaf() const;
};

struct CellOctree {
  glm::dvec3 origin{0.0};
  double size = 1.0;
  std::vector<BuildNode> nodes;  // preorder, children in octant order
  double cellSize(const BuildNode& n) const { return size / double(uint64_t(1) << n.level); }
  glm::dvec3 cellCentre(const BuildNode& n) const;
};

// The root cube around bounds `b` (of the triangles' float vertices): a hair larger than the
// bounds, so every vertex is strictly inside. Sets origin and size.
void fitRootCube(CellOctree& tree, const Bounds& b);

// The octant of a cell centred at `centre` whose child (side childSize) takes the triangle
// (a, b, c): the child holding its centroid, when all three vertices lie in that child's bounding
// sphere; -1 when the triangle stays in the cell. The one rule of the in-memory and the external
// construction.
int childOctant(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                const glm::dvec3& centre, double childSize);
// The same with the triangle's centroid (centroidOf) given, for callers that reuse it per level.
glm::dvec3 centroidOf(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);
int childOctant(const glm::dvec3& centroid, const glm::dvec3& a, const glm::dvec3& b,
                const glm::dvec3& c, const glm::dvec3& centre, double childSize);

// The root cube around every triangle, split until a cell holds at most leafTriangles (or
// reaches kMaxLevel).
CellOctree buildCellOctree(const TriangleInput& in, const std::vector<double>& areas,
                           uint32_t leafTriangles);
// The subtree of cell (level, cell) of the cube `frame` (origin and size set), holding every
// triangle of `in` (all of P(cell), in input order): nodes[0] is that cell.
void buildCellSubtree(CellOctree& frame, const TriangleInput& in, const std::vector<double>& areas,
                      uint32_t leafTriangles, uint8_t level, const uint32_t (&cell)[3]);

}  // namespace lzb::sampletree
