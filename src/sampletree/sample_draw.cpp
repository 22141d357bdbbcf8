#include "src/sampletree/sample_draw.hpp"

#include <algorithm>
#include <cmath>

#include "src/core/philox_stream.hpp"

namespace lzb::sampletree {

namespace {

// Node u's pool: the children's triangles in octant order, as prefix sums of their areas
// (reused per thread: a bucket samples thousands of nodes).
double poolPrefix(const CellOctree& tree, const BuildNode& node, const std::vector<double>& areas,
                  std::vector<double>& prefix) {
  prefix.clear();
  double total = 0.0;
  for (int32_t ch : node.child) {
    if (ch == kNoChild) continue;
    for (uint32_t t : tree.nodes[size_t(ch)].own) prefix.push_back(total += areas[t]);
  }
  return total;
}

// The drawings of node u from its children's triangles, moved into u.
void sampleNode(CellOctree& tree, size_t u, const std::vector<double>& areas, double c,
                const SampleStream& stream) {
  BuildNode& node = tree.nodes[u];
  const double side = tree.cellSize(node);
  node.draws = sampleDraws(sampleFactor(node.subtreeArea, side), c);
  thread_local std::vector<double> prefix;
  thread_local std::vector<char> chosen;
  const double total = poolPrefix(tree, node, areas, prefix);
  if (prefix.empty() || !(total > 0.0)) return;
  chosen.assign(prefix.size(), 0);
  const uint64_t key = nodeKey(node);
  for (uint32_t i = 0; i < node.draws; ++i) {
    const auto r = stream.draw(key, i);
    const double x = unit53(r.v[0], r.v[1]) * total;
    const size_t k = size_t(std::upper_bound(prefix.begin(), prefix.end(), x) - prefix.begin());
    chosen[std::min(prefix.size() - 1, k)] = 1;
  }
  // Move what was drawn, in pool order: into u, out of the children (their lists keep their order).
  size_t k = 0;
  for (int32_t ch : node.child) {
    if (ch == kNoChild) continue;
    std::vector<uint32_t>& own = tree.nodes[size_t(ch)].own;
    size_t w = 0;
    for (uint32_t t : own) {
      if (chosen[k++])
        node.own.push_back(t);
      else
        own[w++] = t;
    }
    own.resize(w);
  }
}

}  // namespace

uint64_t sampleFactor(double area, double side) {
  return std::max<uint64_t>(1, uint64_t(std::ceil(area / (side * side))));
}

uint32_t sampleDraws(uint64_t q, double c) {
  const double qd = double(q);
  const double m = std::ceil(qd * std::log(qd) + c * qd);
  return uint32_t(std::clamp(m, 0.0, 4294967295.0));
}

uint64_t nodeKey(const BuildNode& n) {
  uint64_t h = mix64(n.level);
  for (uint32_t x : n.cell) h = hashCombine(h, x);
  return h;
}

void drawSamples(CellOctree& tree, const std::vector<double>& areas, double c, uint64_t seed,
                 int threads) {
  const SampleStream stream(seed, kTimelessFrame);
  // Nodes of one level sample independently (each touches only itself and its children): levels
  // deepest first, the nodes of a level on all threads.
  int deepest = 0;
  for (const BuildNode& n : tree.nodes) deepest = std::max(deepest, int(n.level));
  std::vector<std::vector<size_t>> byLevel(size_t(deepest) + 1);
  for (size_t u = 0; u < tree.nodes.size(); ++u)
    if (!tree.nodes[u].leaf()) byLevel[tree.nodes[u].level].push_back(u);
  for (int level = deepest; level >= 0; --level) {
    const std::vector<size_t>& inner = byLevel[size_t(level)];
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::max(threads, 1))
    for (size_t k = 0; k < inner.size(); ++k) sampleNode(tree, inner[k], areas, c, stream);
  }
}

}  // namespace lzb::sampletree
