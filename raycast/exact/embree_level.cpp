#include "raycast/exact/embree_level.hpp"

#include <cmath>
#include <cstring>

namespace lzb::embree {

namespace {

constexpr uint32_t kTieSlackUlps = 16;

void childBounds(const RTCBoundsFunctionArguments* args) {
  const auto* level = static_cast<const Level*>(args->geometryUserPtr);
  const UserChild& c = level->userChildren[args->primID];
  RTCBounds* b = args->bounds_o;
  b->lower_x = c.lower[0], b->lower_y = c.lower[1], b->lower_z = c.lower[2];
  b->upper_x = c.upper[0], b->upper_y = c.upper[1], b->upper_z = c.upper[2];
}

// The ray in the child's frame: the direction is mapped linearly, so t keeps its meaning. A
// translation (grids of instances nest them many levels deep) moves the origin alone: the same
// bits as the product, whose other terms are zeros.
DoubleRay toChild(const UserChild& c, const DoubleRay& r) {
  if (c.translationOnly) return {r.org + glm::dvec3(c.toChild[3]), r.dir};
  return {c.toChild * glm::dvec4(r.org, 1.0), c.toChild * glm::dvec4(r.dir, 0.0)};
}

// After a hit at t, the ray goes on a little past t: Embree's packet traversal culls a box whose
// entry is not below tfar, and its triangle test drops a candidate beyond tfar, which would lose
// a tie in another leaf or instance. Both t and the box entry come from approximate reciprocals
// (rcp and a Newton step) that differ by an ulp or two, and by CPU (a hit exactly at 2 comes out
// 1 ulp short on an AMD EPYC): 16 ulps covers them; the filter orders whatever they let through.
float tfarAfterHit(float t) {
  uint32_t bits;  // t >= 0 and finite: larger floats are larger bit patterns (no libm call)
  std::memcpy(&bits, &t, sizeof bits);
  bits += kTieSlackUlps;
  std::memcpy(&t, &bits, sizeof t);
  return t;
}

// The context filter on a Level's own triangles: keeps a candidate only when it comes before
// the hit kept so far (Embree has set the lane's tfar to the candidate's t for the call).
void keepLeastHit(const RTCFilterFunctionNArguments* args) {
  auto* context = reinterpret_cast<IdContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned r = RTCRayN_id(args->ray, args->N, i);
    const float t = RTCRayN_tfar(args->ray, args->N, i);
    const uint64_t id = RTCHitN_primID(args->hit, args->N, i);
    if (!nearer(t, id, context->ts[r], context->ids[r])) {
      args->valid[i] = 0;
      continue;
    }
    context->ts[r] = t;
    context->ids[r] = id;
    RTCRayN_tfar(args->ray, args->N, i) = tfarAfterHit(t);
  }
}

// Records a child hit in lane i of the parent's ray/hit arrays when it comes before the hit
// kept there (the nested call only returns t <= tfar; a tie goes to the lesser ID).
void acceptHit(const RTCIntersectFunctionNArguments* args, unsigned i, float t, uint64_t id,
               uint64_t offset) {
  auto* context = reinterpret_cast<IdContext*>(args->context);
  const unsigned n = args->N;
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, n);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, n);
  const unsigned r = RTCRayN_id(ray, n, i);
  if (!nearer(t, offset + id, context->ts[r], context->ids[r])) return;
  context->ts[r] = t;
  context->ids[r] = offset + id;
  RTCRayN_tfar(ray, n, i) = tfarAfterHit(t);
  RTCHitN_Ng_x(hit, n, i) = 0.0f;  // lzb shades from the ID, not from Embree's normal
  RTCHitN_Ng_y(hit, n, i) = 0.0f;
  RTCHitN_Ng_z(hit, n, i) = 1.0f;
  RTCHitN_u(hit, n, i) = 0.0f;
  RTCHitN_v(hit, n, i) = 0.0f;
  RTCHitN_primID(hit, n, i) = args->primID;
  RTCHitN_geomID(hit, n, i) = args->geomID;
  RTCHitN_instID(hit, n, i, 0) = args->context->instID[0];
}

void intersectLanes(const RTCIntersectFunctionNArguments* args, const UserChild& c) {
  const auto* context = reinterpret_cast<const IdContext*>(args->context);
  const unsigned n = args->N;
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, n);
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const DoubleRay r = toChild(c, context->rays[RTCRayN_id(ray, n, i)]);
    RTCRayHit rh;
    setRayHit(rh, r, RTCRayN_tnear(ray, n, i), RTCRayN_tfar(ray, n, i));
    const uint64_t id = intersect1(*c.child, rh, r);
    if (id != kMiss) acceptHit(args, i, rh.ray.tfar, id, c.offset);
  }
}

