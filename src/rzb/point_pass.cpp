// The point pass's hot loops. On x86-64 this file is compiled for cmpxchg16b (every x86-64 CPU
// since 2006 has it; checked at run time before a 128-bit key buffer is used), so the 16-byte
// compare-and-swap of wide keys is inlined into the splat loop.
#if defined(__x86_64__)
#pragma GCC target("cx16")
#include <cpuid.h>
#endif

#include "src/rzb/point_pass.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <stdexcept>

#include "src/core/shading.hpp"
#include "src/core/timer.hpp"
#include "src/rzb/box_sampler.hpp"

namespace lzb::rzb {

namespace {

bool wideKeysSupported() {
#if defined(__x86_64__)
  unsigned a, b, c, d;
  return __get_cpuid(1, &a, &b, &c, &d) && (c & bit_CMPXCHG16B);
#else
  return true;
#endif
}

__extension__ typedef unsigned __int128 U128;

inline void minNarrow(uint64_t* p, uint64_t key) {
  std::atomic_ref<uint64_t> a(*p);
  uint64_t cur = a.load(std::memory_order_relaxed);
  while (key < cur && !a.compare_exchange_weak(cur, key, std::memory_order_relaxed)) {
  }
}

inline void minWide(Key128* p, uint64_t hi, uint64_t lo) {
  // Read hi before lo (x86 keeps loads in order): a torn read then never looks smaller than a
  // value the pixel really held, so skipping the write on it is safe.
  uint64_t chi = __atomic_load_n(&p->hi, __ATOMIC_ACQUIRE);
  uint64_t clo = __atomic_load_n(&p->lo, __ATOMIC_ACQUIRE);
  while (hi < chi || (hi == chi && lo < clo)) {
    const U128 expected = U128(chi) << 64 | clo, desired = U128(hi) << 64 | lo;
    const U128 seen = __sync_val_compare_and_swap(reinterpret_cast<U128*>(p), expected, desired);
    if (seen == expected) return;
    chi = uint64_t(seen >> 64);
    clo = uint64_t(seen);
  }
}

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

// Projects camera-space points and keeps the minimum key per pixel (or per d x d splat). Points
// are buffered per batch and splatted in flush(): the tree lookups and the key buffer then take
// turns in the cache instead of evicting each other.
template <bool kWide, bool kPixel>
struct Splatter {
  const SplatSetup s;  // a copy: the atomics would make the compiler reload a reference's fields
  void* keys;
  double cx, cy;
  Affine toCam;
  glm::dvec3 eye{0.0};
  Counters c;
  struct Pending {
    float x, y, z;
    uint64_t id;
  };
  std::vector<Pending> pending;
  struct Target {
    size_t pixel;
    uint32_t zbits;
    uint64_t id;
  };
  std::vector<Target> targets;

  Splatter(const SplatSetup& setup, KeyBuffer& kb)
      : s(setup),
        keys(kWide ? static_cast<void*>(kb.wideKeys()) : static_cast<void*>(kb.narrow())),
        cx(0.5 * setup.width),
        cy(0.5 * setup.height) {
    pending.reserve(kDrawBatch);
    if constexpr (kPixel) targets.resize(kDrawBatch);
  }

  inline void prefetchKey(size_t i) const {
    if constexpr (kWide)
      __builtin_prefetch(static_cast<Key128*>(keys) + i, 1);
    else
      __builtin_prefetch(static_cast<uint64_t*>(keys) + i, 1);
  }

  inline void write(size_t i, uint32_t zbits, uint64_t id) {
    if constexpr (kWide)
      minWide(static_cast<Key128*>(keys) + i, zbits, id);
    else
      minNarrow(static_cast<uint64_t*>(keys) + i, uint64_t(zbits) << 32 | (id & 0xffffffffu));
  }

  // q: camera space (x right, y up, z view depth); float is ample for the pixel and the depth key.
  inline void put(float qx, float qy, float qz, uint64_t id) {
    if (!(qz >= s.nearPlane && qz <= s.farPlane)) return;
    const double inv = s.pixelScale / qz;
    const double px = cx + qx * inv, py = cy - qy * inv;
    const uint32_t zbits = std::bit_cast<uint32_t>(qz);
    if constexpr (kPixel) {
      if (!(px >= 0.0 && px < s.width && py >= 0.0 && py < s.height)) return;
      write(size_t(int(py)) * size_t(s.width) + size_t(int(px)), zbits, id);
      ++c.splatted;
    } else {
      const double d = s.splat, off = 0.5 - 0.5 * d;
      const double fx = std::floor(px + off), fy = std::floor(py + off);
      if (!(fx > -d && fx < s.width && fy > -d && fy < s.height)) return;
      const int x0 = std::max(int(fx), 0), x1 = std::min(int(fx) + s.splat, s.width);
      const int y0 = std::max(int(fy), 0), y1 = std::min(int(fy) + s.splat, s.height);
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) write(size_t(y) * size_t(s.width) + size_t(x), zbits, id);
      ++c.splatted;
    }
  }

