#include "src/sampletree/tree_build.hpp"

#include <algorithm>
#include <string>

#include "src/core/error.hpp"
#include "src/sampletree/cell_octree.hpp"
#include "src/sampletree/representative.hpp"
#include "src/sampletree/sample_draw.hpp"

namespace lzb::sampletree {

namespace {

// Triangles in each build node's subtree after sampling (the layout drops empty subtrees).
std::vector<uint64_t> remainingCounts(const CellOctree& oct) {
  std::vector<uint64_t> count(oct.nodes.size(), 0);
  // Preorder: children come after their parent, so a backward sweep sees children first.
  for (size_t u = oct.nodes.size(); u-- > 0;) {
    count[u] += oct.nodes[u].own.size();
    for (int32_t ch : oct.nodes[u].child)
      if (ch != kNoChild) count[u] += count[size_t(ch)];
  }
  return count;
}

struct Layout {
  const CellOctree& oct;
  const TriangleInput& in;
  const std::vector<double>& areas;
  const std::vector<uint64_t>& remaining;
  SampleTree& tree;

  void emit(size_t u) {
    const BuildNode& b = oct.nodes[u];
    const size_t index = tree.nodes.size();
    TreeNode n;
    std::copy(b.cell, b.cell + 3, n.cell);
    n.level = b.level;
    n.subtreeTriangles = b.subtreeTriangles;
    n.subtreeArea = float(b.subtreeArea);
    n.draws = b.draws;
    n.firstTriangle = tree.ids.size();
    n.triangleCount = uint32_t(b.own.size());
    n.representativeId = kNoId;
    std::vector<uint32_t> own = b.own;
    std::sort(own.begin(), own.end(), [&](uint32_t x, uint32_t y) { return in.ids[x] < in.ids[y]; });
    for (uint32_t t : own) {
      for (int k = 0; k < 3; ++k) tree.positions.push_back(in.vertex(t, k));
      tree.ids.push_back(in.ids[t]);
      tree.colours.push_back(in.colours[t]);
    }
    if (!own.empty()) {
      const uint32_t r = medianTriangle(in, areas, own);
      n.representativeId = in.ids[r];
      n.representativeColour = in.colours[r];
      const glm::vec3 centroid = (in.vertex(r, 0) + in.vertex(r, 1) + in.vertex(r, 2)) / 3.0f;
      for (int k = 0; k < 3; ++k) n.representativePoint[k] = centroid[k];
    }
    tree.nodes.push_back(n);
    for (int32_t ch : b.child)
      if (ch != kNoChild && remaining[size_t(ch)] > 0) emit(size_t(ch));
    tree.nodes[index].subtreeEnd = uint32_t(tree.nodes.size());
  }
};

}  // namespace

void validateParams(const TreeParams& p) {
  require(p.c >= 0.0 && p.c <= 50.0, "--c", "must be in [0, 50], got " + std::to_string(p.c));
  require(p.leafTriangles > 0, "--leaf-triangles", "must be > 0");
}

SampleTree buildTree(const TriangleInput& in, const TreeParams& params, int threads) {
  validateParams(params);
  std::vector<double> areas(in.size());
  for (size_t t = 0; t < in.size(); ++t) areas[t] = in.area(t);
  CellOctree oct = buildCellOctree(in, areas, params.leafTriangles);
  drawSamples(oct, areas, params.c, params.seed, threads);
  SampleTree tree;
  tree.params = params;
  tree.origin = oct.origin;
  tree.size = oct.size;
  tree.sceneTriangles = in.size();
  tree.positions.reserve(in.positions.size());
  tree.ids.reserve(in.size());
  tree.colours.reserve(in.size());
  if (!oct.nodes.empty()) {
    const std::vector<uint64_t> remaining = remainingCounts(oct);
    Layout{oct, in, areas, remaining, tree}.emit(0);
  }
  return tree;
}

SampleTree buildTree(const Scene& scene, const TreeParams& params, int threads) {
  validateParams(params);
  SampleTree tree = buildTree(gatherTriangles(scene), params, threads);
  tree.sceneTriangles = scene.expandedTriangles();
  return tree;
}

}  // namespace lzb::sampletree
