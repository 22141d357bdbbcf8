#include "raycast/lzb/lzb_cull.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <span>
#include <string>

#include "src/core/error.hpp"

namespace lzb::localz {

namespace {

InputError tooInstanced() {
  return InputError("lzb: more than " + std::to_string(kMaxCullPaths) +
                    " visible instances with triangles or " + std::to_string(kMaxCullLeaves) +
                    " visible octree leaves: too instanced for local z-buffering's per-leaf "
                    "culling (use --method raycast, rzb or hybrid)");
}

// Paths and leaves listed by every Culler of one cull, so a scene past a limit is refused at the
// limit, before its lists outgrow memory.
struct CullCounts {
  std::atomic<size_t> paths{0}, leaves{0};
  std::atomic<uint64_t> triangles{0};
  uint64_t triangleBudget = std::numeric_limits<uint64_t>::max();
};

// A child instance to visit: its node, placement and ID base.
struct ChildVisit {
  uint32_t node;
  glm::dmat4 world;
  uint64_t idBase;
};

// The camera's frustum with its far plane at view depth farDepth when that is nearer.
Frustum frustumTo(const Camera& camera, double farDepth) {
  Frustum f = camera.frustum();
  if (farDepth < camera.farPlane())
    f.planes[5] =
        Plane{-camera.forward(), glm::dot(camera.forward(), camera.position()) + farDepth};
  return f;
}

class Culler {
 public:
  Culler(const LzbAccel& accel, const Camera& camera, double farDepth, const LeafFilter* filter,
         CullCounts& listed)
      : accel_(accel), scene_(accel.scene()), camera_(camera),
        frustum_(frustumTo(camera, farDepth)), filter_(filter), listed_(listed) {}

  // Culls node's octree into out and walks its visible instances, or, with `deferred`, lists
  // them there (in instance order) for the caller to walk.
  void visit(uint32_t node, const glm::dmat4& world, uint64_t idBase, CulledScene& out,
             std::vector<ChildVisit>* deferred = nullptr) {
    const NodeAccel& a = accel_.node(node);
    if (a.empty()) return;
    if (listed_.triangles.load(std::memory_order_relaxed) >= listed_.triangleBudget) return;
    const bool hasTriangles = !scene_.nodes[node].mesh.empty();
    CullPath p;
    p.node = node;
    p.world = world;
    p.idBase = idBase;
    depthPlane(world, camera_.position(), camera_.forward(), p.depthGrad, p.depthOffset);
    if (filter_) {  // (the area scale only for a filter: lzb's own cull needs none)
      const LeafPlacement placement{p.depthGrad, p.depthOffset, maxAreaScale(glm::dmat3(world))};
      p.subtree = !scene_.nodes[node].instances.empty() &&
                  filter_->subtreeDrawnElsewhere(node, placement);
      p.drawnElsewhere =
          p.subtree || (hasTriangles && filter_->nodeDrawnElsewhere(node, placement));
    }
    uint32_t pathIndex = 0;
    if (hasTriangles || p.subtree) {
      if (listed_.paths.fetch_add(1, std::memory_order_relaxed) >= kMaxCullPaths)
        throw tooInstanced();
      pathIndex = uint32_t(out.paths.size());
      out.paths.push_back(p);
    }
    if (p.subtree) return;  // the other pass draws all of it
    const bool listLeaves = hasTriangles && !p.drawnElsewhere;
    std::vector<uint32_t> instances;
    const Frustum local = hasTriangles ? frustumToNodeSpace(frustum_, world) : Frustum{};
    const size_t leavesBefore = out.leaves.size();
    uint64_t leafTriangles = 0;
    double leafDepthMin = std::numeric_limits<double>::infinity();
    a.octree().cullFrustum(frustum_, world, [&](uint32_t leaf, Cull cull) {
      // The leaf's content box, tighter than its cube, decides (cube inside: content inside).
      const size_t triangles = listLeaves ? a.leafTriangles(leaf).size() : 0;
      if (triangles > 0 &&
          (cull == Cull::kInside || local.classify(a.contentBox(leaf)) != Cull::kOutside)) {
        double lo, hi;
        depthRange(a.contentBox(leaf), p.depthGrad, p.depthOffset, lo, hi);
        out.leaves.push_back({pathIndex, leaf, lo, hi});
        leafTriangles += triangles;
        leafDepthMin = std::min(leafDepthMin, lo);
      }
      for (uint32_t i : a.leafInstances(leaf)) instances.push_back(i);
    });
    const size_t added = out.leaves.size() - leavesBefore;
    listed_.triangles.fetch_add(leafTriangles, std::memory_order_relaxed);
    if (listLeaves) {
      CullPath& listed = out.paths[pathIndex];
      listed.firstLeaf = uint32_t(leavesBefore);
      listed.leafCount = uint32_t(added);
      listed.leafTriangles = leafTriangles;
      listed.leafDepthMin = leafDepthMin;
    }
    if (listed_.leaves.fetch_add(added, std::memory_order_relaxed) + added > kMaxCullLeaves)
      throw tooInstanced();
    if (instances.empty()) return;
    // An instance is listed by every leaf its box overlaps: walk it once, in instance order.
    std::sort(instances.begin(), instances.end());
    instances.erase(std::unique(instances.begin(), instances.end()), instances.end());
    const Node& nd = scene_.nodes[node];
    for (uint32_t i : instances) {
      if (!a.instanceUsable(i)) continue;
      const Instance& inst = nd.instances[i];
      const glm::dmat4 childWorld = world * inst.transform;
      if (frustum_.classify(scene_.nodeBounds[inst.node].transformed(childWorld)) == Cull::kOutside)
        continue;
      ++out.instancesVisited;
      const uint64_t childBase = idBase + scene_.childOffset(node, i);
      if (deferred)
        deferred->push_back({inst.node, childWorld, childBase});
      else
        visit(inst.node, childWorld, childBase, out);
    }
  }

