#pragma once
// LZB step 1: hierarchical view-frustum culling on the octrees of the instanced scene graph. Each
// node's octree is culled in the node's frame; instance entries of the surviving leaves lead into
// the child's octree (each instance once per path). The result lists every non-empty leaf with
// triangles in the frustum (its content box, NodeAccel::contentBox, tested), with the view-depth
// range of that box, so that the partition plane can split it into the near scene (z-buffer) and
// the far scene (rays, OOR objects) afterwards.
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <vector>

#include "raycast/lzb/lzb_accel.hpp"
#include "raycast/lzb/lzb_leaf_filter.hpp"
#include "src/core/camera.hpp"

namespace lzb::localz {

// A (node, instance path) placement reached by the culling walk.
struct CullPath {
  uint32_t node = 0;
  glm::dmat4 world{1.0};  // node frame -> world
  uint64_t idBase = 0;    // expanded ID of the node's triangle 0 at this place
  // View depth of a node-frame point p: dot(depthGrad, p) + depthOffset (affine in p).
  glm::dvec3 depthGrad{0.0};
  double depthOffset = 0.0;
  // A filter (LeafFilter::nodeDrawnElsewhere) took all of its triangles: no leaf is listed.
  bool drawnElsewhere = false;
  // LeafFilter::subtreeDrawnElsewhere took the node and everything it instances: nothing below
  // it is listed (the path may name a node without triangles).
  bool subtree = false;
  // Its leaves: CulledScene::leaves[firstLeaf, firstLeaf + leafCount), their triangles and the
  // nearest of their depthMin (infinite without leaves).
  uint32_t firstLeaf = 0, leafCount = 0;
  uint64_t leafTriangles = 0;
  double leafDepthMin = std::numeric_limits<double>::infinity();
};

struct CullLeaf {
  uint32_t path;              // index into CulledScene::paths
  uint32_t leaf;              // octree node index (a leaf with triangles)
  double depthMin, depthMax;  // view-depth range of the leaf's content box
};

struct CulledScene {
  std::vector<CullPath> paths;   // in ascending idBase order (depth-first, instances in order)
  std::vector<CullLeaf> leaves;  // grouped by path, in path order
  uint64_t instancesVisited = 0;
  // The parallel walk's part per root instance, kept so that their memory serves the next frame.
  std::vector<CulledScene> parts;
};

// Visible-instance limit: past it the scene is too instanced for a per-leaf cull (throws
// InputError; the ray casting and sampling methods handle such scenes).
constexpr size_t kMaxCullPaths = size_t(1) << 22;
// Visible-leaf limit (24 bytes a leaf: 400 MB), for the same reason.
constexpr size_t kMaxCullLeaves = size_t(1) << 24;

// The root's visible instances are culled on `threads` threads; the result does not depend on it.
// With a filter, a placement whose triangles the filter takes wholly is listed with
// drawnElsewhere set and none of its leaves (its instances are walked as usual); a placement
// whose whole subtree the filter takes is listed with subtree set too, and not walked into.
CulledScene cullScene(const LzbAccel& accel, const Camera& camera, int threads = 1,
                      const LeafFilter* filter = nullptr);
// The same into `out` (cleared first), reusing its memory frame after frame. With farDepth
// nearer than the camera's far plane, the frustum ends there: every leaf whose content box is
// not wholly beyond that view depth is listed, as the whole cull lists it.
// With a triangle budget, the walk stops listing placements once the listed leaves hold that
// many triangles: the result is then incomplete and holds at least the budget (a probe that
// only asks whether that many lie in front of a depth).
void cullScene(const LzbAccel& accel, const Camera& camera, CulledScene& out, int threads = 1,
               const LeafFilter* filter = nullptr,
               double farDepth = std::numeric_limits<double>::infinity(),
               uint64_t triangleBudget = std::numeric_limits<uint64_t>::max());

}  // namespace lzb::localz
