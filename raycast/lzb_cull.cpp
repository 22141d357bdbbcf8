#include "raycast/lzb_cull.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "src/core/error.hpp"

namespace lzb {

namespace {

class Culler {
 public:
  Culler(const LzbAccel& accel, const Camera& camera)
      : accel_(accel), scene_(accel.scene()), camera_(camera), frustum_(camera.frustum()) {}

  void visit(uint32_t node, const glm::dmat4& world, uint64_t idBase, CulledScene& out) {
    const NodeAccel& a = accel_.node(node);
    if (a.empty()) return;
    const bool hasTriangles = !scene_.nodes[node].mesh.empty();
    uint32_t pathIndex = 0;
    if (hasTriangles) {
      if (out.paths.size() >= kMaxCullPaths)
        throw InputError("lzb: more than " + std::to_string(kMaxCullPaths) +
                         " visible instances with triangles: too instanced for local "
                         "z-buffering's per-leaf culling (use --method raycast)");
      CullPath p;
      p.node = node;
      p.world = world;
      p.idBase = idBase;
      p.depthGrad = glm::transpose(glm::dmat3(world)) * camera_.forward();
      p.depthOffset = glm::dot(glm::dvec3(world[3]) - camera_.position(), camera_.forward());
      pathIndex = uint32_t(out.paths.size());
      out.paths.push_back(p);
    }
    const glm::dvec3 grad = hasTriangles ? out.paths[pathIndex].depthGrad : glm::dvec3(0.0);
    const double offset = hasTriangles ? out.paths[pathIndex].depthOffset : 0.0;
    std::vector<uint32_t> instances;
    const Frustum local = hasTriangles ? frustumToNodeSpace(frustum_, world) : Frustum{};
    a.octree().cullFrustum(frustum_, world, [&](uint32_t leaf, Cull cull) {
      // The leaf's content box, tighter than its cube, decides (cube inside: content inside).
      if (hasTriangles && !a.leafTriangles(leaf).empty() &&
          (cull == Cull::kInside || local.classify(a.contentBox(leaf)) != Cull::kOutside)) {
        const Bounds& b = a.contentBox(leaf);
        const glm::dvec3 c = b.center(), h = 0.5 * b.extent();
        const double mid = glm::dot(grad, c) + offset;
        const double reach = glm::dot(glm::abs(grad), h);
        out.leaves.push_back({pathIndex, leaf, mid - reach, mid + reach});
      }
      for (uint32_t i : a.leafInstances(leaf)) instances.push_back(i);
    });
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
      visit(inst.node, childWorld, idBase + scene_.childOffset(node, i), out);
    }
  }

 private:
  const LzbAccel& accel_;
  const Scene& scene_;
  const Camera& camera_;
  Frustum frustum_;
};

}  // namespace

void cullScene(const LzbAccel& accel, const Camera& camera, CulledScene& out) {
  out.paths.clear();
  out.leaves.clear();
  out.instancesVisited = 0;
  Culler(accel, camera).visit(accel.scene().root, glm::dmat4(1.0), 0, out);
}

CulledScene cullScene(const LzbAccel& accel, const Camera& camera) {
  CulledScene out;
  cullScene(accel, camera, out);
  return out;
}

}  // namespace lzb
