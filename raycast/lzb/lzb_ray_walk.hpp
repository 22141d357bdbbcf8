#pragma once
// PVL finding (paper, sections III.A-B, D): one ray walks the octrees of the instanced scene
// front to back, tests triangles of the leaves it traverses until its visibility is resolved,
// and records every traversed leaf that holds triangles; the PVL is the union of those leaves'
// triangles. A leaf counts as traversed when the ray crosses its content box (the part of the
// leaf cube its triangles occupy, NodeAccel::contentBox): a ray through the empty rest of the
// cube cannot hit any of them there.
//
// What a ray records (its local list): a ray that hits records every leaf it traversed up to
// the hit that resolved it (the paper: "all the primitives associative the leaves traversed by
// r and current leaf"). A ray that finds no hit at all shows nothing, so only the leaves it
// could not clear are needed: those whose triangles were not all tested (occluder selection) or
// that it missed by less than 0.05 pixel (the z-buffer rasterizes in fixed point and may still
// cover the pixel centre). This keeps empty pixels between objects from filling the PVL.
//
// The walk is exact for the PVL, whatever the occluder selection: with tBest the nearest hit
// found so far (a real triangle at that depth, so the visible one is no farther), the walk goes
// on through every leaf entered at t <= tBest. The visible hit point p (at t* <= tBest) lies in
// the content box of a leaf listing its triangle, which the ray enters at t <= t*, so that leaf
// is traversed and its triangles - the visible one among them - are recorded. Occluder selection
// only decides how soon tBest gets small.
//
// Leaf tests (LeafTest):
//   kAll      (lazy)     every triangle of the leaf until the first hit;
//   kStatic   (Octree-o) only the leaf's K largest triangles;
//   kDynamic             triangles (largest first) whose visibility -v.n.area (v: the ray
//                        direction in the node frame, unit; n.area: area-weighted normal)
//                        exceeds the leaf's base visibility (0.5 x mean triangle area of the
//                        leaf); triangles smaller than that can never pass and are not listed;
//   kHybrid              the K static occluders, filtered by the same visibility test.
//
// Instances: a leaf's instance entries whose box (parent frame) the ray crosses start a walk of
// the child node's octree with the ray carried into the child frame in double (affine, so t is
// unchanged), once per ray and path.
// All octrees of one ray share one priority queue on entry t, so leaves are processed front to
// back across instances and the walk stops as soon as the next entry lies beyond tBest.
//
// Octree walks (OctreeWalk):
//   kTopDown   best-first from each octree's root: inner nodes push their children clipped to
//              the ray (what Octree::traverseRay does);
//   kCoherent  the start leaf is located from the previous ray's start leaf in the same octree
//              (climbing parent links only until the box claims the entry point), then the ray
//              steps leaf to leaf through the exit face's rope (OctreeRopes); inner nodes are
//              touched only when a rope leads to a larger neighbour.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <unordered_map>
#include <vector>

#include "raycast/lzb/lzb_accel.hpp"
#include "raycast/lzb/lzb_leaf_filter.hpp"
#include "raycast/lzb/lzb_options.hpp"
#include "src/octree/octree.hpp"

