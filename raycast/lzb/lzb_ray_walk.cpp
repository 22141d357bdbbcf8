#include "raycast/lzb/lzb_ray_walk.hpp"

#include <algorithm>
#include <cmath>

namespace lzb::localz {

namespace {

constexpr uint32_t kNone = ~uint32_t(0);

// The leaf under `node` holding p, entering from the face of `axis` that the ray crosses: on
// that axis the half next to the face (robust to p rounding off the face), elsewhere as
// OctreeRopes::descend.
uint32_t descendAcross(const Octree& tree, uint32_t node, const glm::dvec3& p,
                       const glm::dvec3& dir, int axis) {
  for (;;) {
    const Octree::Node& nd = tree.node(node);
    if (nd.leaf()) return node;
    const glm::dvec3 mid = tree.nodeBox(nd.firstChild).hi;
    uint32_t o = 0;
    for (int k = 0; k < 3; ++k) {
      const bool upper =
          k == axis ? dir[k] < 0.0 : p[k] > mid[k] || (p[k] == mid[k] && dir[k] >= 0.0);
      if (upper) o |= 1u << k;
    }
    node = nd.firstChild + o;
  }
}

enum class Hit { kMiss, kNearMiss, kHit };

// Möller-Trumbore in double on the float vertices of the node frame; no tolerance, so a ray
// through a shared edge may miss both triangles (the walk then goes on: the PVL stays exact),
// but it never hits a triangle it passes by. A miss by less than kNearMissPixels at the hit
// plane (pixelScale: pixels per unit at view depth 1; t is the view depth of camera rays) is a
// near miss: the z-buffer's fixed-point rasterization may still cover that pixel centre.
Hit intersect(const Mesh& mesh, uint32_t tri, const WalkRay& ray, double tLo, double tHi,
              double pixelScale, double& tOut) {
  const glm::dvec3 a(mesh.vertex(tri, 0)), b(mesh.vertex(tri, 1)), c(mesh.vertex(tri, 2));
  const glm::dvec3 e1 = b - a, e2 = c - a;
  const glm::dvec3 p = glm::cross(ray.d, e2);
  const double det = glm::dot(e1, p);
  if (det == 0.0 || !std::isfinite(det)) return Hit::kMiss;  // edge-on: covers no pixel
  const double inv = 1.0 / det;
  const glm::dvec3 s = ray.o - a;
  const double u = glm::dot(s, p) * inv;
  if (!(u >= -0.5 && u <= 1.5)) return Hit::kMiss;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(ray.d, q) * inv;
  const double t = glm::dot(e2, q) * inv;
  if (!(t >= tLo && t <= tHi)) return Hit::kMiss;
  const double deficit = std::max({-u, -v, u + v - 1.0});
  if (deficit <= 0.0) {
    tOut = t;
    return Hit::kHit;
  }
  if (pixelScale <= 0.0 || deficit > 0.5) return Hit::kMiss;
  // The miss in pixels: barycentric deficit x the triangle's size, projected at depth t.
  const double size = std::sqrt(glm::length(glm::cross(e1, e2)) * glm::length(ray.d));
  return deficit * size * pixelScale / t <= kNearMissPixels ? Hit::kNearMiss : Hit::kMiss;
}

}  // namespace

LeafTest leafTestFor(const LzbOptions& options) {
  if (!options.usesOccluders()) return LeafTest::kAll;
  switch (options.occluderMode) {
    case OccluderMode::kStatic:
      return LeafTest::kStatic;
    case OccluderMode::kDynamic:
      return LeafTest::kDynamic;
    case OccluderMode::kHybrid:
      return LeafTest::kHybrid;
  }
  return LeafTest::kAll;
}

void RayWalkCounts::add(const RayWalkCounts& o) {
  rays += o.rays;
  nodesVisited += o.nodesVisited;
  leavesVisited += o.leavesVisited;
  triangleTests += o.triangleTests;
  visibilityTests += o.visibilityTests;
  instanceWalks += o.instanceWalks;
  climbs += o.climbs;
  contentMisses += o.contentMisses;
  hits += o.hits;
}

void PvlPart::finish() {
  std::sort(leaves.begin(), leaves.end());
  leaves.erase(std::unique(leaves.begin(), leaves.end()), leaves.end());
  std::sort(placements.begin(), placements.end(),
            [](const PvlPlacement& a, const PvlPlacement& b) { return a.idBase < b.idBase; });
  index.clear();
}

void PvlPart::clear() {
  leaves.clear();
  placements.clear();
  index.clear();
}

RayWalker::RayWalker(const LzbAccel& accel, LeafTest test, OctreeWalk walk)
    : accel_(accel), test_(test), walk_(walk) {
  hint_.assign(accel.scene().nodes.size(), kNone);
  stampRay_.assign(size_t(accel.instanceSlots()), 0);
  stampCtx_.assign(size_t(accel.instanceSlots()), 0);
  heap_.reserve(64);
  ctx_.reserve(16);
}

void RayWalker::resetCoherence() {
  std::fill(hint_.begin(), hint_.end(), kNone);
}

bool RayWalker::later(const Item& a, const Item& b) {
  return a.tEnter > b.tEnter ||
         (a.tEnter == b.tEnter && (a.ctx > b.ctx || (a.ctx == b.ctx && a.node > b.node)));
}

void RayWalker::push(const Item& item) {
  heap_.push_back(item);
  std::push_heap(heap_.begin(), heap_.end(), later);
}

RayWalker::Item RayWalker::pop() {
  std::pop_heap(heap_.begin(), heap_.end(), later);
  const Item item = heap_.back();
  heap_.pop_back();
  return item;
}

void RayWalker::enter(uint32_t ctx, double t0, double t1) {
  const uint32_t node = ctx_[ctx].node;
  const NodeAccel& a = accel_.node(node);
  if (a.empty()) return;
  const Octree& tree = a.octree();
  double e0 = t0, e1 = t1;
  if (!ctx_[ctx].ray.clip(tree.bounds(), e0, e1)) return;
  if (!ctx_[ctx].coherent) {
    push({e0, e1, ctx, 0});
    return;
  }
  const WalkRay& ray = ctx_[ctx].ray;
  const glm::dvec3 p = ray.o + e0 * ray.d;
  uint32_t leaf;
  if (hint_[node] == kNone) {
    leaf = OctreeRopes::descend(tree, 0, p, ray.d);
  } else {
    int climbed = 0;
    leaf = a.ropes().locate(tree, hint_[node], p, ray.d, &climbed);
    counts.climbs += uint64_t(climbed);
  }
  hint_[node] = leaf;
  // The start leaf holds the entry point: the ray enters it at e0 (no clip, which rounding can
  // push past e0; a leaf is queued by where the ray enters it, never later).
  push({e0, t1, ctx, leaf});
}

bool RayWalker::step(const Item& item, Item& next) {
  Context& c = ctx_[item.ctx];
  const NodeAccel& a = accel_.node(c.node);
  const Octree& tree = a.octree();
  const double limit = std::min(tMax_, tBest_);
  uint32_t leaf = item.node;
  double tEnter = item.tEnter;
  for (;;) {
    if (++c.steps > 4 * tree.nodeCount() + 64) {
      // Float trouble kept the walk from advancing: finish this octree top-down from here.
      c.coherent = false;
      double e0 = tEnter, e1 = tMax_;
      if (c.ray.clip(tree.bounds(), e0, e1)) push({e0, e1, item.ctx, 0});
      return false;
    }
    const Bounds& b = tree.nodeBox(leaf);
    double tx = std::numeric_limits<double>::infinity();
    int axis = -1;
    for (int k = 0; k < 3; ++k) {
      if (c.ray.flat[k]) continue;
      const double e = c.ray.exitAt(b, k);
      if (e < tx) {
        tx = e;
        axis = k;
      }
    }
    if (axis < 0) return false;
    tx = std::max(tx, tEnter);
    if (tx > limit) return false;
    const uint32_t neighbour = a.ropes().rope(leaf, 2 * axis + (c.ray.d[axis] > 0.0 ? 1 : 0));
    if (neighbour == kNone) return false;  // the ray leaves this octree
    const glm::dvec3 p = c.ray.o + tx * c.ray.d;
    leaf = descendAcross(tree, neighbour, p, c.ray.d, axis);
    ++counts.nodesVisited;
    if (tree.node(leaf).count == 0) {
      tEnter = tx;  // empty: step on without queueing
      continue;
    }
    next = {tx, tMax_, item.ctx, leaf};  // entered across the face, at tx
    return true;
  }
}

void RayWalker::flush(PvlPart& out) {
  // A ray that hit records every leaf it traversed (the paper's local list); one that found
  // nothing records only the leaves it could not clear (untested triangles or near misses).
  const bool hit = std::isfinite(tBest_);
  for (const RayLeaf& l : rayLeaves_)
    if (hit || !l.clearMiss) record(l.ctx, l.leaf, out);
  rayLeaves_.clear();
}

glm::dmat4 RayWalker::contextWorld(uint32_t ctx) const {
  uint32_t chain[64];
  int n = 0;
  for (uint32_t k = ctx; ctx_[k].parent != kNone && n < 64; k = ctx_[k].parent) chain[n++] = k;
  glm::dmat4 world(1.0);
  while (n > 0) {
    const Context& kc = ctx_[chain[--n]];
    world = world * accel_.scene().nodes[ctx_[kc.parent].node].instances[kc.instance].transform;
  }
  return world;
}

namespace {

LeafPlacement placementFrom(const glm::dmat4& world, const glm::dvec3& eye,
                            const glm::dvec3& forward) {
  LeafPlacement p;
  depthPlane(world, eye, forward, p.depthGrad, p.depthOffset);
  p.areaScale = maxAreaScale(glm::dmat3(world));
  return p;
}

}  // namespace

const LeafPlacement& RayWalker::placementOf(uint32_t ctx) {
  Context& c = ctx_[ctx];
  if (!c.leafPlaced) {
    c.leafPlacement = placementFrom(contextWorld(ctx), eye_, forward_);
    c.leafPlaced = true;
  }
  return c.leafPlacement;
}

bool RayWalker::drawnElsewhere(uint32_t ctx, uint32_t leaf) {
  const LeafPlacement& p = placementOf(ctx);
  Context& c = ctx_[ctx];
  if (c.wholeNode == 0) c.wholeNode = filter_->nodeDrawnElsewhere(c.node, p) ? 1 : 2;
  return c.wholeNode == 1 || filter_->drawnElsewhere(c.node, leaf, p);
}

bool RayWalker::instanceDrawnElsewhere(uint32_t ctx, uint32_t i) {
  const Scene& scene = accel_.scene();
  const Instance& inst = scene.nodes[ctx_[ctx].node].instances[i];
  // The child's world as contextWorld (and the cull) would compose it: the parent's, then this
  // instance.
  const LeafPlacement p = placementFrom(contextWorld(ctx) * inst.transform, eye_, forward_);
  if (!scene.nodes[inst.node].instances.empty())
    return filter_->subtreeDrawnElsewhere(inst.node, p);
  return filter_->nodeDrawnElsewhere(inst.node, p);
}

void RayWalker::record(uint32_t ctx, uint32_t leaf, PvlPart& out) {
  Context& c = ctx_[ctx];
  if (c.placement < 0) {
    auto it = out.index.find(c.idBase);
    if (it == out.index.end()) {
      it = out.index.emplace(c.idBase, uint32_t(out.placements.size())).first;
      out.placements.push_back({c.idBase, c.node, contextWorld(ctx)});
    }
    c.placement = int32_t(it->second);
  }
  out.leaves.push_back({c.idBase, c.node, leaf});
}

void RayWalker::processLeaf(uint32_t ctx, uint32_t leaf, PvlPart& out) {
  const uint32_t node = ctx_[ctx].node;
  const NodeAccel& a = accel_.node(node);
  const Scene& scene = accel_.scene();
  std::span<const uint32_t> tris = a.leafTriangles(leaf);
  // Triangles another pass draws are not tested (the filter's leaves are never recorded).
  if (filter_ && !countAll_ && !tris.empty() && drawnElsewhere(ctx, leaf)) tris = {};
  double c0 = tMin_, c1 = std::min(tBest_, tMax_);
  // A ray that misses the leaf's content box cannot hit a triangle of the leaf (in the leaf).
  if (!tris.empty() && !ctx_[ctx].ray.clip(a.contentBox(leaf), c0, c1)) {
    ++counts.contentMisses;
  } else if (!tris.empty() && countAll_) {
    const Mesh& mesh = scene.nodes[node].mesh;
    for (uint32_t t : tris) {
      double th;
      if (intersect(mesh, t, ctx_[ctx].ray, tMin_, tMax_, 0.0, th) == Hit::kHit)
        surfaces_.push_back(ctx_[ctx].idBase + t);
    }
  } else if (!tris.empty()) {
    const Mesh& mesh = scene.nodes[node].mesh;
    const WalkRay& ray = ctx_[ctx].ray;
    const glm::vec3 v = ctx_[ctx].unitDir;
    const float base = a.baseVisibility(leaf);
    const bool filter = test_ == LeafTest::kDynamic || test_ == LeafTest::kHybrid;
    const std::span<const uint32_t> candidates =
        test_ == LeafTest::kStatic || test_ == LeafTest::kHybrid
            ? a.leafOccluders(leaf)
            : (test_ == LeafTest::kDynamic ? a.leafDynamicCandidates(leaf) : tris);
    size_t tested = 0;
    bool near = false;
    for (uint32_t t : candidates) {
      if (filter) {
        ++counts.visibilityTests;
        if (!(-glm::dot(v, areaNormal(mesh, t)) > base)) continue;  // paper, equation (1)
      }
      ++counts.triangleTests;
      ++tested;
      double th;
      const Hit h = intersect(mesh, t, ray, tMin_, std::min(tBest_, tMax_), pixelScale_, th);
      if (h == Hit::kHit) {
        tBest_ = th;
        break;  // lazy: the first hit resolves this leaf
      }
      near |= h == Hit::kNearMiss;
    }
    // Every triangle tested and clearly missed: nothing of this leaf shows at this pixel.
    const bool clearMiss = pixelScale_ > 0.0 && tested == tris.size() && !near;
    rayLeaves_.push_back({ctx, leaf, clearMiss});
  }
  const std::span<const uint32_t> instances = a.leafInstances(leaf);
  if (instances.empty()) return;
  const Node& nd = scene.nodes[node];
  for (uint32_t i : instances) {
    if (!a.instanceUsable(i)) continue;
    const size_t slot = size_t(accel_.instanceSlot(node, i));
    if (stampRay_[slot] == rayNumber_ && stampCtx_[slot] == ctx) continue;  // walked already
    stampRay_[slot] = rayNumber_;
    stampCtx_[slot] = ctx;
    double i0 = tMin_, i1 = std::min(tBest_, tMax_);
    if (!ctx_[ctx].ray.clip(a.instanceBox(i), i0, i1)) continue;  // misses the instance
    if (filter_ && !countAll_ && instanceDrawnElsewhere(ctx, i)) continue;
    const Affine& inv = a.instanceInverse(i);
    const WalkRay& parentRay = ctx_[ctx].ray;
    const glm::dvec3 o = inv.point(parentRay.o), d = inv.vector(parentRay.d);
    const double len = glm::length(d);
    Context child{nd.instances[i].node,
                  ctx_[ctx].idBase + scene.childOffset(node, i),
                  ctx,
                  i,
                  WalkRay(o, d),
                  len > 0.0 ? glm::vec3(d / len) : glm::vec3(0.0f),
                  -1,
                  walk_ == OctreeWalk::kCoherent,
                  0};
    ctx_.push_back(child);
    ++counts.instanceWalks;
    enter(uint32_t(ctx_.size() - 1), tMin_, std::min(tMax_, tBest_));
  }
}

uint64_t RayWalker::countSurfaces(const glm::dvec3& origin, const glm::dvec3& dir, double tMin,
                                  double tMax) {
  const RayWalkCounts saved = counts;
  const OctreeWalk walk = walk_;
  walk_ = OctreeWalk::kTopDown;
  countAll_ = true;
  surfaces_.clear();
  PvlPart unused;
  cast(origin, dir, tMin, tMax, unused);
  countAll_ = false;
  walk_ = walk;
  counts = saved;
  std::sort(surfaces_.begin(), surfaces_.end());
  return uint64_t(std::unique(surfaces_.begin(), surfaces_.end()) - surfaces_.begin());
}

double RayWalker::cast(const glm::dvec3& origin, const glm::dvec3& dir, double tMin, double tMax,
                       PvlPart& out) {
  if (++rayNumber_ == 0) {  // wrapped: old stamps could match again
    std::fill(stampRay_.begin(), stampRay_.end(), 0);
    rayNumber_ = 1;
  }
  ctx_.clear();
  heap_.clear();
  rayLeaves_.clear();
  tMin_ = tMin;
  tMax_ = tMax;
  tBest_ = std::numeric_limits<double>::infinity();
  ++counts.rays;
  const double len = glm::length(dir);
  ctx_.push_back({accel_.scene().root, 0, kNone, 0, WalkRay(origin, dir),
                  len > 0.0 ? glm::vec3(dir / len) : glm::vec3(0.0f), -1,
                  walk_ == OctreeWalk::kCoherent, 0});
  enter(0, tMin, tMax);
  Item item{};
  bool held = false;  // item is the next to process (it precedes everything in the queue)
  for (;;) {
    if (!held) {
      if (heap_.empty()) break;
      item = pop();
    }
    held = false;
    if (item.tEnter > std::min(tBest_, tMax_)) break;  // every later leaf lies beyond the hit
    ++counts.nodesVisited;
    const Octree& tree = accel_.node(ctx_[item.ctx].node).octree();
    const Octree::Node& n = tree.node(item.node);
    if (!n.leaf()) {
      const WalkRay& ray = ctx_[item.ctx].ray;
      for (uint32_t c = n.firstChild; c < n.firstChild + 8; ++c) {
        const Octree::Node& child = tree.node(c);
        if (child.leaf() && child.count == 0) continue;
        double c0 = item.tEnter, c1 = item.tExit;
        if (ray.clip(tree.nodeBox(c), c0, c1)) push({c0, c1, item.ctx, c});
      }
      continue;
    }
    ++counts.leavesVisited;
    processLeaf(item.ctx, item.node, out);
    Item next;
    if (ctx_[item.ctx].coherent && step(item, next)) {
      // The common case, one walk in the queue: the next leaf comes first, skip the queue.
      if (heap_.empty() || !later(next, heap_.front())) {
        item = next;
        held = true;
      } else {
        push(next);
      }
    }
  }
  flush(out);
  if (std::isfinite(tBest_)) ++counts.hits;
  return tBest_;
}

}  // namespace lzb::localz
