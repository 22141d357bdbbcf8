#include "src/hybrid/screen_cover.hpp"

#include <algorithm>
#include <vector>

namespace lzb::hybrid {

namespace {

// A box at most this many pixels wide and high on screen (its rounding margin included) is
// marked whole rather than walked further: on the city's distant frames at 1080p, 8 pixels
// visited 7-13 K nodes (1.0-1.9 ms), 32 pixels 1.8-4.8 K (0.26-0.9 ms) for 3-5 % more blocks.
constexpr int kMarkPixels = 32;

bool small(const TileRect& r) { return r.x1 - r.x0 <= kMarkPixels && r.y1 - r.y0 <= kMarkPixels; }

class CoverWalk {
 public:
  CoverWalk(const localz::LzbAccel& accel, const Camera& camera, uint64_t budget)
      : accel_(accel), camera_(camera), budget_(budget), cover_(camera.width(), camera.height()) {}

  // Marks what scene node `node`, placed by `world`, holds; false once over the budget.
  bool node(uint32_t node, const glm::dmat4& world) {
    const localz::NodeAccel& a = accel_.node(node);
    if (a.empty()) return true;
    const Scene& scene = accel_.scene();
    const CameraPlacement placed(camera_, world);
    // Content boxes hold triangles only: a node with instances prunes by the octree's cubes.
    const bool trianglesOnly = scene.nodes[node].instances.empty();
    std::vector<uint32_t> instances;
    if (!octant(a, trianglesOnly, 0, placed, instances)) return false;
    // An instance is listed by every leaf its box overlaps: walk it once.
    std::sort(instances.begin(), instances.end());
    instances.erase(std::unique(instances.begin(), instances.end()), instances.end());
    for (uint32_t i : instances) {
      if (!a.instanceUsable(i)) continue;  // Embree holds nothing there either
      if (++visited_ > budget_) return false;
      const TileRect r = pixelsUnder(a.instanceBox(i), placed, camera_);
      if (cover_.allIn(r)) continue;
      if (small(r)) {
        if (!mark(r)) return false;
        continue;
      }
      const Instance& inst = scene.nodes[node].instances[i];
      if (!this->node(inst.node, world * inst.transform)) return false;
    }
    return true;
  }

  BlockCover& cover() { return cover_; }

 private:
  // Adds r; false (the walk stops: no cover) when r is the whole frame, where a cover would
  // save nothing.
  bool mark(const TileRect& r) {
    if (r.x0 == 0 && r.y0 == 0 && r.x1 == camera_.width() && r.y1 == camera_.height()) return false;
    cover_.add(r);
    return true;
  }

  bool octant(const localz::NodeAccel& a, bool trianglesOnly, uint32_t o,
              const CameraPlacement& placed, std::vector<uint32_t>& instances) {
    if (++visited_ > budget_) return false;
    const Bounds& box = trianglesOnly ? a.contentBox(o) : a.octree().nodeBox(o);
    const TileRect r = pixelsUnder(box, placed, camera_);
    if (cover_.allIn(r)) return true;  // nothing there, or marked already
    if (small(r)) return mark(r);  // the cube holds all its leaves hold: triangles, instance parts
    const Octree::Node& n = a.octree().node(o);
    if (!n.leaf()) {
      for (uint32_t c = 0; c < 8; ++c)
        if (!octant(a, trianglesOnly, n.firstChild + c, placed, instances)) return false;
      return true;
    }
    if (!a.leafTriangles(o).empty() &&
        !mark(trianglesOnly ? r : pixelsUnder(a.contentBox(o), placed, camera_)))
      return false;
    for (uint32_t i : a.leafInstances(o)) instances.push_back(i);
    return true;
  }

  const localz::LzbAccel& accel_;
  const Camera& camera_;
  uint64_t budget_, visited_ = 0;
  BlockCover cover_;
};

}  // namespace

std::optional<BlockCover> screenCover(const localz::LzbAccel& accel, const Camera& camera,
                                      uint64_t budget) {
  CoverWalk walk(accel, camera, budget);
  if (!walk.node(accel.scene().root, glm::dmat4(1.0))) return std::nullopt;
  return std::move(walk.cover());
}

}  // namespace lzb::hybrid
