#pragma once
// An Embree 3 view of a lzb::Scene for exact ray casting, built once and reused by every pass
// that casts rays (the raycast reference, coarse rays for the partition plane, far-scene rays).
//
// Instancing of any depth without flattening: one Embree scene per lzb node (see
// embree_level.hpp), so memory follows the unique scene even for 10^12 expanded triangles.
//
// Precision: each node's Embree scene lives in the node's frame shifted by the centre of its
// bounds (shift computed in double), and rays are carried in double through the instance levels
// (double transforms); a ray is rounded to float only in the frame of the node whose BVH it is
// traversing. A scene placed 1e7 from the origin, or a wide one seen close up, traces as
// precisely as a small one at the origin, and no camera change rebuilds anything.
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "src/core/scene.hpp"

namespace lzb {

struct FrameStats;
struct RenderOptions;

struct Ray {
  glm::dvec3 origin{0.0};
  glm::dvec3 dir{0.0, 0.0, -1.0};
  double tnear = 0.0;
  double tfar = std::numeric_limits<double>::infinity();
};

struct RayHit {
  float t = std::numeric_limits<float>::infinity();  // origin + t * dir is the hit point
  uint64_t id = kNoId;                               // expanded triangle ID
  bool hit() const { return id != kNoId; }
};

struct EmbreeSceneOptions {
  int threads = 1;  // Embree's build threads
  // RTC_BUILD_QUALITY_HIGH for the node BVHs. Under RTC_SCENE_FLAG_ROBUST, Embree 3.13 builds
  // the same BVH8<triangle4v> by its SAH builder at HIGH and MEDIUM (its verbose log; no spatial
  // splits), so this changes nothing but the build's own bookkeeping.
  bool highQuality = true;
  // RTC_SCENE_FLAG_COMPACT (`--bvh compact`): leaves that index the vertices, still the robust
  // test; the same IDs, about half of raycast's memory, its rays 1.45-1.6x slower.
  bool compactLeaves = false;
  // Extra Embree device configuration ("key=value,...", e.g. "tri_accel=bvh8.triangle4i"), for
  // the leaf-layout benchmark (runs/memory/leaves.py); empty for every method.
  std::string deviceConfig;
};

struct EmbreeBuildStats {
  double seconds = 0.0;
  uint64_t levels = 0;            // Embree scenes: one per node reached
  uint64_t triangles = 0;         // triangles given to Embree (each unique triangle once)
  uint64_t instances = 0;         // lzb instances, each one user-geometry primitive
  uint64_t skippedInstances = 0;  // singular or non-finite transforms (nothing to hit)
  // What Embree allocated (its memory monitor: BVHs, leaves, the vertex copies; not the shared
  // index buffers): held after the build, and at most during it (the build's primitive
  // references on top of the growing BVH).
  uint64_t bytes = 0;
  uint64_t peakBytes = 0;
};

// `base` with what a render's options decide: the build threads, and compact leaves under
// `--bvh compact` (every Embree scene a render builds: the methods' and the witness's).
EmbreeSceneOptions withRenderOptions(EmbreeSceneOptions base, const RenderOptions& options);

// The build's set-up figures of a method that holds an EmbreeScene: Embree's held and peak bytes
// (counts: per rank in the report, summed over a rank's regions).
void addEmbreeMemory(const EmbreeBuildStats& build, FrameStats& stats);

class EmbreeScene {
 public:
  // Builds every node's BVH; the scene must be finalized and outlive this object.
  EmbreeScene(const Scene& scene, const EmbreeSceneOptions& options);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // The nearest hit with tnear <= t <= tfar (bounds rounded outwards to float). Thread-safe.
  RayHit intersect(const glm::dvec3& origin, const glm::dvec3& dir, double tnear,
                   double tfar) const;
  // Many rays at once (hits.size() == rays.size()), as packets of packetWidth() consecutive
  // rays through Embree's packet traversal (down through every instance level): order rays so
  // that packets are coherent (one camera, 4x4 pixel blocks). Same hits as one at a time.
  // Thread-safe.
  void intersect(std::span<const Ray> rays, std::span<RayHit> hits) const;
  int packetWidth() const;  // 16, 8, 4 (what the CPU runs natively) or 1
  // The world box of what the scene holds (Embree's bounds of the root level, not the node box,
  // which a scene part keeps at the whole scene's); empty when it holds nothing.
  Bounds heldBounds() const;

  const EmbreeBuildStats& buildStats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lzb
