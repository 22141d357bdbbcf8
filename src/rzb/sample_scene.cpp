#include "src/rzb/sample_scene.hpp"

#include <algorithm>
#include <functional>
#include <stdexcept>

#include "src/core/progress.hpp"
#include "src/core/timer.hpp"

namespace lzb::rzb {

// Builds of fewer unique triangles show no progress line.
constexpr uint64_t kProgressTriangles = uint64_t(1) << 20;

InstanceRef makeInstanceRef(const Scene& scene, uint32_t child, const DistributionTree* childTree,
                            const glm::dmat4& transform, uint64_t idOffset) {
  InstanceRef r;
  r.node = child;
  r.child = childTree;
  r.transform = Affine::from(transform);
  r.idOffset = idOffset;
  r.translationOnly = r.transform.translationOnly();
  r.detSign = r.transform.det() < 0.0 ? -1.0 : 1.0;
  r.areaScale = maxAreaScale(r.transform.a);
  r.stretch = maxStretch(r.transform.a);
  const Bounds& b = childTree ? childTree->bounds() : scene.nodeBounds[child];
  r.bounds = b.transformed(transform);
  return r;
}

std::vector<InstanceRef> SampleScene::flattenInstances(uint32_t node) const {
  struct Pending {
    uint32_t node;
    glm::dmat4 transform;
    uint64_t idOffset;
  };
  const Scene& s = *scene_;
  std::vector<Pending> list;
  const Node& n = s.nodes[node];
  for (size_t i = 0; i < n.instances.size(); ++i)
    if (s.expandedCount[n.instances[i].node] > 0)
      list.push_back({n.instances[i].node, n.instances[i].transform, s.childOffset(node, i)});
  // Breadth-first: expand every triangle-less node in one pass while the budget allows.
  for (;;) {
    size_t grown = list.size();
    bool any = false;
    for (const Pending& p : list) {
      const Node& c = s.nodes[p.node];
      if (c.mesh.empty() && !c.instances.empty()) {
        grown += c.instances.size() - 1;
        any = true;
      }
    }
    if (!any || grown > params_.flattenBudget) break;
    std::vector<Pending> next;
    next.reserve(grown);
    for (const Pending& p : list) {
      const Node& c = s.nodes[p.node];
      if (!(c.mesh.empty() && !c.instances.empty())) {
        next.push_back(p);
        continue;
      }
      for (size_t i = 0; i < c.instances.size(); ++i)
        if (s.expandedCount[c.instances[i].node] > 0)
          next.push_back({c.instances[i].node, p.transform * c.instances[i].transform,
                          p.idOffset + s.childOffset(p.node, i)});
    }
    list = std::move(next);
  }
  std::vector<InstanceRef> out;
  out.reserve(list.size());
  for (const Pending& p : list)
    out.push_back(makeInstanceRef(s, p.node, trees_[p.node].get(), p.transform, p.idOffset));
  return out;
}

SampleScene::SampleScene(const Scene& scene, const DistributionParams& params)
    : scene_(&scene), params_(params) {
  Stopwatch clock;
  const size_t n = scene.nodes.size();
  trees_.resize(n);
  referencedBy_.assign(n, {});
  // Which nodes need a tree, and each one's height (children first), following the flattened
  // graph: the targets of a node's flattened instance entries.
  std::vector<int> height(n, -1);
  std::vector<std::vector<uint32_t>> targets(n);
  std::function<int(uint32_t)> visit = [&](uint32_t v) -> int {
    if (height[v] >= 0) return height[v];
    height[v] = 0;
    // Targets without trees yet: only the node indices matter here.
    std::vector<InstanceRef> refs = flattenInstances(v);
    int h = 0;
    for (const InstanceRef& r : refs) {
      targets[v].push_back(r.node);
      h = std::max(h, visit(r.node) + 1);
    }
    return height[v] = h;
  };
  visit(scene.root);
  const int maxHeight = height[scene.root];
  uint64_t toBuild = 0;
  for (uint32_t v = 0; v < n; ++v)
    if (height[v] >= 0) toBuild += scene.nodes[v].mesh.size();
  Progress progress("rzb distribution trees (triangles)", toBuild,
                    params_.progress && toBuild >= kProgressTriangles);
  for (int h = 0; h <= maxHeight; ++h) {
    std::vector<uint32_t> level;
    for (uint32_t v = 0; v < n; ++v)
      if (height[v] == h) level.push_back(v);
    // Large meshes first, so one big tree does not end the level alone.
    std::stable_sort(level.begin(), level.end(), [&](uint32_t a, uint32_t b) {
      return scene.nodes[a].mesh.size() > scene.nodes[b].mesh.size();
    });
#pragma omp parallel for schedule(dynamic, 1)
    for (size_t k = 0; k < level.size(); ++k) {
      const uint32_t v = level[k];
      trees_[v] = std::make_unique<DistributionTree>(scene, v, std::span<const uint32_t>{}, true,
                                                     flattenInstances(v), params_);
      progress.add(scene.nodes[v].mesh.size());
    }
  }
  progress.done();
  for (uint32_t v = 0; v < n; ++v) {
    if (!trees_[v]) continue;
    const DistributionTree& t = *trees_[v];
    for (uint32_t i = 0; i < t.instanceCount(); ++i)
      referencedBy_[t.instance(i).node].push_back({v, i});
  }
  // Samples descend into referenced trees by whole-list picks: those get alias tables.
#pragma omp parallel for schedule(dynamic, 1)
  for (uint32_t v = 0; v < n; ++v)
    if (trees_[v] && !referencedBy_[v].empty()) trees_[v]->enableAlias();
  for (uint32_t v = 0; v < n; ++v) {
    if (!trees_[v]) continue;
    const DistributionTree& t = *trees_[v];
    const TreeStats ts = t.stats();
    ++stats_.trees;
    stats_.nodes += ts.nodes;
    stats_.triangles += ts.triangles;
    stats_.instanceEntries += ts.instances;
    stats_.memoryBytes += ts.memoryBytes;
    stats_.maxDepth = std::max(stats_.maxDepth, ts.depth);
  }
  stats_.buildSeconds = clock.seconds();
}

DistributionTree& SampleScene::mutableTree(uint32_t node) {
  if (node >= trees_.size() || !trees_[node])
    throw std::invalid_argument("SampleScene: node " + std::to_string(node) + " has no tree");
  return *trees_[node];
}

// The tree of `node` changed its area: refresh the entries that reference it, up the graph.
void SampleScene::propagate(uint32_t node) {
  const DistributionTree& t = *trees_[node];
  for (const auto& [parent, entry] : referencedBy_[node]) {
    mutableTree(parent).updateInstance(entry, t.totalArea(), t.maxTriArea());
    propagate(parent);
  }
}

void SampleScene::insertTriangle(uint32_t node, uint32_t meshTriangle) {
  mutableTree(node).insertTriangle(meshTriangle);
  propagate(node);
}

void SampleScene::removeTriangle(uint32_t node, uint32_t meshTriangle) {
  mutableTree(node).removeTriangle(meshTriangle);
  propagate(node);
}

uint32_t SampleScene::insertInstance(uint32_t node, uint32_t child, const glm::dmat4& transform,
                                     uint64_t idOffset) {
  const DistributionTree& c = mutableTree(child);
  DistributionTree& t = mutableTree(node);
  const uint32_t entry = t.insertInstance(makeInstanceRef(*scene_, child, &c, transform, idOffset),
                                          c.totalArea(), c.maxTriArea());
  if (referencedBy_[child].empty()) mutableTree(child).enableAlias();
  referencedBy_[child].push_back({node, entry});
  propagate(node);
  return entry;
}

void SampleScene::removeInstance(uint32_t node, uint32_t entry) {
  DistributionTree& t = mutableTree(node);
  t.removeInstance(entry);
  auto& refs = referencedBy_[t.instance(entry).node];
  refs.erase(std::remove(refs.begin(), refs.end(), std::make_pair(node, entry)), refs.end());
  propagate(node);
}

void SampleScene::compact() {
  for (auto& t : trees_)
    if (t) t->compact();
}

}  // namespace lzb::rzb
