#pragma once
// PVL finding by Embree (--lzb-rays embree): which rays are cast (the unfinished pixels, OOR) and
// what is drawn (the PVL by z-buffer) stay local z-buffering's; only the traversal is Embree's.
//
// What a ray records: nothing when Embree finds no hit; else, in the hit triangle's placement,
// every octree leaf with triangles whose content box comes within kNearMissPixels (plus float
// slack) of the hit point. Why this is what the PVL needs at the pixel: the z-buffer rasterizes
// in fixed point, so the pixel centre may belong to a triangle next to the hit one (a neighbour
// across an edge passing within a snapping error of the centre, or a coincident duplicate);
// every triangle with a point within that radius of the hit point lies in such a leaf (a leaf
// lists every triangle overlapping its closed box, and its content box holds the triangles' part
// in the leaf). The hit triangle is among them, so every ray-cast pixel's exact hit is in the PVL.
// Unlike the walk, leaves the ray only passes through in front of the hit are not recorded: a
// triangle there that the ray misses by less than a snapping error, which the z-buffer would
// show instead, is drawn only if some other ray recorded it (the PVL is rasterized at every
// unfinished pixel); the measured effect is in raycast/lzb/README.md.
//
// Placements: an expanded ID names its instance path (Scene::resolve, composed root first as the
// cull composes it, so PVL and near-pass placements agree bit for bit). A few recent placements
// are kept with their inverse maps, so neighbouring rays on one mesh resolve once.
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "raycast/exact/embree_scene.hpp"
#include "raycast/lzb/lzb_accel.hpp"
#include "raycast/lzb/lzb_ray_walk.hpp"
#include "src/core/affine.hpp"

namespace lzb::localz {

struct HitLeafCounts {
  uint64_t rays = 0;
  uint64_t hits = 0;
  uint64_t nodesVisited = 0;    // octree nodes whose box the query box was tested against
  uint64_t leavesRecorded = 0;  // leaves recorded (before the part's dedup)
  uint64_t resolves = 0;        // IDs resolved to a placement (cache misses)
  void add(const HitLeafCounts& o);
};

class HitLeafRecorder {
 public:
  explicit HitLeafRecorder(const LzbAccel& accel);

  // Camera rays (t is the view depth): pixels per unit length at view depth 1.
  void setPixelScale(double pixelsPerUnitAtDepth1) { pixelScale_ = pixelsPerUnitAtDepth1; }
  // A new part (screen tile) starts: placement indices into the previous part are forgotten.
  void beginPart();
  // The leaves around the hit of the ray origin + t dir into out (nothing for a miss).
  void record(const glm::dvec3& origin, const glm::dvec3& dir, const RayHit& hit, PvlPart& out);

  HitLeafCounts counts;

 private:
  // One resolved placement: its expanded IDs [base, end) and maps.
  struct Placed {
    uint64_t base = 1, end = 0;  // empty until filled
    uint32_t node = 0;
    glm::dmat4 world{1.0};     // node frame -> world
    Affine toNode;             // world -> node frame
    glm::dvec3 spread{0.0};    // node-frame half extents of a unit world cube
    uint32_t partSerial = 0;   // the last part it was listed in
  };
  Placed& placed(uint64_t id);
  void collect(Placed& p, const Bounds& query, PvlPart& out);
  void recordLeaf(Placed& p, uint32_t leaf, PvlPart& out);

  const LzbAccel& accel_;
  double pixelScale_ = 0.0;
  static constexpr int kCache = 8;
  std::array<Placed, kCache> cache_;
  int next_ = 0;                  // cache slot to replace next
  uint32_t partSerial_ = 1;
  std::vector<uint32_t> hint_;    // per scene node: the last leaf recorded (a shortcut only)
  std::vector<uint32_t> stack_;
};

}  // namespace lzb::localz