namespace lzb::localz {

enum class LeafTest { kAll, kStatic, kDynamic, kHybrid };

// A ray passing a triangle by less than this many pixels (at the hit plane) may still see it in
// the z-buffer, which rasterizes in fixed point: the walk's near misses, and the radius around
// an Embree hit whose leaves the PVL takes (lzb_hit_leaves.hpp).
constexpr double kNearMissPixels = 0.05;

// A ray set up for slab tests against closed boxes. A direction component whose reciprocal is
// not finite (zero or subnormal) is treated as zero: containment on that axis instead of a
// division, so no 0 * inf NaN (over any finite t the ray moves less than 1e-290 along it).
struct WalkRay {
  glm::dvec3 o, d, inv;
  bool flat[3];
  bool anyFlat;
  uint8_t neg[3];  // 1 where d < 0: the slab is entered through hi
  WalkRay() = default;
  WalkRay(const glm::dvec3& origin, const glm::dvec3& dir) : o(origin), d(dir) {
    anyFlat = false;
    for (int k = 0; k < 3; ++k) {
      inv[k] = 1.0 / d[k];
      flat[k] = !std::isfinite(inv[k]);
      if (flat[k]) inv[k] = 0.0;
      anyFlat |= flat[k];
      neg[k] = d[k] < 0.0 ? 1 : 0;
    }
  }
  // Narrows [t0, t1] to the part inside the closed box; false when nothing is left.
  [[gnu::always_inline]] bool clip(const Bounds& b, double& t0, double& t1) const {
    double a = t0, c = t1;
    for (int k = 0; k < 3; ++k) {
      if (anyFlat && flat[k]) {
        if (o[k] < b.lo[k] || o[k] > b.hi[k]) return false;
        continue;
      }
      const double enter = ((neg[k] ? b.hi[k] : b.lo[k]) - o[k]) * inv[k];
      const double exit = ((neg[k] ? b.lo[k] : b.hi[k]) - o[k]) * inv[k];
      a = enter > a ? enter : a;
      c = exit < c ? exit : c;
    }
    t0 = a;
    t1 = c;
    return a <= c;
  }
  // t where the ray leaves the box through the face of axis k (not flat).
  double exitAt(const Bounds& b, int k) const {
    return ((d[k] > 0.0 ? b.hi[k] : b.lo[k]) - o[k]) * inv[k];
  }
};

LeafTest leafTestFor(const LzbOptions& options);

struct RayWalkCounts {
  uint64_t rays = 0;
  uint64_t nodesVisited = 0;     // octree nodes popped or stepped through (all octrees)
  uint64_t leavesVisited = 0;    // of those, leaves
  uint64_t triangleTests = 0;    // ray-triangle intersection tests
  uint64_t visibilityTests = 0;  // dynamic visibility evaluations
  uint64_t instanceWalks = 0;    // child octree walks started
  uint64_t climbs = 0;           // coherent start: parent links climbed
  uint64_t contentMisses = 0;    // traversed leaves whose content box the ray misses
  uint64_t hits = 0;             // rays whose walk found a hit
  void add(const RayWalkCounts& o);
};

// One recorded leaf: triangles of leaf `leaf` of node `node` placed at expanded ID base idBase
// (the base names the placement: only nodes with triangles record leaves).
struct PvlLeaf {
  uint64_t idBase;
  uint32_t node;
  uint32_t leaf;
  bool operator<(const PvlLeaf& o) const {
    return idBase < o.idBase || (idBase == o.idBase && leaf < o.leaf);
  }
  bool operator==(const PvlLeaf& o) const { return idBase == o.idBase && leaf == o.leaf; }
};

struct PvlPlacement {
  uint64_t idBase;
  uint32_t node;
  glm::dmat4 world;  // node frame -> world
};

// The PVL part of a set of rays (a screen tile): recorded leaves and their placements.
struct PvlPart {
  std::vector<PvlLeaf> leaves;           // sorted and unique after finish()
  std::vector<PvlPlacement> placements;  // one per idBase, sorted by idBase after finish()
  void finish();
  void clear();
  // Index of the placement with this idBase (-1 if none).
  std::unordered_map<uint64_t, uint32_t> index;
};

class RayWalker {
 public:
  RayWalker(const LzbAccel& accel, LeafTest test, OctreeWalk walk);

  // Forgets the coherence state (start leaves): call at the start of every tile, so a tile's
  // result does not depend on which tiles the same thread walked before.
  void resetCoherence();
  // Camera rays (t is the view depth): pixels per unit length at view depth 1. With it set, a
  // ray that finds no hit records only the leaves it could not clear (see the top); 0 (the
  // default) records every traversed leaf of every ray.
  void setPixelScale(double pixelsPerUnitAtDepth1) { pixelScale_ = pixelsPerUnitAtDepth1; }
  // Leaves another pass draws (null: none): their triangles are not tested. eye and forward are
  // the camera's, for the leaves' placements.
  void setLeafFilter(const LeafFilter* filter, const glm::dvec3& eye, const glm::dvec3& forward) {
    filter_ = filter;
    eye_ = eye;
    forward_ = forward;
  }
  // Walks the world-space ray origin + t dir, t in [tMin, tMax]; records traversed leaves into
  // out. Returns the nearest hit found (+inf for none: the ray saw nothing behind tMin).
  double cast(const glm::dvec3& origin, const glm::dvec3& dir, double tMin, double tMax,
              PvlPart& out);

