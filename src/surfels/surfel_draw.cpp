#include "src/surfels/surfel_draw.hpp"

#include <omp.h>

#include <algorithm>
#include <memory>

#include "src/splat/splatter.hpp"

namespace lzb::surfels {

PlacedLevel PlacedLevel::make(const SurfelLevel& level, const glm::dmat4& world, uint64_t idBase,
                              const Camera& camera, int sprite, uint64_t count,
                              bool cullBackfaces) {
  PlacedLevel p;
  p.level = &level;
  p.idBase = idBase;
  p.sprite = sprite;
  p.count = count;
  const double step = level.latticeStep();
  const glm::dvec3 origin = level.domain.origin + 0.5 * step;  // lattice point 0's centre
  const glm::dvec3 c0 = glm::dvec3(world * glm::dvec4(origin, 1.0)) - camera.position();
  const glm::dvec3 axes[3] = {camera.right(), camera.up(), camera.forward()};
  for (int r = 0; r < 3; ++r) {
    for (int i = 0; i < 3; ++i)
      p.toCamera[r][i] = float(glm::dot(axes[r], glm::dvec3(world[i]) * step));
    p.toCamera[r][3] = float(glm::dot(axes[r], c0));
  }
  const glm::dvec3 eyeLocal = glm::dvec3(glm::inverse(world) * glm::dvec4(camera.position(), 1.0));
  p.eye = glm::vec3((eyeLocal - origin) / step);
  // An octant faces away from the whole cube when, on every axis, the eye lies beyond the cube on
  // the side the octant's normals point away from (then each term of n . (q - eye) is > 0).
  const CollectorLayout& l = level.collector.layout();
  if (cullBackfaces && level.collector.quality() == CollectorQuality::kHigh) {
    const float last = float(l.lattice() - 1);
    for (uint32_t s = 0; s < 8; ++s) {
      bool away = true;
      for (int k = 0; k < 3; ++k) away = away && ((s >> k & 1) ? p.eye[k] > last : p.eye[k] < 0.0f);
      if (away) p.culledOctants |= uint8_t(1u << s);
    }
  }
  return p;
}

std::vector<SurfelJob> makeJobs(std::span<const PlacedLevel> placed,
                                std::span<const uint32_t> which, uint64_t chunk) {
  PlacementJobs jobs;
  for (uint32_t i : which) jobs.addRuns(i, placed[i].count, chunk);
  return std::move(jobs.list);
}

namespace {

// One thread's splatters, one per sprite size in use.
template <bool kWide>
class Splatters {
 public:
  Splatters(const Camera& camera, bool disc, KeyBuffer& keys)
      : camera_(camera), disc_(disc), keys_(keys) {}
  void add(int d, float x, float y, float z, uint64_t id) {
    if (d == 1) {
      if (!pixel_)
        pixel_ = std::make_unique<PointSplatter<kWide, true>>(SplatSetup::from(camera_, 1), keys_);
      pixel_->add(x, y, z, id);
      return;
    }
    if (sized_.size() <= size_t(d)) sized_.resize(size_t(d) + 1);
    if (!sized_[size_t(d)]) {
      SplatSetup s = SplatSetup::from(camera_, d);
      s.disc = disc_;
      sized_[size_t(d)] = std::make_unique<PointSplatter<kWide, false>>(s, keys_);
    }
    sized_[size_t(d)]->add(x, y, z, id);
  }
  uint64_t flush() {
    uint64_t n = 0;
    if (pixel_) {
      pixel_->flush();
      n += pixel_->splatted();
    }
    for (auto& s : sized_)
      if (s) {
        s->flush();
        n += s->splatted();
      }
    return n;
  }

