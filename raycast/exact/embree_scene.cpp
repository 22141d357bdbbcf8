#include "raycast/exact/embree_scene.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "raycast/exact/embree_level.hpp"
#include "src/core/renderer.hpp"
#include "src/core/timer.hpp"

namespace lzb {

using embree::DoubleRay;
using embree::Level;
using embree::UserChild;

namespace {

float roundDown(double x) {
  const float f = float(x);
  return double(f) > x ? std::nextafter(f, -INFINITY) : f;
}
float roundUp(double x) {
  const float f = float(x);
  return double(f) < x ? std::nextafter(f, INFINITY) : f;
}

// An instance whose linear part cannot be inverted (or whose bounds overflow float) places
// nothing a ray can hit reliably.
bool usable(const glm::dmat4& m, const Bounds& box) {
  const double det = glm::determinant(glm::dmat3(m));
  if (!std::isfinite(det) || det == 0.0) return false;
  const glm::dmat4 inv = glm::inverse(m);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r)
      if (!std::isfinite(inv[c][r])) return false;
  return std::isfinite(float(box.lo.x)) && std::isfinite(float(box.lo.y)) &&
         std::isfinite(float(box.lo.z)) && std::isfinite(float(box.hi.x)) &&
         std::isfinite(float(box.hi.y)) && std::isfinite(float(box.hi.z));
}

}  // namespace

struct EmbreeScene::Impl {
  const Scene& scene;
  EmbreeSceneOptions options;
  RTCDevice device = nullptr;
  std::mutex errorMutex;
  std::string firstError;
  std::vector<glm::dvec3> shift;               // per node: Level frame = node frame - shift
  std::vector<std::unique_ptr<Level>> levels;  // per node, built when reached
  const Level* root = nullptr;
  int packetWidth = 1;  // widest packet the CPU and this Embree build trace natively
  EmbreeBuildStats stats;
  std::atomic<int64_t> heldBytes{0}, peakBytes{0};  // Embree's allocations (countMemory)

  Impl(const Scene& s, const EmbreeSceneOptions& o) : scene(s), options(o) {}
  ~Impl() {
    for (auto& level : levels)
      if (level) rtcReleaseScene(level->scene);
    if (device) rtcReleaseDevice(device);
  }

  // Embree's memory monitor: bytes > 0 before an allocation, < 0 after a release.
  static bool countMemory(void* user, ssize_t bytes, bool) {
    auto* impl = static_cast<Impl*>(user);
    const int64_t now = impl->heldBytes.fetch_add(bytes, std::memory_order_relaxed) + bytes;
    int64_t peak = impl->peakBytes.load(std::memory_order_relaxed);
    while (now > peak && !impl->peakBytes.compare_exchange_weak(peak, now)) {
    }
    return true;
  }

  static void reportError(void* user, RTCError code, const char* message) {
    auto* impl = static_cast<Impl*>(user);
    std::lock_guard<std::mutex> lock(impl->errorMutex);
    if (impl->firstError.empty())
      impl->firstError = "error " + std::to_string(int(code)) + ": " + (message ? message : "");
  }

  void check(const std::string& what) {
    if (rtcGetDeviceError(device) == RTC_ERROR_NONE && firstError.empty()) return;
    throw std::runtime_error("Embree: " + what + ": " + firstError);
  }

  RTCBuildQuality quality() const {
    return options.highQuality ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM;
  }

