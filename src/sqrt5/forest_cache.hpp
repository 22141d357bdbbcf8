#pragma once
// The per-object cache of sqrt(5) sample forests across frames (section 5.2). A line of an
// object's initial grid (a row of roots) keeps its forest: every sample's surface point and the
// images of its spawning vectors (node frame), and where it was refined, its children. The next
// frame walks the cached forest top-down, re-evaluates the undersampling factor from the cached
// points (a matrix product each, no surface evaluation), descends into cached children where it
// still refines, and evaluates new children only where it refines further than before.
//
// The cached and the fresh walk compute F from the same doubles (the node-frame points mapped by
// the same matrix), so the cache never changes a decision: the image does not depend on which
// rank cached which line. A line is keyed by (node, ID base, initial grid side, line); the sector
// of a terrain moves with the camera, so terrains in a sector are not cached. Lines a frame did
// not use are dropped after it, and everything when the cache exceeds its budget.
#include <cstdint>
#include <algorithm>
#include <map>
#include <tuple>
#include <vector>

#include "src/sqrt5/refine.hpp"

namespace lzb::sqrt5 {

struct ForestSample {
  glm::dvec2 uv;
  glm::dvec3 p, pu, pv;  // node frame: the point and the points at uv + u_level, uv + v_level
  uint32_t first = 0;    // children [first, first + count) (the self copy first), when refined
  uint16_t count = 0;
  int16_t level = 0;
};

struct CachedLine {
  std::vector<ForestSample> samples;  // the roots first, in order
  uint32_t roots = 0;
  bool used = false;
  uint64_t bytes() const { return samples.capacity() * sizeof(ForestSample); }
};

struct ForestCacheCounts {
  uint64_t hits = 0, misses = 0;
};

class ForestCache {
 public:
  using Key = std::tuple<uint32_t, uint64_t, int, uint64_t>;  // node, ID base, side, line
  // The line's entry, created empty when absent (serially, before the parallel draw).
  CachedLine& line(const Key& key) {
    CachedLine& l = lines_[key];
    l.used = true;
    return l;
  }
  // Drops the lines this frame did not use, and all when over `budgetBytes`.
  void endFrame(uint64_t budgetBytes);
  uint64_t bytes() const;
  uint64_t lineCount() const { return lines_.size(); }

 private:
  std::map<Key, CachedLine> lines_;
};

// Refines line `line` of `view`'s grid through the cache (as refineTree does, root by root) and
// calls sink(point, id, level) for each sample left on the surface.
template <class Sink>
void refineCachedLine(const ProceduralView& view, const Sqrt5Lattice& lattice, int line,
                      CachedLine& cache, std::vector<uint32_t>& stack,
                      std::vector<glm::dvec2>& kids, RefineCounts& counts, ForestCacheCounts& cc,
                      Sink&& sink) {
  const auto make = [&](const glm::dvec2& uv, int level, const glm::dvec3* p) {
    ForestSample s;
    s.uv = uv;
    s.level = int16_t(level);
    s.p = p ? *p : view.nodePoint(uv);
    s.pu = view.nodePoint(uv + lattice.u(level));
    s.pv = view.nodePoint(uv + lattice.v(level));
    ++cc.misses;
    if (!p) ++counts.generated;
    return s;
  };
  if (cache.roots == 0) {
    for (int i = 0; i <= lattice.initialSide(); ++i)
      cache.samples.push_back(make(lattice.root(i, line), 0, nullptr));
    cache.roots = uint32_t(cache.samples.size());
  } else {
    cc.hits += cache.roots;
  }
  counts.roots += cache.roots;
  for (uint32_t r = 0; r < cache.roots; ++r) {
    stack.assign(1, r);
    while (!stack.empty()) {
      const uint32_t k = stack.back();
      stack.pop_back();
      const ForestSample s = cache.samples[k];  // a copy: the vector may grow below
      const glm::dvec3 c = view.toView(s.p);
      if (view.undersampledBy(c, view.toView(s.pu) - c, view.toView(s.pv) - c)) {
        if (s.level < view.levels) {
          if (s.count == 0) {  // refined for the first time: the self copy, then the children
            kids.clear();
            lattice.children(s.uv, s.level, kids);
            const uint32_t first = uint32_t(cache.samples.size());
            cache.samples.push_back(make(s.uv, s.level + 1, &s.p));
            for (const glm::dvec2& kid : kids) cache.samples.push_back(make(kid, s.level + 1, nullptr));
            cache.samples[k].first = first;
            cache.samples[k].count = uint16_t(cache.samples.size() - first);
          } else {
            cc.hits += s.count;
          }
          ++counts.refined;
          const ForestSample& now = cache.samples[k];
          for (uint32_t j = now.first + now.count; j-- > now.first;) stack.push_back(j);
          continue;
        }
        ++counts.atLevelBound;
      }
      counts.deepest = std::max(counts.deepest, int(s.level));
      if (!view.onSurface(s.uv)) continue;
      ++counts.drawn;
      sink(c, view.id(s.uv), int(s.level));
    }
  }
}

}  // namespace lzb::sqrt5
