#include "src/regions/distributed_cut.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>

#include "mpi/collectives.hpp"

namespace lzb::regions {

namespace {

// (coordinate, index) in one unsigned number that orders as the serial cut's `before` does.
__extension__ typedef unsigned __int128 Key;

// A double's bits mapped so that unsigned order is numeric order (-0 taken as +0: they compare
// equal, and the index decides).
uint64_t orderedBits(double d) {
  if (d == 0.0) d = 0.0;
  const uint64_t u = std::bit_cast<uint64_t>(d);
  return u >> 63 ? ~u : u | (uint64_t(1) << 63);
}

// Units order[begin, end) of this rank, to be cut into regions [first, first + count) of a node
// holding `total` units over all ranks.
struct Node {
  uint32_t first, count;
  uint64_t total;
  size_t begin, end;
};

// The widest axis of each node's units over all ranks, as splitRange takes it.
std::vector<int> widestAxes(const mpi::Group& g, std::span<const glm::dvec3> centres,
                            const std::vector<uint32_t>& order, const std::vector<Node>& nodes) {
  std::vector<Bounds> boxes(nodes.size());
  for (size_t a = 0; a < nodes.size(); ++a)
    for (size_t i = nodes[a].begin; i < nodes[a].end; ++i) boxes[a].extend(centres[order[i]]);
  mpi::boundsOverRanks(g, boxes);
  std::vector<int> axes(nodes.size());
  for (size_t a = 0; a < nodes.size(); ++a) {
    const glm::dvec3 extent = boxes[a].extent();
    axes[a] = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  }
  return axes;
}

// How many of the node's units go to its left regions, as splitRange counts them.
uint64_t leftUnits(const Node& n) {
  const uint32_t left = n.count / 2;
  const long double target = (long double)n.total * left / n.count;
  const uint64_t at = std::min(n.total, uint64_t(std::max(0.0L, std::ceil(target - 0.5L))));
  return std::clamp<uint64_t>(at, 1, n.total - 1);
}

// Each node's keys on its axis, keys[i] that of unit order[i].
void keysOf(std::span<const glm::dvec3> centres, uint64_t firstIndex, const std::vector<int>& axes,
            const std::vector<Node>& nodes, const std::vector<uint32_t>& order,
            std::vector<Key>& keys) {
#pragma omp parallel for schedule(dynamic)
  for (long a = 0; a < long(nodes.size()); ++a)
    for (size_t i = nodes[size_t(a)].begin; i < nodes[size_t(a)].end; ++i)
      keys[i] =
          Key(orderedBits(centres[order[i]][axes[size_t(a)]])) << 64 | (firstIndex + order[i]);
}

// The round (bit shift) each node's select starts at: the leading bytes that the least and the
// greatest coordinate over all ranks share are every key's, so `prefix` holds them already.
std::vector<int> firstRounds(const mpi::Group& g, const std::vector<Node>& nodes,
                             const std::vector<Key>& keys, std::vector<Key>& prefix) {
  std::vector<uint64_t> least(2 * nodes.size(), ~uint64_t(0));  // the least, the greatest negated
  for (size_t a = 0; a < nodes.size(); ++a)
    for (size_t i = nodes[a].begin; i < nodes[a].end; ++i) {
      const uint64_t value = uint64_t(keys[i] >> 64);
      least[2 * a] = std::min(least[2 * a], value);
      least[2 * a + 1] = std::min(least[2 * a + 1], ~value);
    }
  mpi::allreduceInPlace(g, least.data(), least.size(), MPI_UINT64_T, MPI_MIN);
  std::vector<int> first(nodes.size());
  for (size_t a = 0; a < nodes.size(); ++a) {
    const uint64_t lo = least[2 * a], hi = ~least[2 * a + 1];
    const int shared = lo == hi ? 8 : std::countl_zero(lo ^ hi) / 8;  // leading bytes alike
    prefix[a] = shared ? Key(lo >> (64 - 8 * shared) << (64 - 8 * shared)) << 64 : Key(0);
    first[a] = 120 - 8 * shared;
  }
  return first;
}

// Each node's want[a]-th least key over all ranks (1-based; keys are distinct): a radix select,
// 8 bits a round from the first byte the node's keys do not all share, the node's candidates'
// counts per byte value all-reduced; a round keeps the candidates of the byte value that holds
// the wanted key.
std::vector<Key> cutKeys(const mpi::Group& g, const std::vector<Node>& nodes,
                         const std::vector<Key>& keys, std::vector<uint64_t> want) {
  const size_t count = nodes.size();
  std::vector<Key> prefix(count, 0);
  const std::vector<int> first = firstRounds(g, nodes, keys, prefix);
  std::vector<std::vector<uint32_t>> candidates(count);  // positions; none yet: the whole node
  std::vector<uint64_t> histogram(256 * count);
  for (int shift = *std::max_element(first.begin(), first.end()); shift >= 0; shift -= 8) {
    std::fill(histogram.begin(), histogram.end(), 0);
    const auto byteAt = [&](size_t i) { return size_t(keys[i] >> shift & 255); };
#pragma omp parallel for schedule(dynamic)
    for (long a = 0; a < long(count); ++a) {
      const Node& n = nodes[size_t(a)];
      uint64_t* h = &histogram[256 * size_t(a)];
      if (shift > first[size_t(a)]) continue;
      if (shift == first[size_t(a)])
        for (size_t i = n.begin; i < n.end; ++i) ++h[byteAt(i)];
      else
        for (const uint32_t i : candidates[size_t(a)]) ++h[byteAt(i)];
    }
    mpi::allreduceInPlace(g, histogram.data(), histogram.size(), MPI_UINT64_T, MPI_SUM);
#pragma omp parallel for schedule(dynamic)
    for (long a = 0; a < long(count); ++a) {
      if (shift > first[size_t(a)]) continue;
      const uint64_t* h = &histogram[256 * size_t(a)];
      size_t byte = 0;
      while (h[byte] < want[size_t(a)]) want[size_t(a)] -= h[byte++];
      prefix[size_t(a)] |= Key(byte) << shift;
      std::vector<uint32_t>& c = candidates[size_t(a)];
      if (shift == first[size_t(a)]) {
        for (size_t i = nodes[size_t(a)].begin; i < nodes[size_t(a)].end; ++i)
          if (byteAt(i) == byte) c.push_back(uint32_t(i));
      } else {
        c.erase(std::remove_if(c.begin(), c.end(), [&](uint32_t i) { return byteAt(i) != byte; }),
                c.end());
      }
    }
  }
  return prefix;
}

// Node n's units with a key at or below `at` moved before the others, each side in its order
// (units stay in rising index order, so the centres are read forwards); returns where the others
// start.
size_t partitionAt(const Node& n, Key at, std::vector<uint32_t>& order,
                   const std::vector<Key>& keys, std::vector<uint32_t>& above) {
  above.clear();
  size_t below = n.begin;
  for (size_t i = n.begin; i < n.end; ++i)
    if (keys[i] <= at)
      order[below++] = order[i];
    else
      above.push_back(order[i]);
  std::copy(above.begin(), above.end(), order.begin() + std::ptrdiff_t(below));
  return below;
}

}  // namespace

std::vector<uint32_t> splitIntoRegionsTogether(const mpi::Group& group,
                                               std::span<const glm::dvec3> centres,
                                               uint64_t firstIndex, uint32_t regions) {
  const size_t n = centres.size();
  std::vector<uint32_t> regionOf(n, 0), order(n), above;
  std::iota(order.begin(), order.end(), 0u);
  std::vector<Key> keys(n);
  uint64_t total = n;
  mpi::allreduceInPlace(group, &total, 1, MPI_UINT64_T, MPI_SUM);
  std::vector<Node> level;
  if (regions > 0) level.push_back({0, regions, total, 0, n});
  while (!level.empty()) {
    // A node of one region, or of one unit or none, is done (splitRange's first case).
    std::vector<Node> cut;
    for (const Node& node : level) {
      if (node.count > 1 && node.total > 1) {
        cut.push_back(node);
        continue;
      }
      for (size_t i = node.begin; i < node.end; ++i) regionOf[order[i]] = node.first;
    }
    level.clear();
    if (cut.empty()) break;
    const std::vector<int> axes = widestAxes(group, centres, order, cut);
    keysOf(centres, firstIndex, axes, cut, order, keys);
    std::vector<uint64_t> left(cut.size());
    for (size_t a = 0; a < cut.size(); ++a) left[a] = leftUnits(cut[a]);
    const std::vector<Key> at = cutKeys(group, cut, keys, left);
    for (size_t a = 0; a < cut.size(); ++a) {
      const Node& node = cut[a];
      // The node's units with a key at or below the cut's go left.
      const size_t mid = partitionAt(node, at[a], order, keys, above);
      const uint32_t leftRegions = node.count / 2;
      level.push_back({node.first, leftRegions, left[a], node.begin, mid});
      level.push_back({node.first + leftRegions, node.count - leftRegions, node.total - left[a],
                       mid, node.end});
    }
  }
  return regionOf;
}

RegionCut cutIntoRegionsTogether(const mpi::Group& group, std::span<const glm::dvec3> centres,
                                 uint64_t firstIndex, uint32_t regions) {
  RegionCut cut;
  cut.regionOf = splitIntoRegionsTogether(group, centres, firstIndex, regions);
  cut.regionTriangles.assign(regions, 0);
  for (const uint32_t r : cut.regionOf) ++cut.regionTriangles[r];
  mpi::allreduceInPlace(group, cut.regionTriangles.data(), regions, MPI_UINT64_T, MPI_SUM);
  return cut;
}

}  // namespace lzb::regions
