#include "raycast/lzb/lzb_hit_leaves.hpp"

#include <cmath>
#include <stdexcept>

namespace lzb::localz {

namespace {

constexpr uint32_t kNone = ~uint32_t(0);
// Embree's hit point is float: its t (relative to the distance) and the vertices it holds
// (rounded in a frame centred on the node, relative to the node's size). Generous bounds on both.
constexpr double kDistanceSlack = 1e-6;
constexpr double kNodeSlack = 1e-6;

// The open interior of b holds q: no other leaf's closed box can reach q.
bool strictlyInside(const Bounds& q, const Bounds& b) {
  return q.lo.x > b.lo.x && q.lo.y > b.lo.y && q.lo.z > b.lo.z && q.hi.x < b.hi.x &&
         q.hi.y < b.hi.y && q.hi.z < b.hi.z;
}

}  // namespace

void HitLeafCounts::add(const HitLeafCounts& o) {
  rays += o.rays;
  hits += o.hits;
  nodesVisited += o.nodesVisited;
  leavesRecorded += o.leavesRecorded;
  resolves += o.resolves;
}

HitLeafRecorder::HitLeafRecorder(const LzbAccel& accel) : accel_(accel) {
  hint_.assign(accel.scene().nodes.size(), kNone);
  stack_.reserve(64);
}

void HitLeafRecorder::beginPart() {
  ++partSerial_;
}

HitLeafRecorder::Placed& HitLeafRecorder::placed(uint64_t id) {
  for (Placed& c : cache_)
    if (id >= c.base && id < c.end) return c;
  const Scene& scene = accel_.scene();
  const auto ref = scene.resolve(id);
  if (!ref) throw std::logic_error("lzb: a ray hit an ID outside the scene");
  ++counts.resolves;
  Placed& c = cache_[size_t(next_)];
  next_ = (next_ + 1) % kCache;
  c.base = id - ref->triangle;
  c.end = c.base + scene.nodes[ref->node].mesh.size();
  c.node = ref->node;
  c.world = ref->transform;
  c.toNode.a = glm::inverse(glm::dmat3(c.world));
  c.toNode.t = -(c.toNode.a * glm::dvec3(c.world[3]));
  for (int k = 0; k < 3; ++k)  // row k of the linear part (glm is column-major)
    c.spread[k] = std::abs(c.toNode.a[0][k]) + std::abs(c.toNode.a[1][k]) +
                  std::abs(c.toNode.a[2][k]);
  c.partSerial = 0;
  return c;
}

void HitLeafRecorder::record(const glm::dvec3& origin, const glm::dvec3& dir, const RayHit& hit,
                             PvlPart& out) {
  ++counts.rays;
  if (!hit.hit()) return;  // nothing seen: nothing to draw
  ++counts.hits;
  Placed& p = placed(hit.id);
  const double t = double(hit.t);
  const glm::dvec3 centre = p.toNode.point(origin + t * dir);
  // The near-miss radius at the hit's view depth (t), in world units, and the float slack.
  const double r = kNearMissPixels * t / pixelScale_ + kDistanceSlack * t * glm::length(dir);
  const glm::dvec3 half =
      r * p.spread + glm::dvec3(kNodeSlack * accel_.scene().nodeBounds[p.node].diagonal());
  collect(p, Bounds{centre - half, centre + half}, out);
}

void HitLeafRecorder::collect(Placed& p, const Bounds& query, PvlPart& out) {
  const NodeAccel& a = accel_.node(p.node);
  if (a.empty()) return;
  const Octree& tree = a.octree();
  uint32_t& hint = hint_[p.node];
  if (hint != kNone) {
    ++counts.nodesVisited;
    if (strictlyInside(query, tree.nodeBox(hint))) {
      if (a.contentBox(hint).overlaps(query)) recordLeaf(p, hint, out);
      return;
    }
  }
  stack_.clear();
  stack_.push_back(0);
  while (!stack_.empty()) {
    const uint32_t n = stack_.back();
    stack_.pop_back();
    ++counts.nodesVisited;
    // Content boxes (empty where no triangle is) are inside the node boxes: one test does both.
    if (!a.contentBox(n).overlaps(query)) continue;
    const Octree::Node& node = tree.node(n);
    if (node.leaf()) {
      recordLeaf(p, n, out);
      hint = n;
      continue;
    }
    for (uint32_t c = 0; c < 8; ++c) stack_.push_back(node.firstChild + c);
  }
}

void HitLeafRecorder::recordLeaf(Placed& p, uint32_t leaf, PvlPart& out) {
  if (p.partSerial != partSerial_) {  // listed once per part
    if (out.index.emplace(p.base, uint32_t(out.placements.size())).second)
      out.placements.push_back({p.base, p.node, p.world});
    p.partSerial = partSerial_;
  }
  const PvlLeaf l{p.base, p.node, leaf};
  if (!out.leaves.empty() && out.leaves.back() == l) return;  // the previous ray's leaf
  out.leaves.push_back(l);
  ++counts.leavesRecorded;
}

}  // namespace lzb::localz
