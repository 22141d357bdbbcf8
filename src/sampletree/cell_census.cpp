#include "src/sampletree/cell_census.hpp"

#include <algorithm>

#include "src/core/philox_stream.hpp"

namespace lzb::sampletree {

CellKey CellKey::child(int o) const {
  CellKey k;
  k.level = uint8_t(level + 1);
  k.cell[0] = 2 * cell[0] + uint32_t(o & 1);
  k.cell[1] = 2 * cell[1] + uint32_t(o >> 1 & 1);
  k.cell[2] = 2 * cell[2] + uint32_t(o >> 2 & 1);
  return k;
}

CellKey CellKey::parent() const {
  CellKey k;
  k.level = uint8_t(level - 1);
  for (int i = 0; i < 3; ++i) k.cell[i] = cell[i] >> 1;
  return k;
}

size_t CellKeyHash::operator()(const CellKey& k) const {
  // A marker bit above the level's 3 * level coordinate bits makes the packing unique (61 bits at
  // kMaxLevel); one mix, not one per coordinate (the census looks up every cell of every path).
  const int l = k.level;
  const uint64_t packed = uint64_t(1) << (3 * l) | uint64_t(k.cell[0]) << (2 * l) |
                          uint64_t(k.cell[1]) << l | uint64_t(k.cell[2]);
  return size_t(mix64(packed));
}

// Cells counted per pass: each pass descends kCensusLevels below the last pass's top cells.
constexpr int kCensusLevels = 5;

CellCensus::CellCensus(const TriangleStream& in, const CellOctree& frame, uint64_t bucketTriangles,
                       CensusSink* sink)
    : bucketTriangles_(bucketTriangles), sink_(sink) {
  for (int lo = 0; lo <= kMaxLevel; lo += kCensusLevels) {
    const int hi = std::min(lo + kCensusLevels - 1, kMaxLevel);
    pass(in, frame, lo, hi);
    const bool open = std::any_of(stats_.begin(), stats_.end(), [&](const auto& e) {
      return e.first.level == hi && top(e.first);
    });
    if (!open) break;
  }
}

void CellCensus::pass(const TriangleStream& in, const CellOctree& frame, int lo, int hi) {
  PathMemo<CellStat*> memo;  // map nodes stay put while others are inserted
  if (sink_) sink_->beginPass();
  in.forEach([&](std::span<const StreamTriangle> batch) {
    for (const StreamTriangle& t : batch) {
      const double area = triangleArea(t.v[0], t.v[1], t.v[2]);
      CellKey deepest;
      descend(t, frame, [&](const CellKey& k) {
        deepest = k;
        CellStat* s = memo.get(k, [&](const CellKey& key) { return &stats_[key]; });
        if (k.level < lo) return top(k, *s);  // counted by an earlier pass: go on below top cells
        ++s->count;
        s->area += area;
        return int(k.level) < hi;
      });
      if (sink_) sink_->add(t, deepest);
    }
  });
}

const CellStat* CellCensus::find(const CellKey& k) const {
  const auto it = stats_.find(k);
  return it == stats_.end() ? nullptr : &it->second;
}

bool CellCensus::top(const CellKey& k) const {
  const CellStat* s = find(k);
  return s && top(k, *s);
}

bool CellCensus::top(const CellKey& k, const CellStat& s) const {
  return s.count > bucketTriangles_ && k.level < kMaxLevel;
}

}  // namespace lzb::sampletree
