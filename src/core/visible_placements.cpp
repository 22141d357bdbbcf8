#include "src/core/visible_placements.hpp"

namespace lzb {

namespace {

struct Walk {
  const Scene& scene;
  const std::vector<Bounds>& meshBounds;
  const Frustum& frustum;
  const PlacementVisitor& visit;

  void node(uint32_t index, const glm::dmat4& world, uint64_t idBase) const {
    if (frustum.classify(scene.nodeBounds[index].transformed(world)) == Cull::kOutside) return;
    const Node& n = scene.nodes[index];
    if (!n.mesh.empty()) {
      const Bounds b = meshBounds[index].transformed(world);
      if (frustum.classify(b) != Cull::kOutside) visit(index, world, idBase, b);
    }
    for (size_t i = 0; i < n.instances.size(); ++i)
      node(n.instances[i].node, world * n.instances[i].transform,
           idBase + scene.childOffset(index, i));
  }
};

}  // namespace

void forEachVisiblePlacement(const Scene& scene, const std::vector<Bounds>& meshBounds,
                             const Frustum& frustum, const PlacementVisitor& visit) {
  Walk{scene, meshBounds, frustum, visit}.node(scene.root, glm::dmat4(1.0), 0);
}

}  // namespace lzb
