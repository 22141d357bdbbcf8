#include "src/rzb/sample_cache.hpp"

#include <algorithm>
#include <cmath>

#include "src/rzb/box_sampler.hpp"

namespace lzb::rzb {

namespace {

// Grid cell side in splats (pixels at d = 1) at the set's density.
constexpr double kCellSplats = 1.0;

uint16_t toSnorm(double v) { return uint16_t(std::lround((std::clamp(v, -1.0, 1.0) * 0.5 + 0.5) * 65535.0)); }
double fromSnorm(uint16_t v) { return double(v) / 65535.0 * 2.0 - 1.0; }

}  // namespace

uint32_t encodeNormal(const glm::dvec3& n) {
  const double l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  if (!(l1 > 0.0)) return 0;
  double x = n.x / l1, y = n.y / l1;
  if (n.z < 0.0) {
    const double ox = (1.0 - std::abs(y)) * (x >= 0.0 ? 1.0 : -1.0);
    const double oy = (1.0 - std::abs(x)) * (y >= 0.0 ? 1.0 : -1.0);
    x = ox;
    y = oy;
  }
  return uint32_t(toSnorm(x)) | uint32_t(toSnorm(y)) << 16;
}

glm::vec3 decodeNormal(uint32_t code) {
  double x = fromSnorm(uint16_t(code)), y = fromSnorm(uint16_t(code >> 16));
  const double z = 1.0 - std::abs(x) - std::abs(y);
  if (z < 0.0) {
    const double ox = (1.0 - std::abs(y)) * (x >= 0.0 ? 1.0 : -1.0);
    const double oy = (1.0 - std::abs(x)) * (y >= 0.0 ? 1.0 : -1.0);
    x = ox;
    y = oy;
  }
  return glm::vec3(glm::normalize(glm::dvec3(x, y, z)));
}

int cacheLevel(double ppu) {
  return int(std::clamp(std::ceil(2.0 * std::log2(std::max(ppu, 1e-300))), -2000.0, 2000.0));
}

std::vector<CachedSample> buildSampleSet(const SelectedBox& box, int level, uint64_t seed,
                                         double samplesPerPixel, int splat, int threads,
                                         uint64_t* drawn) {
  SelectedBox b = box;
  b.key = hashCombine(box.key, uint64_t(int64_t(level)));
  const SampleStream stream(seed, kTimelessFrame);
  const double expected = box.area * std::ldexp(1.0, level) * samplesPerPixel;
  const double whole = std::floor(expected);
  const auto w = stream.draw(b.key, 0, kBoxRounding);
  const uint64_t n = uint64_t(whole) + (unit53(w[0], w[1]) < expected - whole ? 1 : 0);
  if (drawn) *drawn = n;
  std::vector<CachedSample> raw(n);
  constexpr uint64_t kChunk = 1 << 14;
  const long chunks = long((n + kChunk - 1) / kChunk);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (chunks > 1)
  for (long c = 0; c < chunks; ++c) {
    const uint64_t first = uint64_t(c) * kChunk, count = std::min(kChunk, n - first);
    uint64_t k = first;
    auto sink = [&](const glm::dvec3& p, const glm::dvec3& nrm, uint64_t id,
                    const DistributionTree*, uint32_t) {
      raw[k++] = CachedSample{glm::vec3(p), encodeNormal(nrm), id};
    };
    drawBoxSamples(b, stream, first, count, n, sink);
  }
  // Quantize to the grid (cells of kCellSplats splats at this level's pixels per unit, in the
  // box frame) and keep one point per cell: an open-addressing set of cell hashes.
  const double ppuLevel = std::exp2(0.5 * level);
  const double h = kCellSplats * double(splat) / (ppuLevel * std::max(box.stretch, 1e-300));
  const glm::dvec3 origin = box.tree->node(box.node).tight.lo;
  size_t cap = 16;
  while (cap < 2 * n) cap <<= 1;
  std::vector<uint64_t> table(cap, 0);
  std::vector<CachedSample> out;
  out.reserve(n / 4 + 16);
  for (const CachedSample& s : raw) {
    const glm::dvec3 g = glm::floor((glm::dvec3(s.p) - origin) / h);
    const uint64_t cell = hashCombine(hashCombine(uint64_t(int64_t(g.x)), uint64_t(int64_t(g.y))),
                                      uint64_t(int64_t(g.z))) | 1;
    size_t slot = size_t(cell) & (cap - 1);
    while (table[slot] != 0 && table[slot] != cell) slot = (slot + 1) & (cap - 1);
    if (table[slot] == cell) continue;
    table[slot] = cell;
    // Snapped to the cell centre: the kept points form a lattice whose projected spacing is at
    // most one splat, so every covered pixel keeps a point (the first sample's ID and normal).
    out.push_back(CachedSample{glm::vec3(origin + (g + 0.5) * h), s.normal, s.id});
  }
  out.shrink_to_fit();
  return out;
}

const std::vector<CachedSample>* SampleCache::lookup(uint64_t key, int level, uint64_t frame) {
  const auto it = map_.find(key);
  if (it == map_.end() || it->second.level != level) {
    ++counts_.misses;
    return nullptr;
  }
  ++counts_.hits;
  Entry& e = it->second;
  e.lastFrame = frame;
  lru_.splice(lru_.begin(), lru_, e.lru);
  return &e.samples;
}

void SampleCache::erase(std::unordered_map<uint64_t, Entry>::iterator it) {
  bytes_ -= bytesOf(it->second.samples);
  lru_.erase(it->second.lru);
  map_.erase(it);
}

const std::vector<CachedSample>* SampleCache::store(uint64_t key, int level,
                                                    std::vector<CachedSample>&& set,
                                                    uint64_t frame) {
  if (auto old = map_.find(key); old != map_.end()) erase(old);
  const uint64_t need = bytesOf(set);
  while (bytes_ + need > budget_ && !lru_.empty()) {
    const auto victim = map_.find(lru_.back());
    if (victim->second.lastFrame == frame) break;  // everything left is in use this frame
    erase(victim);
    ++counts_.evictions;
  }
  if (bytes_ + need > budget_) {
    ++counts_.uncached;
    return nullptr;
  }
  lru_.push_front(key);
  Entry& e = map_[key];
  e.level = level;
  e.lastFrame = frame;
  e.samples = std::move(set);
  e.lru = lru_.begin();
  bytes_ += need;
  return &e.samples;
}

}  // namespace lzb::rzb
