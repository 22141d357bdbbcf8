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

int shareRankOf(uint64_t item, uint64_t total, int size) {
  const uint64_t q = total / uint64_t(size), r = total % uint64_t(size);
  // The first r ranks hold q + 1 items, the others q.
  if (item < r * (q + 1)) return int(item / (q + 1));
  return int(r + (item - r * (q + 1)) / q);
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

}  // namespace lzb
