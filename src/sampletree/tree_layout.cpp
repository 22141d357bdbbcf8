#include "src/sampletree/tree_layout.hpp"

#include <algorithm>

#include "src/sampletree/representative.hpp"
#include "src/sampletree/tree_shading.hpp"

namespace lzb::sampletree {

TreeLayout::TreeLayout(const CellOctree& oct, const TriangleInput& in,
                       const std::vector<double>& areas, std::vector<HiddenSubtree> hidden)
    : oct_(oct), in_(in), areas_(areas), hidden_(std::move(hidden)),
      remaining_(oct.nodes.size(), 0) {
  // Preorder: children come after their parent, so a backward sweep sees children first.
  for (size_t u = oct.nodes.size(); u-- > 0;) {
    remaining_[u] += oct.nodes[u].own.size() + (hidden_.empty() ? 0 : hidden_[u].triangles);
    for (int32_t ch : oct.nodes[u].child)
      if (ch != kNoChild) remaining_[u] += remaining_[size_t(ch)];
  }
}

void TreeLayout::emitChildren(size_t u, SampleTree& out) {
  for (int32_t ch : oct_.nodes[u].child)
    if (ch != kNoChild && remaining_[size_t(ch)] > 0) emit(size_t(ch), out);
}

void TreeLayout::emit(size_t u, SampleTree& out) {
  const BuildNode& b = oct_.nodes[u];
  const size_t index = out.nodes.size();
  TreeNode n;
  std::copy(b.cell, b.cell + 3, n.cell);
  n.level = b.level;
  n.subtreeTriangles = b.subtreeTriangles;
  n.subtreeArea = float(b.subtreeArea);
  n.draws = b.draws;
  n.firstTriangle = out.ids.size() + hiddenTriangles_;
  n.triangleCount = uint32_t(b.own.size());
  n.representativeId = kNoId;
  std::vector<uint32_t> own = b.own;
  const auto byId = [&](uint32_t x, uint32_t y) { return in_.ids[x] < in_.ids[y]; };
  // Leaves' lists come in input (ID) order already: only the sampled ones need sorting.
  if (!std::is_sorted(own.begin(), own.end(), byId)) std::sort(own.begin(), own.end(), byId);
  for (uint32_t t : own) {
    for (int k = 0; k < 3; ++k) out.positions.push_back(in_.vertex(t, k));
    out.ids.push_back(in_.ids[t]);
    out.colours.push_back(in_.colours[t]);
  }
  if (!own.empty()) {
    const uint32_t r = medianTriangle(in_, areas_, own);
    n.representativeId = in_.ids[r];
    n.representativeColour = in_.colours[r];
    const ShadingInputs s = shadingInputs(in_.vertex(r, 0), in_.vertex(r, 1), in_.vertex(r, 2));
    for (int k = 0; k < 3; ++k) n.representativePoint[k] = s.point[k];
    for (int k = 0; k < 3; ++k) n.representativeNormal[k] = s.normal[k];
  }
  out.nodes.push_back(n);
  if (!hidden_.empty() && hidden_[u].nodes > 0) {
    splices_.emplace_back(index, u);
    hiddenNodes_ += hidden_[u].nodes;
    hiddenTriangles_ += hidden_[u].triangles;
  }
  emitChildren(u, out);
  out.nodes[index].subtreeEnd = uint32_t(out.nodes.size() + hiddenNodes_);
}

}  // namespace lzb::sampletree
