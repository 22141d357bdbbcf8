#include "src/sampletree/tree_shading.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "src/core/range_pieces.hpp"
#include "src/core/shading.hpp"

namespace lzb::sampletree {

namespace {

// A bit per hash of an ID: most drawn triangles are not wanted, and one bit test says so.
class IdFilter {
 public:
  explicit IdFilter(const absl::flat_hash_set<uint64_t>& ids) : bits_(kWords, 0) {
    for (uint64_t id : ids) bits_[slot(id) >> 6] |= uint64_t(1) << (slot(id) & 63);
  }
  bool mayHold(uint64_t id) const { return bits_[slot(id) >> 6] >> (slot(id) & 63) & 1; }

 private:
  static constexpr int kBits = 20;
  static constexpr size_t kWords = (size_t(1) << kBits) / 64;
  static uint64_t slot(uint64_t id) { return (id * 0x9E3779B97F4A7C15ull) >> (64 - kBits); }
  std::vector<uint64_t> bits_;
};

}  // namespace

ShadingInputs shadingInputs(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  // Double precision, as Mesh::add, so small far triangles keep a normal.
  const glm::dvec3 n = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
  const double len = glm::length(n);
  ShadingInputs s;
  // A triangle collapsed by its world rounding has no normal: lit as if facing straight up.
  s.normal = len > 0.0 && std::isfinite(len) ? glm::vec3(n / len) : glm::vec3(0.0f, 1.0f, 0.0f);
  s.point = (a + b + c) / 3.0f;
  return s;
}

void TreeShading::addRepresentatives(const SampleTree& table, std::span<const uint32_t> nodes) {
  known_.reserve(known_.size() + nodes.size());
  for (uint32_t i : nodes) {
    const TreeNode& n = table.nodes[i];
    const ShadingInputs s{
        {n.representativeNormal[0], n.representativeNormal[1], n.representativeNormal[2]},
        {n.representativePoint[0], n.representativePoint[1], n.representativePoint[2]}};
    known_.try_emplace(n.representativeId, Entry{s, n.representativeColour});
  }
}

// The IDs fb shows that are not kept yet (each once).
absl::flat_hash_set<uint64_t> TreeShading::unknownShown(const Framebuffer& fb) const {
  absl::flat_hash_set<uint64_t> unknown;
  uint64_t last = kNoId;
  for (uint64_t id : fb.id) {
    if (id == last || id == kNoId) continue;
    last = id;
    if (!known_.contains(id)) unknown.insert(id);
  }
  return unknown;
}

void TreeShading::keepShown(const Framebuffer& fb, const ColouredSoup& soup, int threads) {
  const absl::flat_hash_set<uint64_t> want = unknownShown(fb);
  if (want.empty()) return;
  const IdFilter filter(want);
  std::vector<std::vector<uint64_t>> found(size_t(std::max(threads, 1)));  // triangle indices
  // One parallel loop over chunks of all the ranges: a frame in core draws ~10^5 short ones.
  const std::vector<uint64_t> first = rangeStarts(soup.ranges);
  constexpr uint64_t kChunk = 1 << 14;
  const int64_t chunks = int64_t((first.back() + kChunk - 1) / kChunk);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int64_t c = 0; c < chunks; ++c) {
    std::vector<uint64_t>& mine = found[size_t(omp_get_thread_num())];
    forRangePieces(first, uint64_t(c) * kChunk, std::min(first.back(), uint64_t(c + 1) * kChunk),
                   [&](size_t r, size_t from, size_t to) {
                     for (uint64_t t = soup.ranges[r].begin + from; t < soup.ranges[r].begin + to;
                          ++t) {
                       const uint64_t id = soup.ids[size_t(t)];
                       if (filter.mayHold(id) && want.contains(id)) mine.push_back(t);
                     }
                   });
  }
  for (const std::vector<uint64_t>& part : found)
    for (uint64_t t : part) {
      const glm::vec3* v = &soup.positions[3 * size_t(t)];
      known_.try_emplace(soup.ids[size_t(t)], Entry{shadingInputs(v[0], v[1], v[2]), soup.colours[size_t(t)]});
    }
}

void TreeShading::shade(const Camera& camera, const Light& light, Framebuffer& fb,
                        int threads) const {
  const glm::dvec3 eye = camera.position();
  const glm::vec3 toLight = lightDirection(light);
  const float ambient = float(light.ambient);
  const int64_t n = int64_t(fb.size());
  bool missing = false;
#pragma omp parallel num_threads(threads) reduction(|| : missing)
  {
    uint64_t lastId = kNoId;
    Rgba8 lastColour = kBackground;
#pragma omp for schedule(static)
    for (int64_t i = 0; i < n; ++i) {
      const uint64_t id = fb.id[size_t(i)];
      if (id != lastId) {
        lastId = id;
        lastColour = kBackground;
        if (id != kNoId) {
          const auto it = known_.find(id);
          if (it == known_.end()) {
            missing = true;
          } else {
            const Entry& e = it->second;
            const bool facing =
                glm::dot(glm::dvec3(e.inputs.normal), eye - glm::dvec3(e.inputs.point)) >= 0.0;
            lastColour = lzb::shade(e.colour, e.inputs.normal, facing, toLight, ambient);
          }
        }
      }
      fb.color[size_t(i)] = lastColour;
    }
  }
  if (missing) throw std::logic_error("sampletree: a pixel shows a triangle the frame did not keep");
}

}  // namespace lzb::sampletree
