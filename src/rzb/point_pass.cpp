#include "src/rzb/point_pass.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "src/core/shading.hpp"
#include "src/rzb/box_sampler.hpp"

namespace lzb::rzb {

namespace {

// The octahedral normal as an unnormalised direction (enough for a sign test).
inline glm::dvec3 normalDirection(uint32_t code) {
  double x = double(uint16_t(code)) / 65535.0 * 2.0 - 1.0;
  double y = double(uint16_t(code >> 16)) / 65535.0 * 2.0 - 1.0;
  const double z = 1.0 - std::abs(x) - std::abs(y);
  if (z < 0.0) {
    const double ox = (1.0 - std::abs(y)) * (x >= 0.0 ? 1.0 : -1.0);
    y = (1.0 - std::abs(x)) * (y >= 0.0 ? 1.0 : -1.0);
    x = ox;
  }
  return {x, y, z};
}

struct Counters {
  uint64_t drawn = 0, back = 0, splatted = 0;
};

// The sink of a box's samples (drawn: a CameraSink; or cached): back faces dropped, points to
// camera space, then the splatting core.
template <bool kWide, bool kPixel>
struct BoxSplatter {
  PointSplatter<kWide, kPixel> out;
  bool dropBackfaces;
  Affine toCam;
  glm::dvec3 eye{0.0};
  Counters c;

  BoxSplatter(const SplatSetup& setup, KeyBuffer& kb, bool drop) : out(setup, kb), dropBackfaces(drop) {}

  void flush() { out.flush(); }
  // The camera-space path of drawBoxSamples (CameraSink).
  void point(float x, float y, float z, uint64_t id) { out.add(x, y, z, id); }
  void backfacing() { ++c.back; }

  inline void cached(const CachedSample* first, uint64_t count) {
    for (const CachedSample* cs = first; cs != first + count; ++cs)
      land(*this, glm::dvec3(cs->p), normalDirection(cs->normal), eye, toCam, cs->id);
    flush();
  }

  Counters counters() const { return {c.drawn, c.back, out.splatted()}; }
};

// Runs every job on `threads` threads (dynamic schedule, one job at a time), each thread with its
// own sink from make(); per job, prepare(sink, box), then the job's samples, drawn or (for a sink
// that reads them) cached, go to the sink.
template <class Make, class Prepare>
PassCounts runJobs(std::span<const SplatJob> jobs, std::span<const SelectedBox> boxes,
                   const SampleStream& stream, int threads, Make&& make, Prepare&& prepare) {
  uint64_t drawn = 0, back = 0, splatted = 0;
  const long n = long(jobs.size());
#pragma omp parallel num_threads(threads) reduction(+ : drawn, back, splatted)
  {
    auto sink = make();
#pragma omp for schedule(dynamic, 1)
    for (long k = 0; k < n; ++k) {
      const SplatJob& j = jobs[size_t(k)];
      const SelectedBox& b = boxes[j.box];
      prepare(sink, b);
      sink.c.drawn += j.count;
      if constexpr (requires { sink.cached(j.cached, j.count); }) {
        if (j.cached) {
          sink.cached(j.cached + j.first, j.count);
          continue;
        }
      }
      drawBoxSamples(b, stream, j.first, j.count, b.samples, sink);
    }
    const Counters c = sink.counters();
    drawn += c.drawn;
    back += c.back;
    splatted += c.splatted;
  }
  return PassCounts{drawn, back, splatted};
}

template <bool kWide, bool kPixel>
PassCounts runSplat(std::span<const SplatJob> jobs, std::span<const SelectedBox> boxes,
                    const SampleStream& stream, const SplatSetup& setup, bool dropBackfaces,
                    KeyBuffer& keys, int threads) {
  return runJobs(
      jobs, boxes, stream, threads,
      [&] { return BoxSplatter<kWide, kPixel>(setup, keys, dropBackfaces); },
      [](BoxSplatter<kWide, kPixel>& sp, const SelectedBox& b) {
        sp.toCam = b.toCamera;
        sp.eye = b.eyeLocal;
      });
}

}  // namespace

void appendJobs(std::vector<SplatJob>& jobs, uint32_t box, uint64_t count,
                const CachedSample* cached, uint64_t chunk) {
  for (uint64_t first = 0; first < count; first += chunk)
    jobs.push_back({box, first, std::min(chunk, count - first), cached});
}

PassCounts splatJobs(std::span<const SplatJob> jobs, std::span<const SelectedBox> boxes,
                     const SampleStream& stream, const SplatSetup& setup, bool dropBackfaces,
                     KeyBuffer& keys, int threads) {
  return withSplatter(keys, setup.splat, [&]<bool kWide, bool kPixel>() {
    return runSplat<kWide, kPixel>(jobs, boxes, stream, setup, dropBackfaces, keys, threads);
  });
}

// ---------------------------------------------------------------------------------------------
// Gaussian reconstruction

namespace {

constexpr double kWeightScale = 65535.0;

struct GaussSink {
  const SplatSetup& s;
  bool dropBackfaces;
  const std::vector<float>& depth;
  uint64_t* accum;
  glm::vec3 toLight;
  float ambient;
  double cx, cy, sigma, radius, tolerance;
  Affine toCam;
  glm::dmat3 normalToWorld{1.0};
  glm::dvec3 eye{0.0};
  Counters c;

