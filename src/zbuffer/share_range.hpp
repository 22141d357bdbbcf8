#pragma once
// The contiguous part of the expanded-ID order that one rank draws.
#include <cstdint>

#include "src/core/renderer.hpp"

namespace lzb {

struct IdRange {
  uint64_t begin = 0, end = 0;  // [begin, end)
  bool overlaps(uint64_t b, uint64_t e) const { return b < end && begin < e; }
  bool contains(uint64_t b, uint64_t e) const { return begin <= b && e <= end; }
};

// Splits [0, total) into share.size chunks whose lengths differ by at most one, in rank order.
inline IdRange shareRange(uint64_t total, const WorkShare& share) {
  const uint64_t size = uint64_t(share.size), rank = uint64_t(share.rank);
  const uint64_t q = total / size, r = total % size;
  auto start = [&](uint64_t k) { return k * q + (k < r ? k : r); };
  return {start(rank), start(rank + 1)};
}

}  // namespace lzb