 private:
  const Camera& camera_;
  bool disc_;
  KeyBuffer& keys_;
  std::unique_ptr<PointSplatter<kWide, true>> pixel_;
  std::vector<std::unique_ptr<PointSplatter<kWide, false>>> sized_;
};

template <class TriT>
TriT readTriangle(const uint8_t* table, uint64_t i) {
  TriT t;
  __builtin_memcpy(&t, table + i * sizeof(TriT), sizeof(TriT));
  return t;
}

// Entries [begin, end) of one placed level. kHigh: the 6-byte layout; TriT: the side table's width.
template <bool kHigh, class TriT, class Sink>
void drawRange(const PlacedLevel& p, uint64_t begin, uint64_t end, bool cull,
               const OctahedralNormals& normals, Sink& sink, DrawCounts& counts) {
  const SurfelCollector& c = p.level->collector;
  const CollectorLayout& l = c.layout();
  const int shift = c.shift(), rb = l.positionBits - 4;
  const uint32_t low = (1u << shift) - 1, rmask = (1u << rb) - 1;
  const int normalShift = 3 * rb;
  const uint32_t normalMask = kHigh ? (1u << 2 * l.normalLevels) - 1 : (1u << l.normalBits()) - 1;
  const uint32_t* starts = c.starts();
  const uint8_t* tris = c.triangleTable();
  const float(&m)[3][4] = p.toCamera;
  uint32_t key = uint32_t(std::upper_bound(starts, starts + c.keys() + 1, begin) - starts) - 1;
  counts.drawn += end - begin;
  for (uint64_t i = begin; i < end; ++key) {
    const uint64_t bucketEnd = std::min<uint64_t>(end, starts[key + 1]);
    if (i >= bucketEnd) continue;
    if (p.culledOctants >> c.keyOctant(key) & 1) {  // the whole octant faces away
      counts.backfacing += bucketEnd - i;
      i = bucketEnd;
      continue;
    }
    uint32_t kx, ky, kz;
    c.keyPosition(key, kx, ky, kz);
    const uint32_t octantBits = kHigh ? c.keyOctant(key) << (2 * l.normalLevels) : 0u;
    for (; i < bucketEnd; ++i) {
      uint64_t data;
      if constexpr (kHigh) {
        const auto& w = c.words48()[i];
        data = uint64_t(w[0]) | uint64_t(w[1]) << 16 | uint64_t(w[2]) << 32;
      } else {
        data = c.words32()[i];
      }
      const uint32_t rx = uint32_t(data) & rmask, ry = uint32_t(data >> rb) & rmask,
                     rz = uint32_t(data >> 2 * rb) & rmask;
      const float x = float((rx & low) | kx | (rx >> shift) << (shift + 4));
      const float y = float((ry & low) | ky | (ry >> shift) << (shift + 4));
      const float z = float((rz & low) | kz | (rz >> shift) << (shift + 4));
      if (cull) {
        const glm::vec3& n =
            normals.decode((uint32_t(data >> normalShift) & normalMask) | octantBits);
        if (n.x * (x - p.eye.x) + n.y * (y - p.eye.y) + n.z * (z - p.eye.z) > 0.0f) {
          ++counts.backfacing;
          continue;
        }
      }
      const float cx = m[0][0] * x + m[0][1] * y + m[0][2] * z + m[0][3];
      const float cy = m[1][0] * x + m[1][1] * y + m[1][2] * z + m[1][3];
      const float cz = m[2][0] * x + m[2][1] * y + m[2][2] * z + m[2][3];
      sink.add(p.sprite, cx, cy, cz, p.idBase + readTriangle<TriT>(tris, i));
    }
  }
}

template <class Sink>
void drawJob(const PlacedLevel& p, const SurfelJob& j, bool cull, const OctahedralNormals& normals,
             Sink& sink, DrawCounts& counts) {
  const bool high = p.level->collector.quality() == CollectorQuality::kHigh;
  switch (p.level->collector.triangleBytes() * 2 + int(high)) {
    case 2:
      return drawRange<false, uint8_t>(p, j.begin, j.end, cull, normals, sink, counts);
    case 3:
      return drawRange<true, uint8_t>(p, j.begin, j.end, cull, normals, sink, counts);
    case 4:
      return drawRange<false, uint16_t>(p, j.begin, j.end, cull, normals, sink, counts);
    case 5:
      return drawRange<true, uint16_t>(p, j.begin, j.end, cull, normals, sink, counts);
    case 8:
      return drawRange<false, uint32_t>(p, j.begin, j.end, cull, normals, sink, counts);
    default:
      return drawRange<true, uint32_t>(p, j.begin, j.end, cull, normals, sink, counts);
  }
}

template <bool kWide>
DrawCounts drawAll(std::span<const PlacedLevel> placed, std::span<const SurfelJob> jobs,
                   const Camera& camera, bool disc, bool cull, const OctahedralNormals& normals,
                   KeyBuffer& keys, int threads) {
  DrawCounts total;
#pragma omp parallel num_threads(threads)
  {
    Splatters<kWide> sink(camera, disc, keys);
    DrawCounts mine;
#pragma omp for schedule(dynamic, 1) nowait
    for (size_t k = 0; k < jobs.size(); ++k)
      drawJob(placed[jobs[k].placed], jobs[k], cull, normals, sink, mine);
    mine.splatted = sink.flush();
#pragma omp critical(surfel_counts)
    {
      total.drawn += mine.drawn;
      total.backfacing += mine.backfacing;
      total.splatted += mine.splatted;
    }
  }
  return total;
}

}  // namespace

DrawCounts drawSurfels(std::span<const PlacedLevel> placed, std::span<const SurfelJob> jobs,
                       const Camera& camera, bool disc, bool cullBackfaces,
                       const OctahedralNormals& normals, KeyBuffer& keys, int threads) {
  threads = std::max(threads, 1);
  return withKeyWidth(keys, [&]<bool kWide>() {
    return drawAll<kWide>(placed, jobs, camera, disc, cullBackfaces, normals, keys, threads);
  });
}

}  // namespace lzb::surfels
