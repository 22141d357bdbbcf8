#pragma once
// The sample cache (Wand et al. section 7.2). Per selected box, a sample set drawn for a density
// level (sample counts in steps of 2: level L holds area * 2^L * samplesPerPixel samples, enough
// for pixels-per-unit up to 2^(L/2)) from a stream that does not depend on the frame, without
// back-face culling, quantized to a 3D grid in the box's frame whose cells project to at most one
// pixel (one splat) per side at that density (so at most sqrt(3) along the diagonal): each cell
// that received samples keeps one point at its centre, with the ID and normal of its first sample.
// A set is reused while the box needs the same level (its density within a factor 2 of the
// required one), and sets are evicted least-recently-used beyond a byte budget.
//
// Because the set a box uses depends only on (seed, box, level), never on which sets happen to
// be cached (so no hysteresis between levels), a rank or frame that rebuilds it gets the same
// samples as one that finds it cached: caching changes speed, never the image.
#include <cstdint>
#include <list>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "src/rzb/box_selection.hpp"

namespace lzb::rzb {

struct CachedSample {
  glm::vec3 p;      // box node frame
  uint32_t normal;  // octahedral, 2 x 16 bits, box node frame
  uint64_t id;
};
static_assert(sizeof(CachedSample) == 24);

uint32_t encodeNormal(const glm::dvec3& n);
glm::vec3 decodeNormal(uint32_t code);

// The density level a box needs this frame: ceil(2 log2(pixels per unit at zmin)).
int cacheLevel(double ppu);

// Builds the quantized sample set of box at `level` (threads: OpenMP threads for generation).
std::vector<CachedSample> buildSampleSet(const SelectedBox& box, int level, uint64_t seed,
                                         double samplesPerPixel, int splat, int threads,
                                         uint64_t* drawn = nullptr);

struct CacheCounts {
  uint64_t hits = 0, misses = 0, evictions = 0, uncached = 0;
};

class SampleCache {
 public:
  explicit SampleCache(uint64_t budgetBytes) : budget_(budgetBytes) {}

  // The set of box `key` built at `level`, or null. Marks it used.
  const std::vector<CachedSample>* lookup(uint64_t key, int level, uint64_t frame);
  // Stores a set built at level (replacing the box's older one), evicting least-recently-used
  // sets not used in this frame. Returns the stored set, or null (set left as it was) when it
  // does not fit.
  const std::vector<CachedSample>* store(uint64_t key, int level, std::vector<CachedSample>&& set,
                                         uint64_t frame);
  uint64_t bytes() const { return bytes_; }
  uint64_t budget() const { return budget_; }
  size_t entries() const { return map_.size(); }
  const CacheCounts& counts() const { return counts_; }

  static uint64_t bytesOf(const std::vector<CachedSample>& s) {
    return s.size() * sizeof(CachedSample) + 64;
  }

 private:
  struct Entry {
    int level;
    uint64_t lastFrame;
    std::vector<CachedSample> samples;
    std::list<uint64_t>::iterator lru;
  };
  void erase(std::unordered_map<uint64_t, Entry>::iterator it);

  uint64_t budget_, bytes_ = 0;
  std::unordered_map<uint64_t, Entry> map_;
  std::list<uint64_t> lru_;  // most recently used first
  CacheCounts counts_;
};

}  // namespace lzb::rzb