  inline void operator()(const glm::dvec3& p, const glm::dvec3& n, uint64_t id, const SampleTree*,
                         uint32_t) {
    if (s.dropBackfaces && glm::dot(n, eye - p) < 0.0) {
      ++c.back;
      return;
    }
    const glm::dvec3 q = toCam.point(p);
    pending.push_back(Pending{float(q.x), float(q.y), float(q.z), id});
  }

  void flush() {
    if constexpr (kPixel) {
      // Pixel indices first, then the atomic minima with the key buffer's lines prefetched a few
      // samples ahead (the buffer is larger than L2, and a locked compare-and-swap waits for the
      // loads before it, so misses would otherwise come one at a time).
      if (targets.size() < pending.size()) targets.resize(pending.size());
      size_t m = 0;
      for (const Pending& q : pending) {
        if (!(q.z >= s.nearPlane && q.z <= s.farPlane)) continue;
        const double inv = s.pixelScale / q.z;
        const double px = cx + q.x * inv, py = cy - q.y * inv;
        if (!(px >= 0.0 && px < s.width && py >= 0.0 && py < s.height)) continue;
        targets[m++] = Target{size_t(int(py)) * size_t(s.width) + size_t(int(px)),
                              std::bit_cast<uint32_t>(q.z), q.id};
      }
      constexpr size_t kAhead = 16;
      for (size_t k = 0; k < m; ++k) {
        if (k + kAhead < m) prefetchKey(targets[k + kAhead].pixel);
        write(targets[k].pixel, targets[k].zbits, targets[k].id);
      }
      c.splatted += m;
    } else {
      for (const Pending& q : pending) put(q.x, q.y, q.z, q.id);
    }
    pending.clear();
  }

  inline void cached(const CachedSample* first, uint64_t count) {
    for (const CachedSample* cs = first; cs != first + count; ++cs) {
      const glm::dvec3 p(cs->p);
      if (s.dropBackfaces && glm::dot(normalDirection(cs->normal), eye - p) < 0.0) {
        ++c.back;
        continue;
      }
      const glm::dvec3 q = toCam.point(p);
      pending.push_back(Pending{float(q.x), float(q.y), float(q.z), cs->id});
      if (pending.size() == kDrawBatch) flush();
    }
    flush();
  }
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
    drawn += sink.c.drawn;
    back += sink.c.back;
    splatted += sink.c.splatted;
  }
  return PassCounts{drawn, back, splatted};
}

template <bool kWide, bool kPixel>
PassCounts runSplat(std::span<const SplatJob> jobs, std::span<const SelectedBox> boxes,
                    const SampleStream& stream, const SplatSetup& setup, KeyBuffer& keys,
                    int threads) {
  return runJobs(
      jobs, boxes, stream, threads, [&] { return Splatter<kWide, kPixel>(setup, keys); },
      [](Splatter<kWide, kPixel>& sp, const SelectedBox& b) {
        sp.toCam = b.toCamera;
        sp.eye = b.eyeLocal;
      });
}

}  // namespace

void KeyBuffer::reset(int width, int height, bool wide, int threads) {
  if (wide && !wideKeysSupported())
    throw std::runtime_error("rzb: this CPU has no 16-byte compare-and-swap for 128-bit keys");
  width_ = width;
  height_ = height;
  wide_ = wide;
  const long n = long(width) * long(height);
  if (wide) {
    narrow_.clear();
    wide_keys_.resize(size_t(n));
    Key128* k = wide_keys_.data();
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long i = 0; i < n; ++i) k[i] = Key128{~uint64_t(0), ~uint64_t(0)};
  } else {
    wide_keys_.clear();
    narrow_.resize(size_t(n));
    uint64_t* k = narrow_.data();
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long i = 0; i < n; ++i) k[i] = ~uint64_t(0);
  }
}

