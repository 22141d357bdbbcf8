#include "src/sampletree/tree_build.hpp"

#include <algorithm>
#include <string>

#include "src/core/error.hpp"
#include "src/sampletree/cell_octree.hpp"
#include "src/sampletree/sample_draw.hpp"
#include "src/sampletree/tree_layout.hpp"

namespace lzb::sampletree {

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
  if (!oct.nodes.empty()) TreeLayout(oct, in, areas).emit(0, tree);
  return tree;
}

SampleTree buildTree(const Scene& scene, const TreeParams& params, int threads) {
  validateParams(params);
  SampleTree tree = buildTree(gatherTriangles(scene), params, threads);
  tree.sceneTriangles = scene.expandedTriangles();
  tree.outline = outlineText(outlineOf(scene));
  return tree;
}

}  // namespace lzb::sampletree
