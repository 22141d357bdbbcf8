#include "raycast/lzb/lzb_accel.hpp"

#include <algorithm>
#include <cmath>

#include "src/core/timer.hpp"

namespace lzb::localz {

namespace {

constexpr double kContentPad = 1e-7;  // relative to the box diagonal

bool finiteMatrix(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

}  // namespace

NodeAccel::NodeAccel(const Scene& scene, uint32_t node, const LzbAccelParams& params) {
  const Node& nd = scene.nodes[node];
  const Mesh& mesh = nd.mesh;
  OctreeParams op;
  op.maxDepth = params.maxDepth;
  // Mostly instances (a box test and a frame change each): the small limit.
  op.maxLeafEntries =
      nd.instances.size() >= mesh.size() ? params.instanceLeafEntries : params.leafEntries;
  octree_ = Octree(scene, node, op);
  ropes_ = OctreeRopes(octree_);

  std::vector<float> area(mesh.size());
  for (size_t t = 0; t < mesh.size(); ++t)
    area[t] = float(glm::length(areaVector(mesh, uint32_t(t))));

  instanceBoxes_ = Octree::instanceBoxes(scene, node);
  for (Bounds& b : instanceBoxes_)
    if (!b.empty()) {
      const glm::dvec3 pad(kContentPad * glm::length(b.extent()));
      b.lo -= pad;
      b.hi += pad;
    }
  inverse_.resize(nd.instances.size());
  usable_.assign(nd.instances.size(), 0);
  for (size_t i = 0; i < nd.instances.size(); ++i) {
    const glm::dmat4& m = nd.instances[i].transform;
    const double det = glm::determinant(glm::dmat3(m));
    if (!finiteMatrix(m) || !std::isfinite(det) || det == 0.0) continue;  // nothing to hit
    const glm::dmat4 inv = glm::inverse(m);
    if (!finiteMatrix(inv)) continue;
    inverse_[i] = Affine::from(inv);
    usable_[i] = 1;
  }

  const uint32_t count = octree_.nodeCount();
  triBegin_.assign(size_t(count) + 1, 0);
  instBegin_.assign(size_t(count) + 1, 0);
  occBegin_.assign(size_t(count) + 1, 0);
  dynBegin_.assign(size_t(count) + 1, 0);
  baseVisibility_.assign(count, 0.0f);
  content_.assign(count, Bounds{});
  const size_t k = size_t(std::max(params.occluders, 0));
  std::vector<uint32_t> sorted;
  for (uint32_t i = 0; i < count; ++i) {
    triBegin_[i] = uint32_t(tris_.size());
    instBegin_[i] = uint32_t(insts_.size());
    occBegin_[i] = uint32_t(occluders_.size());
    dynBegin_[i] = uint32_t(dynamic_.size());
    if (!octree_.node(i).leaf()) continue;
    sorted.clear();
    double areaSum = 0.0;
    for (uint32_t e : octree_.leafEntries(i)) {
      if (Octree::isInstance(e)) {
        insts_.push_back(Octree::entryIndex(e));
      } else {
        tris_.push_back(e);
        sorted.push_back(e);
        areaSum += area[e];
        for (int c = 0; c < 3; ++c) content_[i].extend(glm::dvec3(mesh.vertex(e, c)));
      }
    }
    if (!sorted.empty()) {
      // Cut to the leaf, then widen by a hair so rounding in slab tests never loses a hit on
      // the box's faces (content boxes are often flat: a ground plane, a wall).
      const Bounds& box = octree_.nodeBox(i);
      const glm::dvec3 pad(kContentPad * glm::length(box.extent()));
      content_[i].lo = glm::max(content_[i].lo, box.lo) - pad;
      content_[i].hi = glm::min(content_[i].hi, box.hi) + pad;
    }
    if (!sorted.empty())
      baseVisibility_[i] = float(params.baseFacing * areaSum / double(sorted.size()));
    // Largest first (ties: lower index). Octree-o keeps K of them; the dynamic selection only
    // ever tests triangles larger than the base visibility (|v.n| <= 1), so it lists those.
    std::sort(sorted.begin(), sorted.end(), [&](uint32_t a, uint32_t b) {
      return area[a] > area[b] || (area[a] == area[b] && a < b);
    });
    const size_t keep = std::min(k, sorted.size());
    occluders_.insert(occluders_.end(), sorted.begin(), sorted.begin() + ptrdiff_t(keep));
    for (uint32_t t : sorted) {
      if (!(area[t] > baseVisibility_[i] * (1.0f - 1e-5f))) break;
      dynamic_.push_back(t);
    }
  }
  // Inner nodes: the union of their children's content (children follow their parent).
  for (uint32_t i = count; i-- > 0;) {
    const Octree::Node& n = octree_.node(i);
    if (n.leaf()) continue;
    for (uint32_t c = n.firstChild; c < n.firstChild + 8; ++c)
      if (!content_[c].empty()) content_[i].extend(content_[c]);
  }
  triBegin_[count] = uint32_t(tris_.size());
  instBegin_[count] = uint32_t(insts_.size());
  occBegin_[count] = uint32_t(occluders_.size());
  dynBegin_[count] = uint32_t(dynamic_.size());
}

uint64_t NodeAccel::memoryBytes() const {
  return octree_.stats().memoryBytes + octree_.nodeCount() * (7 * 4 + 4 * 4 + 4 + 48) +
         4 * (tris_.size() + insts_.size() + occluders_.size() + dynamic_.size()) +
         (sizeof(Affine) + sizeof(Bounds)) * inverse_.size();
}

LzbAccel::LzbAccel(const Scene& scene, const LzbAccelParams& params)
    : scene_(scene), params_(params) {
  Stopwatch clock;
  nodes_.resize(scene.nodes.size());
  instanceSlotBegin_.assign(scene.nodes.size() + 1, 0);
  for (uint32_t n = 0; n < scene.nodes.size(); ++n) {
    instanceSlotBegin_[n + 1] = instanceSlotBegin_[n] + scene.nodes[n].instances.size();
    const Node& nd = scene.nodes[n];
    if (nd.mesh.empty() && nd.instances.empty()) continue;
    nodes_[n] = NodeAccel(scene, n, params);
    const NodeAccel& a = nodes_[n];
    stats_.octrees += 1;
    stats_.octreeNodes += a.octree().nodeCount();
    stats_.leaves += a.octree().stats().leaves;
    stats_.memoryBytes += a.memoryBytes();
  }
  for (const NodeAccel& a : nodes_)
    for (uint32_t i = 0; i < a.octree().nodeCount(); ++i)
      stats_.occluders += a.leafOccluders(i).size();
  stats_.seconds = clock.seconds();
}

}  // namespace lzb::localz
