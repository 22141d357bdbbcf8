#include "src/regions/region_cut.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lzb::regions {

uint32_t regionCount(uint32_t asked, uint64_t uniqueTriangles, bool onePart) {
  if (asked) return asked;
  const int shift = onePart ? 16 : 20;
  return uint32_t(std::clamp<uint64_t>(uniqueTriangles >> shift, 16, 4096));
}

namespace {

// Halves with more units than this are split as tasks of their own.
constexpr size_t kParallelUnits = size_t(1) << 16;

// Splits the units order[begin, end) into regions [first, first + count).
void splitRange(std::span<const glm::dvec3> centres, std::span<const uint64_t> triangles,
                std::vector<uint32_t>& order, size_t begin, size_t end, uint32_t first,
                uint32_t count, std::vector<uint32_t>& regionOf) {
  if (count == 1 || end - begin <= 1) {
    for (size_t i = begin; i < end; ++i) regionOf[order[i]] = first;
    return;
  }
  glm::dvec3 boxLo(std::numeric_limits<double>::max());
  glm::dvec3 boxHi(std::numeric_limits<double>::lowest());
  for (size_t i = begin; i < end; ++i) {
    boxLo = glm::min(boxLo, centres[order[i]]);
    boxHi = glm::max(boxHi, centres[order[i]]);
  }
  const glm::dvec3 extent = boxHi - boxLo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  const auto before = [&](uint32_t a, uint32_t b) {
    const double ca = centres[a][axis], cb = centres[b][axis];
    return ca < cb || (ca == cb && a < b);
  };
  const auto at = [&](size_t i) { return order.begin() + ptrdiff_t(i); };
  const auto weight = [&](uint32_t u) -> uint64_t { return triangles.empty() ? 1 : triangles[u]; };
  uint64_t total = 0;
  for (size_t i = begin; i < end; ++i) total += weight(order[i]);
  const uint32_t left = count / 2;
  // The cut: the first unit whose triangles, with those before it, pass the left regions'
  // share. Units of one triangle each: its index. Else found by halving [lo, hi) with
  // selections (O(n) in all), never a full sort.
  const long double target = (long double)total * left / count;
  size_t lo = begin;
  if (triangles.empty()) {
    lo = std::min(end, begin + size_t(std::max(0.0L, std::ceil(target - 0.5L))));
  } else {
    long double costBefore = 0.0L;  // of order[begin, lo)
    size_t hi = end;
    while (hi - lo > 1) {
      const size_t mid = lo + (hi - lo) / 2;
      std::nth_element(at(lo), at(mid), at(hi), before);
      long double c = 0.0L;
      for (size_t i = lo; i < mid; ++i) c += weight(order[i]);
      if (costBefore + c + 0.5L * weight(order[mid]) < target) {
        costBefore += c + weight(order[mid]);
        lo = mid + 1;
      } else {
        hi = mid;
      }
    }
    if (hi - lo == 1 && costBefore + 0.5L * weight(order[lo]) < target) ++lo;
  }
  const size_t cut = std::clamp(lo, begin + 1, end - 1);
  // order[begin, cut) must be the cut's smallest units, whatever the halving left in place.
  std::nth_element(at(begin), at(cut), at(end), before);
  // The halves touch disjoint ranges of order and regionOf: large ones split side by side.
#pragma omp task default(shared) if (cut - begin > kParallelUnits)
  splitRange(centres, triangles, order, begin, cut, first, left, regionOf);
  splitRange(centres, triangles, order, cut, end, first + left, count - left, regionOf);
#pragma omp taskwait
}

}  // namespace

std::vector<uint32_t> splitIntoRegions(std::span<const glm::dvec3> centres,
                                       std::span<const uint64_t> triangles, uint32_t regions) {
  std::vector<uint32_t> order(centres.size()), regionOf(centres.size(), 0);
  for (uint32_t u = 0; u < order.size(); ++u) order[u] = u;
  if (regions > 0) {
#pragma omp parallel
#pragma omp single
    splitRange(centres, triangles, order, 0, order.size(), 0, regions, regionOf);
  }
  return regionOf;
}

std::vector<int> regionOwners(std::span<const uint64_t> regionTriangles, int ranks) {
  // Greedy list scheduling in the k-d order: equal regions go round-robin.
  std::vector<uint64_t> held(size_t(std::max(ranks, 1)), 0);
  std::vector<int> owner(regionTriangles.size());
  for (size_t r = 0; r < regionTriangles.size(); ++r) {
    const size_t least = size_t(std::min_element(held.begin(), held.end()) - held.begin());
    held[least] += regionTriangles[r];
    owner[r] = int(least);
  }
  return owner;
}

std::vector<uint32_t> regionsOfRank(std::span<const uint64_t> regionTriangles,
                                    const WorkShare& share) {
  const std::vector<int> owner = regionOwners(regionTriangles, share.size);
  std::vector<uint32_t> mine;
  for (uint32_t r = 0; r < owner.size(); ++r)
    if (owner[r] == share.rank) mine.push_back(r);
  return mine;
}

RegionCut cutIntoRegions(std::span<const glm::dvec3> centres, std::span<const uint64_t> triangles,
                         uint32_t regions) {
  RegionCut cut;
  cut.regionOf = splitIntoRegions(centres, triangles, regions);
  cut.regionTriangles.assign(regions, 0);
  for (size_t u = 0; u < cut.regionOf.size(); ++u)
    cut.regionTriangles[cut.regionOf[u]] += triangles.empty() ? 1 : triangles[u];
  return cut;
}

std::vector<uint64_t> trianglesPerRank(std::span<const uint64_t> regionTriangles, int ranks) {
  std::vector<uint64_t> held(size_t(ranks), 0);
  const std::vector<int> owner = regionOwners(regionTriangles, ranks);
  for (size_t r = 0; r < owner.size(); ++r) held[size_t(owner[r])] += regionTriangles[r];
  return held;
}

}  // namespace lzb::regions