  // Diagnostic: the number of distinct triangles the ray intersects in [tMin, tMax] (every
  // leaf walked, every triangle tested): the depth complexity along it. Counts nothing.
  uint64_t countSurfaces(const glm::dvec3& origin, const glm::dvec3& dir, double tMin, double tMax);

  RayWalkCounts counts;

 private:
  // One octree walk of the ray: a (node, instance path) with the ray in the node's frame.
  struct Context {
    uint32_t node;
    uint64_t idBase;
    uint32_t parent;    // context of the parent node (kNone for the root)
    uint32_t instance;  // instance index in the parent node
    WalkRay ray;
    glm::vec3 unitDir;  // for the visibility measure
    int32_t placement;  // index in the PvlPart, -1 until the first record
    bool coherent;      // rope stepping (false: top-down, also the fallback)
    uint32_t steps;     // rope steps so far (a bound guards against float trouble)
    // With a leaf filter only, computed on first use: the placement, and whether the filter
    // takes all of the node's triangles (0: not asked yet, 1: yes, 2: no).
    bool leafPlaced = false;
    uint8_t wholeNode = 0;
    LeafPlacement leafPlacement{};
  };
  struct Item {
    double tEnter, tExit;
    uint32_t ctx, node;
  };
  void enter(uint32_t ctx, double t0, double t1);
  void processLeaf(uint32_t ctx, uint32_t leaf, PvlPart& out);
  void record(uint32_t ctx, uint32_t leaf, PvlPart& out);
  // Node frame -> world of a context: the instance transforms composed root first.
  glm::dmat4 contextWorld(uint32_t ctx) const;
  const LeafPlacement& placementOf(uint32_t ctx);
  bool drawnElsewhere(uint32_t ctx, uint32_t leaf);
  // With a filter: whether instance i of context ctx's node leads to a node that has no instances
  // and whose triangles the filter takes all of (its walk is then skipped).
  bool instanceDrawnElsewhere(uint32_t ctx, uint32_t i);
  void flush(PvlPart& out);  // end of a ray: its traversed leaves into out
  // Coherent: the next non-empty leaf along the ray into `next` (false: none before the limit,
  // or the walk fell back to top-down and queued its root).
  bool step(const Item& item, Item& next);
  static bool later(const Item& a, const Item& b);  // queue order: (tEnter, ctx, node)
  void push(const Item& item);
  Item pop();

  const LzbAccel& accel_;
  LeafTest test_;
  OctreeWalk walk_;
  std::vector<Context> ctx_;
  std::vector<Item> heap_;
  std::vector<uint32_t> hint_;                 // per scene node: the last start leaf (kNone: none)
  std::vector<uint32_t> stampRay_, stampCtx_;  // per instance slot: expanded by (ray, ctx)
  uint32_t rayNumber_ = 0;
  struct RayLeaf {
    uint32_t ctx, leaf;
    bool clearMiss;  // every triangle tested, none hit or nearly hit
  };
  std::vector<RayLeaf> rayLeaves_;  // the current ray's traversed leaves
  double pixelScale_ = 0.0;
  const LeafFilter* filter_ = nullptr;
  glm::dvec3 eye_{0.0}, forward_{0.0, 0.0, -1.0};
  bool countAll_ = false;           // countSurfaces in progress
  std::vector<uint64_t> surfaces_;  // its hits (expanded IDs)
  double tMin_ = 0.0, tMax_ = 0.0, tBest_ = std::numeric_limits<double>::infinity();
};

}  // namespace lzb::localz