void KeyBuffer::resolve(Framebuffer& fb, int threads) const {
  const long n = long(width_) * long(height_);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long i = 0; i < n; ++i) {
    uint64_t hi, lo;
    bool empty;
    if (wide_) {
      hi = wide_keys_[size_t(i)].hi;
      lo = wide_keys_[size_t(i)].lo;
      empty = hi == ~uint64_t(0);
    } else {
      hi = narrow_[size_t(i)] >> 32;
      lo = narrow_[size_t(i)] & 0xffffffffu;
      empty = narrow_[size_t(i)] == ~uint64_t(0);
    }
    if (empty) {
      fb.depth[size_t(i)] = kEmptyDepth;
      fb.id[size_t(i)] = kNoId;
    } else {
      fb.depth[size_t(i)] = std::bit_cast<float>(uint32_t(hi));
      fb.id[size_t(i)] = lo;
    }
  }
}

SplatSetup SplatSetup::from(const Camera& camera, int splat, bool dropBackfaces) {
  SplatSetup s;
  s.width = camera.width();
  s.height = camera.height();
  s.pixelScale = camera.pixelsPerUnitAt(1.0);
  s.nearPlane = camera.nearPlane();
  s.farPlane = camera.farPlane();
  s.splat = splat;
  s.dropBackfaces = dropBackfaces;
  return s;
}

void appendJobs(std::vector<SplatJob>& jobs, uint32_t box, uint64_t count,
                const CachedSample* cached, uint64_t chunk) {
  for (uint64_t first = 0; first < count; first += chunk)
    jobs.push_back({box, first, std::min(chunk, count - first), cached});
}

PassCounts splatJobs(std::span<const SplatJob> jobs, std::span<const SelectedBox> boxes,
                     const SampleStream& stream, const SplatSetup& setup, KeyBuffer& keys,
                     int threads) {
  const bool pixel = setup.splat == 1;
  if (keys.wide())
    return pixel ? runSplat<true, true>(jobs, boxes, stream, setup, keys, threads)
                 : runSplat<true, false>(jobs, boxes, stream, setup, keys, threads);
  return pixel ? runSplat<false, true>(jobs, boxes, stream, setup, keys, threads)
               : runSplat<false, false>(jobs, boxes, stream, setup, keys, threads);
}

// ---------------------------------------------------------------------------------------------
// Gaussian reconstruction

namespace {

constexpr double kWeightScale = 65535.0;

struct GaussSink {
  const SplatSetup& s;
  const std::vector<float>& depth;
  uint64_t* accum;
  glm::vec3 toLight;
  float ambient;
  double cx, cy, sigma, radius, tolerance;
  Affine toCam;
  glm::dmat3 normalToWorld{1.0};
  glm::dvec3 eye{0.0};
  Counters c;

  void operator()(const glm::dvec3& p, const glm::dvec3& n, uint64_t, const SampleTree* leaf,
                  uint32_t meshIndex) {
    const bool facing = glm::dot(n, eye - p) >= 0.0;
    if (s.dropBackfaces && !facing) {
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
    const Rgba8 color = shade(leaf->mesh().colors[meshIndex], glm::vec3(nw), true, toLight, ambient);
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
};

}  // namespace

PassCounts gaussAccumulate(std::span<const SplatJob> jobs, std::span<const SelectedBox> boxes,
                           const SampleStream& stream, const SplatSetup& setup,
                           const std::vector<float>& depth, const Scene& scene,
                           std::vector<uint64_t>& accum, int threads) {
  accum.assign(4 * size_t(setup.width) * size_t(setup.height), 0);
  const glm::vec3 toLight = lightDirection(scene.light);
  return runJobs(
      jobs, boxes, stream, threads,
      [&] {
        return GaussSink{setup, depth, accum.data(), toLight, float(scene.light.ambient),
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

double measureScatterLimit(int width, int height, int threads, double seconds) {
  const uint64_t pixels = uint64_t(width) * uint64_t(height);
  std::vector<uint64_t> buffer(pixels, ~uint64_t(0));
  constexpr long kBatch = 1 << 22;
  uint64_t done = 0;
  Stopwatch clock;
  uint64_t round = 0;
  do {
    const uint64_t base = round++ * uint64_t(kBatch);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long i = 0; i < kBatch; ++i) {
      const uint64_t x = mix64(base + uint64_t(i));
      minNarrow(buffer.data() + (x >> 32) % pixels, mix64(x) >> 1);
    }
    done += kBatch;
  } while (clock.seconds() < seconds);
  return double(done) / clock.seconds();
}

}  // namespace lzb::rzb