 private:
  const LzbAccel& accel_;
  const Scene& scene_;
  const Camera& camera_;
  Frustum frustum_;
  const LeafFilter* filter_;
  CullCounts& listed_;
};

// Joins the parts into out in their order, each copied to its offset at once (indices shifted);
// out's lists are resized, not cleared, so that only new room is value-initialized.
void joinParts(std::span<const CulledScene> parts, CulledScene& out, int threads) {
  std::vector<size_t> pathAt(parts.size() + 1, 0), leafAt(parts.size() + 1, 0);
  out.instancesVisited = 0;
  for (size_t k = 0; k < parts.size(); ++k) {
    pathAt[k + 1] = pathAt[k] + parts[k].paths.size();
    leafAt[k + 1] = leafAt[k] + parts[k].leaves.size();
    out.instancesVisited += parts[k].instancesVisited;
  }
  out.paths.resize(pathAt.back());
  out.leaves.resize(leafAt.back());
  const long count = long(parts.size());
#pragma omp parallel for schedule(dynamic, 16) num_threads(std::max(threads, 1)) if (count > 16)
  for (long k = 0; k < count; ++k) {
    const CulledScene& part = parts[size_t(k)];
    const uint32_t pathOffset = uint32_t(pathAt[size_t(k)]);
    const uint32_t leafOffset = uint32_t(leafAt[size_t(k)]);
    CullPath* p = out.paths.data() + pathOffset;
    for (const CullPath& from : part.paths) {
      *p = from;
      p++->firstLeaf += leafOffset;
    }
    CullLeaf* l = out.leaves.data() + leafOffset;
    for (const CullLeaf& from : part.leaves) {
      *l = from;
      l++->path += pathOffset;
    }
  }
}

}  // namespace

void cullScene(const LzbAccel& accel, const Camera& camera, CulledScene& out, int threads,
               const LeafFilter* filter, double farDepth, uint64_t triangleBudget) {
  // Part 0 is the root's own, part k + 1 its visible instance k's, walked in parallel; the parts
  // are joined in that order, so the result is the serial walk's whatever the thread count.
  std::vector<CulledScene>& parts = out.parts;
  if (parts.empty()) parts.resize(1);
  const auto clear = [](CulledScene& part) {
    part.paths.clear();
    part.leaves.clear();
    part.instancesVisited = 0;
  };
  clear(parts[0]);
  CullCounts listed;
  listed.triangleBudget = triangleBudget;
  Culler culler(accel, camera, farDepth, filter, listed);
  std::vector<ChildVisit> children;
  culler.visit(accel.scene().root, glm::dmat4(1.0), 0, parts[0], &children);
  if (parts.size() < children.size() + 1) parts.resize(children.size() + 1);
  std::exception_ptr failure;
  const long count = long(children.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::max(threads, 1)) if (count > 1)
  for (long k = 0; k < count; ++k) {
    try {
      const ChildVisit& c = children[size_t(k)];
      CulledScene& part = parts[size_t(k) + 1];
      clear(part);
      Culler(accel, camera, farDepth, filter, listed).visit(c.node, c.world, c.idBase, part);
    } catch (...) {
#pragma omp critical
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
  joinParts(std::span<const CulledScene>(parts).first(children.size() + 1), out, threads);
}

CulledScene cullScene(const LzbAccel& accel, const Camera& camera, int threads,
                      const LeafFilter* filter) {
  CulledScene out;
  cullScene(accel, camera, out, threads, filter);
  return out;
}

}  // namespace lzb::localz
