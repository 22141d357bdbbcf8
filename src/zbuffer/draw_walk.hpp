#pragma once
// The z-buffer's traversal of the scene graph: the draw items of lzb::flattenScene in the same
// expanded-ID order, with hierarchical frustum culling (a node's subtree is skipped when its
// transformed bounds are outside, and not tested further when inside) and a restriction to one
// rank's contiguous ID range (a draw item on the range's edge is drawn in part).
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "src/core/bounds.hpp"
#include "src/core/camera.hpp"
#include "src/core/scene.hpp"
#include "mpi/decomposition.hpp"

namespace lzb {

// Triangles [first, first + count) of node's mesh placed by world; triangle first has ID firstId.
struct DrawCall {
  uint32_t node;
  glm::dmat4 world;
  uint64_t first, count, firstId;
};

struct WalkCounts {
  uint64_t items = 0;      // draw items with triangles in the range
  uint64_t culled = 0;     // of those, outside the frustum
  uint64_t triangles = 0;  // triangles handed to draw
};

class DrawWalk {
 public:
  // Precomputes per-node mesh bounds and draw-item counts; scene: finalized, outlives this.
  explicit DrawWalk(const Scene& scene);
  // Calls draw for the visible part of every draw item in range, in ascending ID order.
  WalkCounts walk(const Frustum& frustum, const IdRange& range,
                  const std::function<void(const DrawCall&)>& draw) const;

 private:
  struct Pass;
  const Scene& scene_;
  std::vector<Bounds> meshBounds_;   // per node: its own triangles only
  std::vector<uint64_t> itemCount_;  // per node: draw items in its expanded subtree (saturating)
};

}  // namespace lzb
