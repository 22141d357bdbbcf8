#include "src/regions/distributed_cut.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>

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

void allreduce(const mpi::Group& g, void* data, size_t n, MPI_Datatype type, MPI_Op op) {
  if (n) LZB_MPI_CALL(MPI_Allreduce(MPI_IN_PLACE, data, int(n), type, op, g.comm));
}

// The widest axis of each node's units over all ranks, as splitRange takes it.
std::vector<int> widestAxes(const mpi::Group& g, std::span<const glm::dvec3> centres,
                            const std::vector<uint32_t>& order, const std::vector<Node>& nodes) {
  // Per node: the least of each coordinate and of each coordinate negated (the greatest).
  std::vector<double> box(6 * nodes.size(), std::numeric_limits<double>::max());
  for (size_t a = 0; a < nodes.size(); ++a)
    for (size_t i = nodes[a].begin; i < nodes[a].end; ++i)
      for (int k = 0; k < 3; ++k) {
        const double c = centres[order[i]][k];
        box[6 * a + size_t(k)] = std::min(box[6 * a + size_t(k)], c);
        box[6 * a + 3 + size_t(k)] = std::min(box[6 * a + 3 + size_t(k)], -c);
      }
  allreduce(g, box.data(), box.size(), MPI_DOUBLE, MPI_MIN);
  std::vector<int> axes(nodes.size());
  for (size_t a = 0; a < nodes.size(); ++a) {
    const double* b = &box[6 * a];
    const glm::dvec3 extent = glm::dvec3(-b[3], -b[4], -b[5]) - glm::dvec3(b[0], b[1], b[2]);
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

// Local unit u's key on `axis`.
Key keyOf(std::span<const glm::dvec3> centres, uint64_t firstIndex, int axis, uint32_t u) {
  return Key(orderedBits(centres[u][axis])) << 64 | (firstIndex + u);
}

// Each node's want[a]-th least key over all ranks (1-based; keys are distinct): a radix select,
// 8 bits a round from the top, the node's candidates' counts per byte value all-reduced; a round
// keeps the candidates of the byte value that holds the wanted key.
std::vector<Key> cutKeys(const mpi::Group& g, std::span<const glm::dvec3> centres,
                         uint64_t firstIndex, const std::vector<int>& axes,
                         const std::vector<Node>& nodes, const std::vector<uint32_t>& order,
                         std::vector<uint64_t> want) {
  const size_t count = nodes.size();
  std::vector<std::vector<uint32_t>> candidates(count);
  for (size_t a = 0; a < count; ++a)
    candidates[a].assign(order.begin() + std::ptrdiff_t(nodes[a].begin),
                         order.begin() + std::ptrdiff_t(nodes[a].end));
  std::vector<Key> prefix(count, 0);
  std::vector<uint64_t> histogram(256 * count);
  for (int shift = 120; shift >= 0; shift -= 8) {
    std::fill(histogram.begin(), histogram.end(), 0);
#pragma omp parallel for schedule(dynamic)
    for (long a = 0; a < long(count); ++a)
      for (const uint32_t u : candidates[size_t(a)])
        ++histogram[256 * size_t(a) +
                    size_t(keyOf(centres, firstIndex, axes[size_t(a)], u) >> shift & 255)];
    allreduce(g, histogram.data(), histogram.size(), MPI_UINT64_T, MPI_SUM);
#pragma omp parallel for schedule(dynamic)
    for (long a = 0; a < long(count); ++a) {
      const uint64_t* h = &histogram[256 * size_t(a)];
      unsigned byte = 0;
      while (h[byte] < want[size_t(a)]) want[size_t(a)] -= h[byte++];
      prefix[size_t(a)] |= Key(byte) << shift;
      std::vector<uint32_t>& c = candidates[size_t(a)];
      c.erase(std::remove_if(c.begin(), c.end(),
                             [&](uint32_t u) {
                               return (keyOf(centres, firstIndex, axes[size_t(a)], u) >> shift &
                                       255) != byte;
                             }),
              c.end());
    }
  }
  return prefix;
}

}  // namespace

std::vector<uint32_t> splitIntoRegionsTogether(const mpi::Group& group,
                                               std::span<const glm::dvec3> centres,
                                               uint64_t firstIndex, uint32_t regions) {
  const size_t n = centres.size();
  std::vector<uint32_t> regionOf(n, 0), order(n);
  std::iota(order.begin(), order.end(), 0u);
  uint64_t total = n;
  allreduce(group, &total, 1, MPI_UINT64_T, MPI_SUM);
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
    std::vector<uint64_t> left(cut.size());
    for (size_t a = 0; a < cut.size(); ++a) left[a] = leftUnits(cut[a]);
    const std::vector<Key> at = cutKeys(group, centres, firstIndex, axes, cut, order, left);
    for (size_t a = 0; a < cut.size(); ++a) {
      const Node& node = cut[a];
      // The node's units with a key at or below the cut's go left.
      const auto first = order.begin() + std::ptrdiff_t(node.begin);
      const auto below = [&](uint32_t u) {
        return keyOf(centres, firstIndex, axes[a], u) <= at[a];
      };
      const size_t mid =
          node.begin +
          size_t(std::partition(first, order.begin() + std::ptrdiff_t(node.end), below) - first);
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
  allreduce(group, cut.regionTriangles.data(), regions, MPI_UINT64_T, MPI_SUM);
  return cut;
}

}  // namespace lzb::regions
