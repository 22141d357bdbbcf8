#include "mpi/decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "src/core/error.hpp"

namespace lzb {

IdRange shareRange(uint64_t total, const WorkShare& share) {
  const uint64_t size = uint64_t(share.size), rank = uint64_t(share.rank);
  const uint64_t q = total / size, r = total % size;
  auto start = [&](uint64_t k) { return k * q + (k < r ? k : r); };
  return {start(rank), start(rank + 1)};
}

std::vector<int> ScreenTiles::owned(const WorkShare& share) const {
  std::vector<int> out;
  for (int t = share.rank; t < count(); t += share.size) out.push_back(t);
  return out;
}

TileDeal parseTileDeal(const std::string& text, const std::string& field) {
  if (text == "interleaved") return TileDeal::kInterleaved;
  if (text == "cost") return TileDeal::kCost;
  throw InputError(field + ": expected interleaved or cost, got '" + text + "'");
}

std::string toString(TileDeal deal) {
  return deal == TileDeal::kCost ? "cost" : "interleaved";
}

std::string tileDealText(TileDeal deal) {
  return deal == TileDeal::kCost
             ? "by cost (contiguous runs of equal ray count, counted alike on every rank)"
             : "interleaved (tile index mod ranks == rank)";
}

std::vector<int> ScreenTiles::ownedByCost(std::span<const double> costs,
                                          const WorkShare& share) const {
  const std::vector<uint32_t> mine = dealByCost(costs, share);
  return {mine.begin(), mine.end()};
}

std::vector<uint32_t> dealByCost(std::span<const double> costs, const WorkShare& share) {
  std::vector<uint32_t> mine;
  if (share.size <= 1) {
    mine.resize(costs.size());
    for (uint32_t i = 0; i < mine.size(); ++i) mine[i] = i;
    return mine;
  }
  double total = 0.0;
  for (double c : costs) total += c;
  double before = 0.0;
  for (uint32_t i = 0; i < costs.size(); ++i) {
    const double mid = total > 0.0 ? (before + 0.5 * costs[i]) / total : 0.0;
    const int rank = std::min(share.size - 1, int(std::floor(mid * share.size)));
    if (rank == share.rank) mine.push_back(i);
    before += costs[i];
  }
  return mine;
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

std::vector<uint32_t> regionsOfRank(std::span<const uint64_t> regionTriangles,
                                    const WorkShare& share) {
  // Greedy list scheduling in the k-d order: equal regions go round-robin.
  std::vector<uint64_t> held(size_t(std::max(share.size, 1)), 0);
  std::vector<uint32_t> mine;
  for (uint32_t r = 0; r < regionTriangles.size(); ++r) {
    const size_t least = size_t(std::min_element(held.begin(), held.end()) - held.begin());
    held[least] += regionTriangles[r];
    if (int(least) == share.rank) mine.push_back(r);
  }
  return mine;
}

}  // namespace lzb
