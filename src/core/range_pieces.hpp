#pragma once
// Ranges numbered end to end: range r holds the global indices [first[r], first[r + 1]). Work
// shared in fixed-size chunks of the global numbering (not per range) stays balanced whether a
// frame is one long range or 10^5 short ones.
#include <algorithm>
#include <cstdint>
#include <vector>

namespace lzb {

// first[r]: the global index of range r's first element; first.back() the total.
template <class Range>
std::vector<uint64_t> rangeStarts(const Range& ranges) {
  std::vector<uint64_t> first(ranges.size() + 1, 0);
  for (size_t r = 0; r < ranges.size(); ++r)
    first[r + 1] = first[r] + (ranges[r].end - ranges[r].begin);
  return first;
}

// Calls body(r, from, to) for the pieces of the ranges that global [begin, end) covers, with
// [from, to) local to range r.
template <class Body>
void forRangePieces(const std::vector<uint64_t>& first, uint64_t begin, uint64_t end, Body body) {
  // The last range starting at or before begin (empty ranges share their start).
  size_t r = size_t(std::upper_bound(first.begin(), first.end(), begin) - first.begin()) - 1;
  for (uint64_t g = begin; g < end; g = first[++r])
    body(r, size_t(g - first[r]), size_t(std::min(end, first[r + 1]) - first[r]));
}

}  // namespace lzb
