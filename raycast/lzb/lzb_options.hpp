#pragma once
// Settings of --method lzb (local z-buffering, Han & Zeiger; see raycast/lzb/README.md): which
// stage of the paper's pipeline handles the far scene, how the partition plane is placed, and the
// local occluders of the selective stages.
#include <cstdint>
#include <string>

#include "mpi/decomposition.hpp"

namespace lzb::localz {

// The far-scene stage; each includes the ones above it (naive is the exception: it has no PVL).
enum class LzbStage {
  kNaive,      // classic ray casting (Embree) of the unfinished pixels
  kLazy,       // own octree walk to the first hit -> potentially visible list (PVL) -> z-buffer
  kSelective,  // lazy with local occluders (Octree-o static / dynamic visibility / hybrid)
  kOor,        // selective, rays only from pixels inside projected far octree leaves
  kFinal,      // oor with the coherent (rope) ray-octree walk instead of top-down
};

enum class OccluderMode { kStatic, kDynamic, kHybrid };

// How a ray walks an octree: best-first from the root, or leaf to leaf along neighbour links
// starting from the previous ray's start leaf (see lzb_ray_walk.hpp).
enum class OctreeWalk { kTopDown, kCoherent };

// Which z-buffer draws a pass (near scene, PVL): the project's native multithreaded z-buffer
// (src/zbuffer/native_raster.hpp; the PVL only at the unfinished pixels), or OSMesa.
enum class ZBufferKind { kNative, kGl };

// Who casts the far rays of the PVL stages: Embree, each hit recorded as the octree leaves around
// its hit point (lzb_hit_leaves.hpp), or the paper's own octree walk (lzb_ray_walk.hpp).
enum class FarRays { kEmbree, kWalk };

struct LzbOptions {
  LzbStage stage = LzbStage::kFinal;
  double planeFraction = 0.0;  // 0: dynamic plane (coarse ray casting); else static, in (0, 1)
  bool costPlane = true;       // dynamic: the cost-model plane (default) instead of the mean
  int planeGrid = 32;          // coarse rays: planeGrid x planeGrid uniform pixel grid
  int planeReuse = 8;          // frames a dynamic plane may be reused (0: recompute every frame)
  int occluders = 5;           // K static local occluders per leaf (the paper's setting)
  OccluderMode occluderMode = OccluderMode::kDynamic;  // smallest PVL measured (README.md)
  int leafEntries = 150;        // octree leaf limit for nodes with triangles (the paper's)
  int instanceLeafEntries = 8;  // leaf limit for nodes with more instances than triangles
  bool walkOverride = false;    // use `walk` instead of the stage's own octree walk
  OctreeWalk walk = OctreeWalk::kCoherent;
  ZBufferKind nearRender = ZBufferKind::kNative;  // faster on the paper experiment (README.md)
  ZBufferKind pvlRender = ZBufferKind::kNative;   // faster on the paper experiment (README.md)
  int depthComplexityGrid = 0;  // diagnostic: G x G rays count every surface (0: off)
  FarRays farRays = FarRays::kEmbree;  // faster on the paper experiment (README.md)
  TileDeal tileDeal = TileDeal::kInterleaved;  // how the far rays' tiles go to ranks

  bool dynamicPlane() const { return planeFraction == 0.0; }
  bool usesPvl() const { return stage != LzbStage::kNaive; }
  bool usesOccluders() const { return stage >= LzbStage::kSelective; }
  // The PVL is found by the octree walk (occluders and the octree walk matter only then).
  bool usesWalk() const { return usesPvl() && farRays == FarRays::kWalk; }
  bool usesOor() const { return stage >= LzbStage::kOor; }
  OctreeWalk octreeWalk() const {
    if (walkOverride) return walk;
    return stage == LzbStage::kFinal ? OctreeWalk::kCoherent : OctreeWalk::kTopDown;
  }
};

// Parsing and names (parse* throw InputError naming `field` on an unknown value).
LzbStage parseLzbStage(const std::string& text, const std::string& field);
OccluderMode parseOccluderMode(const std::string& text, const std::string& field);
OctreeWalk parseOctreeWalk(const std::string& text, const std::string& field);
ZBufferKind parseZBufferKind(const std::string& text, const std::string& field);
FarRays parseFarRays(const std::string& text, const std::string& field);
// --plane: "auto" (dynamic, mean depth), "cost" (dynamic, cost model) or a fraction in (0, 1)
// (static); sets planeFraction and costPlane.
void parsePlane(const std::string& text, const std::string& field, LzbOptions& options);
std::string toString(LzbStage stage);
std::string toString(OccluderMode mode);
std::string toString(OctreeWalk walk);
std::string toString(ZBufferKind kind);
std::string toString(FarRays rays);

// Throws InputError naming the option (CLI spelling) for an out-of-range value.
void validate(const LzbOptions& options);

}  // namespace lzb::localz