// A packet stays a packet through the instance: the lanes that reached this child go down
// together, so coherent primary rays keep Embree's packet traversal at every level.
template <int N>
void intersectPacket(const RTCIntersectFunctionNArguments* args, const UserChild& c) {
  const auto* context = reinterpret_cast<const IdContext*>(args->context);
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, N);
  alignas(64) RTCRayHitNt<N> p;
  alignas(64) int valid[N];
  DoubleRay rays[N];
  uint64_t ids[N];
  float ts[N];
  for (int k = 0; k < N; ++k) {
    const bool active = args->valid[k] == -1;
    rays[k] = active ? toChild(c, context->rays[RTCRayN_id(ray, N, unsigned(k))])
                     : DoubleRay{glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0)};
    ts[k] = active ? RTCRayN_tfar(ray, N, unsigned(k)) : -INFINITY;
    setPacketLane(p, valid, k, active, rays[k], active ? RTCRayN_tnear(ray, N, unsigned(k)) : 0.0f,
                  ts[k]);
    ids[k] = kMiss;
  }
  IdContext sub;
  initContext(sub, rays, ids, ts, args->context->flags);
  intersectPacketN<N>(valid, c.child->scene, &sub.ctx, p);
  for (int k = 0; k < N; ++k)
    if (valid[k] && ids[k] != kMiss) acceptHit(args, unsigned(k), ts[k], ids[k], c.offset);
}

void intersectChild(const RTCIntersectFunctionNArguments* args) {
  const auto* level = static_cast<const Level*>(args->geometryUserPtr);
  const UserChild& c = level->userChildren[args->primID];
  switch (args->N) {
    case 16:
      intersectPacket<16>(args, c);
      break;
    case 8:
      intersectPacket<8>(args, c);
      break;
    case 4:
      intersectPacket<4>(args, c);
      break;
    default:
      intersectLanes(args, c);
  }
}

void occludedChild(const RTCOccludedFunctionNArguments* args) {
  const auto* level = static_cast<const Level*>(args->geometryUserPtr);
  const UserChild& c = level->userChildren[args->primID];
  const auto* context = reinterpret_cast<const IdContext*>(args->context);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const DoubleRay r = toChild(c, context->rays[RTCRayN_id(args->ray, n, i)]);
    RTCRayHit rh;
    setRayHit(rh, r, RTCRayN_tnear(args->ray, n, i), RTCRayN_tfar(args->ray, n, i));
    if (intersect1(*c.child, rh, r) != kMiss) RTCRayN_tfar(args->ray, n, i) = -INFINITY;
  }
}

}  // namespace

void attachUserChildren(RTCDevice device, Level& level) {
  if (level.userChildren.empty()) return;
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geom, unsigned(level.userChildren.size()));
  rtcSetGeometryUserData(geom, &level);
  rtcSetGeometryBoundsFunction(geom, childBounds, nullptr);
  rtcSetGeometryIntersectFunction(geom, intersectChild);
  rtcSetGeometryOccludedFunction(geom, occludedChild);
  rtcCommitGeometry(geom);
  level.userGeom = rtcAttachGeometry(level.scene, geom);
  rtcReleaseGeometry(geom);
}

void setRayHit(RTCRayHit& rh, const DoubleRay& ray, float tnear, float tfar) {
  rh.ray.org_x = float(ray.org.x), rh.ray.org_y = float(ray.org.y), rh.ray.org_z = float(ray.org.z);
  rh.ray.dir_x = float(ray.dir.x), rh.ray.dir_y = float(ray.dir.y), rh.ray.dir_z = float(ray.dir.z);
  rh.ray.tnear = tnear;
  rh.ray.tfar = tfar;
  rh.ray.time = 0.0f;
  rh.ray.mask = ~0u;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

void initContext(IdContext& context, const DoubleRay* rays, uint64_t* ids, float* ts,
                 RTCIntersectContextFlags flags) {
  rtcInitIntersectContext(&context.ctx);
  context.ctx.flags = flags;
  context.ctx.filter = keepLeastHit;
  context.rays = rays;
  context.ids = ids;
  context.ts = ts;
}

uint64_t intersect1(const Level& level, RTCRayHit& rh, const DoubleRay& ray) {
  uint64_t id = kMiss;
  float t = rh.ray.tfar;
  IdContext context;
  initContext(context, &ray, &id, &t, RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT);
  rh.ray.id = 0;
  rtcIntersect1(level.scene, &context.ctx, &rh);
  rh.ray.tfar = t;
  return id;
}

}  // namespace lzb::embree
