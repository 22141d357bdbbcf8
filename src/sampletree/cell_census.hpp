#pragma once
// The counting passes of the external construction (section 5.1): |P(u)| and A(P(u)) of the
// octree's cells, found by following each streamed triangle down the same child rule as the
// in-memory build (childOctant), without holding the triangles. Cells are counted a few levels per
// pass, and a pass descends only below cells found too large for a bucket, so the census stays
// small: it classifies cells into the top levels (built last, in memory) and buckets (subtrees
// whose triangles fit the memory budget, built one at a time).
#include <array>
#include <cstdint>
#include <unordered_map>

#include "src/sampletree/cell_octree.hpp"
#include "src/sampletree/triangle_stream.hpp"

namespace lzb::sampletree {

struct CellKey {
  uint8_t level = 0;
  uint32_t cell[3] = {0, 0, 0};
  bool operator==(const CellKey& o) const {
    return level == o.level && cell[0] == o.cell[0] && cell[1] == o.cell[1] && cell[2] == o.cell[2];
  }
  CellKey child(int octant) const;
  CellKey parent() const;  // of a cell below the root
};
struct CellKeyHash {
  size_t operator()(const CellKey& k) const;
};

// Follows triangle t down the octree of `frame` (origin and size): calls visit(cell) from the root
// on, going on into the child that takes t while visit returns true; stops where t stays in a
// cell (no child takes it) or at kMaxLevel.
template <class Visit>
void descend(const StreamTriangle& t, const CellOctree& frame, Visit&& visit);

// The last cell looked up on each level and what was found for it: consecutive triangles mostly
// share their path (an object's triangles, a terrain row), so most hash lookups are skipped.
template <class V>
class PathMemo {
 public:
  template <class Find>
  V get(const CellKey& k, Find&& find) {
    Entry& e = entries_[k.level];
    if (!e.set || !(e.key == k)) e = {k, find(k), true};
    return e.value;
  }

 private:
  struct Entry {
    CellKey key;
    V value{};
    bool set = false;
  };
  std::array<Entry, kMaxLevel + 1> entries_{};
};

struct CellStat {
  uint64_t count = 0;  // |P(u)|
  double area = 0.0;   // A(P(u)), summed in input order as the in-memory build sums it
};

// What a counting pass hands on: every triangle with the deepest cell it reached in that pass
// (the external build spills it there, so the last counting pass is also the writing pass).
class CensusSink {
 public:
  virtual ~CensusSink() = default;
  virtual void beginPass() = 0;
  virtual void add(const StreamTriangle& t, const CellKey& deepest) = 0;
};

class CellCensus {
 public:
  // Passes over `in` until every cell on a path is classified; a cell above bucketTriangles is a
  // top cell (split, unless at kMaxLevel). Each pass's triangles go to `sink` when given.
  CellCensus(const TriangleStream& in, const CellOctree& frame, uint64_t bucketTriangles,
             CensusSink* sink = nullptr);
  // The cell's statistics; nullptr when no triangle reaches it.
  const CellStat* find(const CellKey& k) const;
  // Split in the in-memory build too: more than a bucket holds (more than a leaf), above kMaxLevel.
  bool top(const CellKey& k) const;

 private:
  void pass(const TriangleStream& in, const CellOctree& frame, int lo, int hi);
  bool top(const CellKey& k, const CellStat& s) const;
  std::unordered_map<CellKey, CellStat, CellKeyHash> stats_;
  uint64_t bucketTriangles_;
  CensusSink* sink_;
};

template <class Visit>
void descend(const StreamTriangle& t, const CellOctree& frame, Visit&& visit) {
  const glm::dvec3 a(t.v[0]), b(t.v[1]), c(t.v[2]);
  const glm::dvec3 centroid = centroidOf(a, b, c);
  CellKey key;
  while (visit(static_cast<const CellKey&>(key)) && key.level < kMaxLevel) {
    // The same expressions as the in-memory Builder, so the same doubles.
    const double s = frame.size / double(uint64_t(1) << key.level);
    const glm::dvec3 centre =
        frame.origin + s * (glm::dvec3(key.cell[0], key.cell[1], key.cell[2]) + 0.5);
    const int o =
        childOctant(centroid, a, b, c, centre, 0.5 * frame.size / double(uint64_t(1) << key.level));
    if (o < 0) return;
    key = key.child(o);
  }
}

}  // namespace lzb::sampletree