  void attachMesh(Level& level, const Mesh& mesh, const glm::dvec3& s, const std::string& name) {
    // Embree numbers primitives with 32 bits.
    if (mesh.size() > (size_t(1) << 30))
      throw std::runtime_error("Embree: node '" + name + "' holds more than 2^30 triangles");
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // The vertices recentred into Embree's own (padded) buffer; the model's indices shared as
    // they are (the scene outlives this object).
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indices.data(),
                               0, 3 * sizeof(uint32_t), mesh.size());
    check("allocating the triangles of node '" + name + "'");
    const long n = long(mesh.positions.size());
#pragma omp parallel for schedule(static) num_threads(options.threads)
    for (long i = 0; i < n; ++i) {
      const glm::dvec3 p = glm::dvec3(mesh.positions[size_t(i)]) - s;
      v[3 * i] = float(p.x), v[3 * i + 1] = float(p.y), v[3 * i + 2] = float(p.z);
    }
    rtcSetGeometryBuildQuality(g, quality());
    rtcCommitGeometry(g);
    level.meshGeom = rtcAttachGeometry(level.scene, g);
    rtcReleaseGeometry(g);
    stats.triangles += mesh.size();
  }

  // One user primitive per instance whose subtree holds triangles.
  void attachInstances(Level& level, uint32_t node) {
    const Node& n = scene.nodes[node];
    const glm::dmat4 toLevel = glm::translate(glm::dmat4(1.0), -shift[node]);
    for (size_t i = 0; i < n.instances.size(); ++i) {
      const Instance& inst = n.instances[i];
      if (scene.expandedCount[inst.node] == 0) continue;
      // Child Level frame -> this Level frame, composed in double.
      const glm::dmat4 m =
          toLevel * inst.transform * glm::translate(glm::dmat4(1.0), shift[inst.node]);
      const Bounds box = scene.nodeBounds[inst.node].transformed(toLevel * inst.transform);
      if (!usable(m, box)) {
        ++stats.skippedInstances;
        continue;
      }
      UserChild c;
      c.child = &build(inst.node);
      c.toChild = glm::dmat4x3(glm::inverse(m));
      c.translationOnly = glm::dmat3(c.toChild) == glm::dmat3(1.0);
      c.offset = scene.childOffset(node, i);
      // Padded so that float rounding of rays and boxes never culls a grazing hit.
      const double pad =
          1e-6 * std::max(glm::length(box.lo), glm::length(box.hi)) + 1e-5 * box.diagonal();
      for (int k = 0; k < 3; ++k) {
        c.lower[k] = roundDown(box.lo[k] - pad);
        c.upper[k] = roundUp(box.hi[k] + pad);
      }
      level.userChildren.push_back(c);
      ++stats.instances;
    }
    embree::attachUserChildren(device, level);
  }

  // The Level of a node, built once, children first.
  const Level& build(uint32_t node) {
    if (levels[node]) return *levels[node];
    auto level = std::make_unique<Level>();
    level->scene = rtcNewScene(device);
    rtcSetSceneFlags(level->scene,
                     RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION |
                         (options.compactLeaves ? RTC_SCENE_FLAG_COMPACT : RTC_SCENE_FLAG_NONE));
    rtcSetSceneBuildQuality(level->scene, quality());
    const Node& n = scene.nodes[node];
    if (!n.mesh.empty()) attachMesh(*level, n.mesh, shift[node], n.name);
    attachInstances(*level, node);
    rtcCommitScene(level->scene);
    check("building node '" + n.name + "'");
    ++stats.levels;
    levels[node] = std::move(level);
    return *levels[node];
  }

  DoubleRay rootRay(const glm::dvec3& origin, const glm::dvec3& dir) const {
    return {origin - shift[scene.root], dir};
  }
};

