#pragma once
// Internal to EmbreeScene: one RTCScene per lzb node, and instancing of any depth on an Embree
// built with RTC_MAX_INSTANCE_LEVEL_COUNT == 1 (Debian's).
//
// A Level is the RTCScene of one lzb node, in the node's frame shifted by the centre of the
// node's bounds (so float coordinates stay small): the node's own triangles are attached
// directly, and its instances are the primitives of one user geometry. A primitive's intersect
// callback moves the ray into the child's frame and calls rtcIntersect on the child's Level with
// a fresh context, so Embree never sees more than one level at a time and the nesting depth is
// unbounded. Memory grows with the unique scene: one Level per node, one primitive per Instance.
//
// Precision: the context carries each ray in double next to Embree's float copy, and the
// callback maps the double ray with the double transform; a ray becomes float only in the frame
// of the Level being traversed, where coordinates are relative to that node's centre. So a
// scene far from the origin, or a wide one seen close up, traces as precisely as a small one at
// the origin, with no per-camera rebuild.
//
// Expanded IDs: a hit on the node's own triangles is its primID; a hit on an instance is
// Scene::childOffset plus the ID found below.
//
// Ties: every query keeps the least (t, expanded ID), as the depth composite's key does, so a
// ray that meets two triangles at the same t (a shared edge, two faces crossing, a coplanar
// overlap) names the same one whatever the BVH, its traversal order or the split of the scene
// across ranks. A context filter orders the node's own triangles (Embree presents every
// candidate at t <= tfar to it, also the others of the same leaf); the instance callback orders
// what comes from below. Only barycentrics at an edge would not do: most ties measured on the
// landscape lie where two faces cross, inside one of them.
#include <embree3/rtcore.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "src/core/depth_key.hpp"

namespace lzb::embree {

constexpr uint64_t kMiss = ~uint64_t(0);

struct Level;

// One lzb Instance as a user-geometry primitive.
struct UserChild {
  const Level* child = nullptr;
  glm::dmat4x3 toChild{1.0};  // parent Level frame -> child Level frame
  float lower[3], upper[3];   // the child's bounds in the parent Level frame, padded outwards
  uint64_t offset = 0;        // Scene::childOffset of this instance
  bool translationOnly = false;  // toChild's linear part is the identity
};

struct Level {
  RTCScene scene = nullptr;
  unsigned meshGeom = RTC_INVALID_GEOMETRY_ID;  // the node's own triangles
  unsigned userGeom = RTC_INVALID_GEOMETRY_ID;  // one primitive per entry of userChildren
  std::vector<UserChild> userChildren;
};

// A ray in double in some Level's frame.
struct DoubleRay {
  glm::dvec3 org, dir;
};

// The context of every rtcIntersect call on a Level; Embree hands it to the filter and the
// callbacks, which find a lane's entries through RTCRay::id.
struct IdContext {
  RTCIntersectContext ctx;  // first member: Embree sees a plain RTCIntersectContext
  const DoubleRay* rays;    // per ray id: the ray in the Level's frame
  uint64_t* ids;            // per ray id: the expanded ID of the hit kept so far, or kMiss
  float* ts;                // per ray id: its t (before a hit: the ray's tfar)
};

// Sets up `context` with its filter; the caller sets ids[] = kMiss and ts[] = each ray's tfar.
void initContext(IdContext& context, const DoubleRay* rays, uint64_t* ids, float* ts,
                 RTCIntersectContextFlags flags);

// Creates the user geometry of level.userChildren (when there are any) and attaches it.
void attachUserChildren(RTCDevice device, Level& level);

// Fills an RTCRayHit for `ray` (float copy of the double ray) with id 0 and a reset hit.
void setRayHit(RTCRayHit& rh, const DoubleRay& ray, float tnear, float tfar);

// Traces one ray through `level` (rh from setRayHit, ray its double version); returns the
// expanded ID relative to the level's node (the least at the nearest t), or kMiss;
// rh.ray.tfar is the hit distance.
uint64_t intersect1(const Level& level, RTCRayHit& rh, const DoubleRay& ray);

// Lane k of a packet: the float copy of `ray` from tnear to tfar (an inactive lane: pass
// tfar = -inf), lane id k, a reset hit; valid[k] = -1 (active) or 0.
template <int N>
void setPacketLane(RTCRayHitNt<N>& p, int* valid, int k, bool active, const DoubleRay& ray,
                   float tnear, float tfar) {
  valid[k] = active ? -1 : 0;
  p.ray.org_x[k] = float(ray.org.x), p.ray.org_y[k] = float(ray.org.y);
  p.ray.org_z[k] = float(ray.org.z);
  p.ray.dir_x[k] = float(ray.dir.x), p.ray.dir_y[k] = float(ray.dir.y);
  p.ray.dir_z[k] = float(ray.dir.z);
  p.ray.tnear[k] = tnear;
  p.ray.tfar[k] = tfar;
  p.ray.time[k] = 0.0f;
  p.ray.mask[k] = ~0u;
  p.ray.id[k] = unsigned(k);
  p.ray.flags[k] = 0;
  p.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
  p.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
}

// rtcIntersect4/8/16 on a packet of native width N.
template <int N>
void intersectPacketN(int* valid, RTCScene scene, RTCIntersectContext* context,
                      RTCRayHitNt<N>& p) {
  static_assert(N == 4 || N == 8 || N == 16);
  if constexpr (N == 16)
    rtcIntersect16(valid, scene, context, reinterpret_cast<RTCRayHit16*>(&p));
  else if constexpr (N == 8)
    rtcIntersect8(valid, scene, context, reinterpret_cast<RTCRayHit8*>(&p));
  else
    rtcIntersect4(valid, scene, context, reinterpret_cast<RTCRayHit4*>(&p));
}

}  // namespace lzb::embree
