#pragma once
// The randomized sample tree (Klein et al., section 4): an octree whose node u stores a sample of
// m_u = q_u ln q_u + c q_u triangles drawn by area from its children, every triangle of the scene
// stored exactly once. Nodes are kept in preorder (children in octant order, so neighbouring
// cells' nodes lie together, in Morton order); a node's subtree is [index, subtreeEnd). Triangles
// lie in node order: node u stores [firstTriangle, firstTriangle + triangleCount).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "src/core/bounds.hpp"
#include "src/core/color.hpp"

namespace lzb::sampletree {

// One node as it is kept in memory and in the store (little-endian, 88 bytes).
struct TreeNode {
  uint64_t firstTriangle = 0;
  uint32_t triangleCount = 0;   // stored in this node
  uint32_t subtreeEnd = 0;      // preorder index just past this node's subtree
  uint32_t cell[3] = {0, 0, 0};  // cell coordinates at `level` (the root is level 0)
  uint8_t level = 0;
  uint8_t pad[3] = {0, 0, 0};
  uint64_t subtreeTriangles = 0;  // |P(u)|: triangles of the cell when the octree was built
  uint64_t representativeId = 0;  // the triangle whose colour stands for the node (kNoId: none)
  float representativePoint[3] = {0, 0, 0};  // its centroid, where the node's splat is drawn
  float representativeNormal[3] = {0, 0, 0};  // its shading normal (tree_shading.hpp)
  Rgba8 representativeColour = 0;
  uint32_t draws = 0;       // drawings made for this node's sample (0: a leaf)
  float subtreeArea = 0.0f;  // A(P(u))
  uint32_t pad2 = 0;        // explicit, so the stored bytes are always the same
};
static_assert(sizeof(TreeNode) == 88, "the store keeps nodes byte for byte");

// Leaves of at most 128 triangles: against 32, a 10^7 landscape frame in core took 0.089 s
// instead of 0.126 (as accurate), and a 10^8 store holds a quarter of the nodes, so its node
// table (88 bytes a node, resident out of core) leaves room for a cache that keeps a walk under
// 1 s a frame within 2 GB (runs/sampletree, part trade and scale).
constexpr uint32_t kDefaultLeafTriangles = 128;

// Construction settings, kept in the store's header.
struct TreeParams {
  double c = 13.8;          // p = exp(-exp(-c)) per stopping node
  uint64_t seed = 1;        // Philox key of the drawings
  uint32_t leafTriangles = kDefaultLeafTriangles;  // octree cells with more are split
};

struct SampleTree {
  TreeParams params;
  glm::dvec3 origin{0.0};  // the root cell: the cube [origin, origin + size]^3
  double size = 1.0;
  uint64_t sceneTriangles = 0;  // expanded triangles of the scene it was built from
  std::vector<TreeNode> nodes;  // preorder; nodes[0] is the root (empty: an empty scene)
  std::vector<glm::vec3> positions;  // world, 3 per triangle
  std::vector<uint64_t> ids;         // expanded triangle IDs
  std::vector<Rgba8> colours;
  std::string outline;  // the scene's outline (src/core/scene_outline.hpp) as text

  uint64_t triangles() const { return ids.size(); }
  double cellSize(const TreeNode& n) const { return size / double(uint64_t(1) << n.level); }
  Bounds cellBounds(const TreeNode& n) const;
  // Bytes of nodes and triangle data (what the store holds besides its header and checksums).
  uint64_t dataBytes() const;
};

}  // namespace lzb::sampletree