EmbreeScene::EmbreeScene(const Scene& scene, const EmbreeSceneOptions& options)
    : impl_(std::make_unique<Impl>(scene, options)) {
  Stopwatch clock;
  Impl& m = *impl_;
  const std::string config = options.deviceConfig + (options.deviceConfig.empty() ? "" : ",") +
                             "threads=" + std::to_string(std::max(options.threads, 1));
  m.device = rtcNewDevice(config.c_str());
  if (!m.device)
    throw std::runtime_error("Embree: cannot create a device (error " +
                             std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(m.device, Impl::reportError, &m);
  rtcSetDeviceMemoryMonitorFunction(m.device, Impl::countMemory, &m);
  if (rtcGetDeviceProperty(m.device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED))
    m.packetWidth = 16;
  else if (rtcGetDeviceProperty(m.device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED))
    m.packetWidth = 8;
  else if (rtcGetDeviceProperty(m.device, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED))
    m.packetWidth = 4;
  m.shift.assign(scene.nodes.size(), glm::dvec3(0.0));
  for (size_t i = 0; i < scene.nodes.size(); ++i)
    if (i < scene.nodeBounds.size() && !scene.nodeBounds[i].empty())
      m.shift[i] = scene.nodeBounds[i].center();
  m.levels.resize(scene.nodes.size());
  m.root = &m.build(scene.root);
  m.stats.seconds = clock.seconds();
  m.stats.bytes = uint64_t(std::max<int64_t>(m.heldBytes.load(), 0));
  m.stats.peakBytes = uint64_t(std::max<int64_t>(m.peakBytes.load(), 0));
}

EmbreeSceneOptions withRenderOptions(EmbreeSceneOptions base, const RenderOptions& options) {
  base.threads = std::max(options.threads, 1);
  base.compactLeaves = base.compactLeaves || options.compactBvh;
  return base;
}

void addEmbreeMemory(const EmbreeBuildStats& build, FrameStats& stats) {
  stats.addCount("embree_bytes", double(build.bytes));
  stats.addCount("embree_peak_bytes", double(build.peakBytes));
}

EmbreeScene::~EmbreeScene() = default;

Bounds EmbreeScene::heldBounds() const {
  RTCBounds b;
  rtcGetSceneBounds(impl_->root->scene, &b);
  Bounds out;
  if (b.lower_x > b.upper_x) return out;
  const glm::dvec3 s = impl_->shift[impl_->scene.root];
  out.extend(glm::dvec3(b.lower_x, b.lower_y, b.lower_z) + s);
  out.extend(glm::dvec3(b.upper_x, b.upper_y, b.upper_z) + s);
  return out;
}

const EmbreeBuildStats& EmbreeScene::buildStats() const {
  return impl_->stats;
}

int EmbreeScene::packetWidth() const {
  return impl_->packetWidth;
}

RayHit EmbreeScene::intersect(const glm::dvec3& origin, const glm::dvec3& dir, double tnear,
                              double tfar) const {
  const DoubleRay ray = impl_->rootRay(origin, dir);
  RTCRayHit rh;
  embree::setRayHit(rh, ray, std::max(roundDown(tnear), 0.0f), roundUp(tfar));
  const uint64_t id = embree::intersect1(*impl_->root, rh, ray);
  if (id == embree::kMiss) return {};
  return {rh.ray.tfar, id};
}

namespace {

// Up to N rays (lanes past `count` inactive) as one packet; N is Embree's native width.
template <int N>
void intersectPacket(const Level& root, const DoubleRay* rays, const Ray* src, size_t count,
                     RayHit* hits) {
  alignas(64) RTCRayHitNt<N> p;
  alignas(64) int valid[N];
  uint64_t ids[N];
  float ts[N];
  for (int k = 0; k < N; ++k) {
    const bool active = size_t(k) < count;
    ts[k] = active ? roundUp(src[k].tfar) : -INFINITY;
    embree::setPacketLane(p, valid, k, active, rays[active ? k : 0],
                          active ? std::max(roundDown(src[k].tnear), 0.0f) : 0.0f, ts[k]);
    ids[k] = embree::kMiss;
  }
  embree::IdContext context;
  embree::initContext(context, rays, ids, ts, RTC_INTERSECT_CONTEXT_FLAG_COHERENT);
  embree::intersectPacketN<N>(valid, root.scene, &context.ctx, p);
  for (size_t k = 0; k < count; ++k)
    hits[k] = ids[k] == embree::kMiss ? RayHit{} : RayHit{ts[k], ids[k]};
}

}  // namespace

void EmbreeScene::intersect(std::span<const Ray> rays, std::span<RayHit> hits) const {
  const Impl& m = *impl_;
  const size_t w = size_t(m.packetWidth);
  DoubleRay local[16];
  for (size_t first = 0; first < rays.size(); first += w) {
    const size_t count = std::min(w, rays.size() - first);
    const Ray* r = rays.data() + first;
    RayHit* h = hits.data() + first;
    for (size_t k = 0; k < count; ++k) local[k] = m.rootRay(r[k].origin, r[k].dir);
    switch (m.packetWidth) {
      case 16:
        intersectPacket<16>(*m.root, local, r, count, h);
        break;
      case 8:
        intersectPacket<8>(*m.root, local, r, count, h);
        break;
      case 4:
        intersectPacket<4>(*m.root, local, r, count, h);
        break;
      default:
        *h = intersect(r->origin, r->dir, r->tnear, r->tfar);
    }
  }
}

}  // namespace lzb