  void operator()(const glm::dvec3& p, const glm::dvec3& n, uint64_t, const DistributionTree* leaf,
                  uint32_t meshIndex) {
    const bool facing = glm::dot(n, eye - p) >= 0.0;
    if (dropBackfaces && !facing) {
      ++c.back;
      return;
    }
    const glm::dvec3 q = toCam.point(p);
    if (!(q.z >= s.nearPlane && q.z <= s.farPlane)) return;
    const double inv = s.pixelScale / q.z;
    const double px = cx + q.x * inv, py = cy - q.y * inv;
    if (!(px >= 0.0 && px < s.width && py >= 0.0 && py < s.height)) return;
    const size_t pixel = size_t(int(py)) * size_t(s.width) + size_t(int(px));
    // Visible: no deeper than the splat pass's surface there, within a few pixel footprints.
    if (!(q.z <= double(depth[pixel]) + tolerance * q.z)) return;
    ++c.splatted;
    const glm::dvec3 nw = glm::normalize(normalToWorld * (facing ? n : -n));
    const Rgba8 color = shade(leaf->mesh().color(meshIndex), glm::vec3(nw), true, toLight, ambient);
    const uint64_t rgb[3] = {channel(color, 0), channel(color, 1), channel(color, 2)};
    const int x0 = std::max(int(std::ceil(px - 0.5 - radius)), 0);
    const int x1 = std::min(int(std::floor(px - 0.5 + radius)), s.width - 1);
    const int y0 = std::max(int(std::ceil(py - 0.5 - radius)), 0);
    const int y1 = std::min(int(std::floor(py - 0.5 + radius)), s.height - 1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double dx = x + 0.5 - px, dy = y + 0.5 - py;
        const double r2 = dx * dx + dy * dy;
        if (r2 > radius * radius) continue;
        const uint64_t w = uint64_t(std::lround(std::exp(-0.5 * r2 / (sigma * sigma)) * kWeightScale));
        if (!w) continue;
        uint64_t* a = accum + 4 * (size_t(y) * size_t(s.width) + size_t(x));
        std::atomic_ref<uint64_t>(a[0]).fetch_add(w * rgb[0], std::memory_order_relaxed);
        std::atomic_ref<uint64_t>(a[1]).fetch_add(w * rgb[1], std::memory_order_relaxed);
        std::atomic_ref<uint64_t>(a[2]).fetch_add(w * rgb[2], std::memory_order_relaxed);
        std::atomic_ref<uint64_t>(a[3]).fetch_add(w, std::memory_order_relaxed);
      }
  }

  Counters counters() const { return c; }
};

}  // namespace

PassCounts gaussAccumulate(std::span<const SplatJob> jobs, std::span<const SelectedBox> boxes,
                           const SampleStream& stream, const SplatSetup& setup, bool dropBackfaces,
                           const std::vector<float>& depth, const Scene& scene,
                           std::vector<uint64_t>& accum, int threads) {
  accum.assign(4 * size_t(setup.width) * size_t(setup.height), 0);
  const glm::vec3 toLight = lightDirection(scene.light);
  return runJobs(
      jobs, boxes, stream, threads,
      [&] {
        return GaussSink{setup, dropBackfaces, depth, accum.data(), toLight, float(scene.light.ambient),
                         0.5 * setup.width, 0.5 * setup.height, 0.5 * setup.splat, setup.splat * 1.0,
                         // A surface seen at up to ~75 degrees changes depth by < 4 footprints per
                         // splat.
                         4.0 * setup.splat / setup.pixelScale, {}, glm::dmat3(1.0), glm::dvec3(0.0),
                         {}};
      },
      [](GaussSink& g, const SelectedBox& b) {
        g.toCam = b.toCamera;
        g.eye = b.eyeLocal;
        g.normalToWorld = glm::transpose(glm::inverse(b.toWorld.a));
      });
}

}  // namespace lzb::rzb
