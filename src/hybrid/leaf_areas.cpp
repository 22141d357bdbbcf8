#include "src/hybrid/leaf_areas.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "src/core/affine.hpp"
#include "src/core/timer.hpp"

namespace lzb::hybrid {

namespace {

// Spreads the low 21 bits of v to every third bit (a 63-bit Morton code from three of them).
uint64_t spreadBits(uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

// Morton code of every triangle's centroid in the mesh's bounds: sorting by it lists triangles
// along a space-filling curve, so consecutive list positions are close on the surface.
std::vector<uint64_t> mortonCodes(const Mesh& mesh) {
  Bounds b;
  for (const glm::vec3& p : mesh.positions) b.extend(glm::dvec3(p));
  const glm::dvec3 lo = b.lo, scale = 2097151.0 / glm::max(b.extent(), glm::dvec3(1e-300));
  std::vector<uint64_t> code(mesh.size());
  for (size_t t = 0; t < mesh.size(); ++t) {
    const glm::dvec3 c = (glm::dvec3(mesh.vertex(t, 0)) + glm::dvec3(mesh.vertex(t, 1)) +
                          glm::dvec3(mesh.vertex(t, 2))) / 3.0;
    const glm::dvec3 q = glm::clamp((c - lo) * scale, 0.0, 2097151.0);
    code[t] = spreadBits(uint64_t(q.x)) | spreadBits(uint64_t(q.y)) << 1 |
              spreadBits(uint64_t(q.z)) << 2;
  }
  return code;
}

// Sorts triangle indices along the curve (ties by index: the order is fixed).
void sortAlongCurve(std::vector<uint32_t>& tris, const std::vector<uint64_t>& code) {
  std::sort(tris.begin(), tris.end(), [&](uint32_t a, uint32_t b) {
    return code[a] < code[b] || (code[a] == code[b] && a < b);
  });
}

// Each triangle's area (node frame, double), as lzb's set-up measures it.
std::vector<double> triangleAreas(const Mesh& mesh) {
  std::vector<double> area(mesh.size());
  for (size_t t = 0; t < mesh.size(); ++t)
    area[t] = glm::length(localz::areaVector(mesh, uint32_t(t)));
  return area;
}

// Calls visit(n) for every node of the scene, each after the nodes it instances (an iterative
// depth-first post-order: the graph is acyclic).
template <class Visit>
void childrenFirst(const Scene& scene, Visit&& visit) {
  std::vector<uint8_t> done(scene.nodes.size(), 0);
  std::vector<std::pair<uint32_t, size_t>> stack;
  for (uint32_t start = 0; start < scene.nodes.size(); ++start) {
    if (done[start]) continue;
    stack.push_back({start, 0});
    while (!stack.empty()) {
      auto& [n, next] = stack.back();
      const std::vector<Instance>& instances = scene.nodes[n].instances;
      if (next < instances.size()) {
        const uint32_t child = instances[next++].node;
        if (!done[child]) stack.push_back({child, 0});
        continue;
      }
      visit(n);
      done[n] = 1;
      stack.pop_back();
    }
  }
}

}  // namespace

LeafAreas::LeafAreas(const localz::LzbAccel& accel) : accel_(accel) {
  const Scene& scene = accel.scene();
  nodes_.resize(scene.nodes.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (size_t n = 0; n < scene.nodes.size(); ++n) {
    const localz::NodeAccel& a = accel.node(uint32_t(n));
    const std::vector<double> area = triangleAreas(scene.nodes[n].mesh);
    PerNode& out = nodes_[n];
    for (double x : area) out.wholeMax = std::max(out.wholeMax, x);
    const uint32_t count = a.empty() ? 0 : a.octree().nodeCount();
    out.maxArea.assign(count, 0.0);
    out.leastLeafMax = std::numeric_limits<double>::infinity();
    for (uint32_t leaf = 0; leaf < count; ++leaf) {
      const std::span<const uint32_t> tris = a.leafTriangles(leaf);
      for (uint32_t t : tris) out.maxArea[leaf] = std::max(out.maxArea[leaf], area[t]);
      if (!tris.empty()) out.leastLeafMax = std::min(out.leastLeafMax, out.maxArea[leaf]);
    }
  }
  childrenFirst(scene, [&](uint32_t n) {
    PerNode& out = nodes_[n];
    const std::vector<Instance>& instances = scene.nodes[n].instances;
    const localz::NodeAccel& a = accel.node(n);
    out.subtreeMax = out.wholeMax;
    for (size_t i = 0; i < instances.size(); ++i)
      if (!a.empty() && a.instanceUsable(uint32_t(i)))
        out.subtreeMax =
            std::max(out.subtreeMax, nodes_[instances[i].node].subtreeMax *
                                         maxAreaScale(glm::dmat3(instances[i].transform)));
    out.flat = flatten(accel, n);
    flatTotal_ += out.flat.size();
  });
}

void LeafAreas::listAlongCurve(uint32_t node, Sampling& out) const {
  const localz::NodeAccel& a = accel_.node(node);
  const Mesh& mesh = accel_.scene().nodes[node].mesh;
  const std::vector<double> area = triangleAreas(mesh);
  const std::vector<uint64_t> code = mortonCodes(mesh);
  // Appends tris (sorted along the curve) to order and their running area sums to prefix.
  const auto list = [&](std::vector<uint32_t> tris, std::vector<uint32_t>& order,
                        std::vector<double>& prefix) {
    sortAlongCurve(tris, code);
    double sum = 0.0;
    for (uint32_t t : tris) {
      order.push_back(t);
      prefix.push_back(sum += area[t]);
    }
  };
  std::vector<uint32_t> all(mesh.size());
  std::iota(all.begin(), all.end(), 0u);
  list(std::move(all), out.wholeOrder, out.wholePrefix);
  out.guide.resize(out.wholePrefix.size());
  for (size_t b = 0, j = 0; b < out.guide.size(); ++b) {
    const double bound = double(b) * out.wholePrefix.back() / double(out.guide.size());
    while (j + 1 < out.wholePrefix.size() && !(out.wholePrefix[j] > bound)) ++j;
    out.guide[b] = uint32_t(j);
  }
  const uint32_t count = a.empty() ? 0 : a.octree().nodeCount();
  out.begin.assign(size_t(count) + 1, 0);
  for (uint32_t leaf = 0; leaf < count; ++leaf) {
    out.begin[leaf] = uint32_t(out.prefix.size());
    const std::span<const uint32_t> tris = a.leafTriangles(leaf);
    list(std::vector<uint32_t>(tris.begin(), tris.end()), out.order, out.prefix);
  }
  out.begin[count] = uint32_t(out.prefix.size());
}

void LeafAreas::prepareSampling() const {
  if (prepared_) return;
  Stopwatch clock;
  std::vector<Sampling> built(nodes_.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (size_t n = 0; n < nodes_.size(); ++n) listAlongCurve(uint32_t(n), built[n]);
  childrenFirst(accel_.scene(), [&](uint32_t n) {
    Sampling& out = built[n];
    double sum = out.wholePrefix.empty() ? 0.0 : out.wholePrefix.back();
    out.flatPrefix.assign(1, sum);
    for (const FlatInstance& f : nodes_[n].flat)
      out.flatPrefix.push_back(sum +=
                               built[f.node].flatPrefix.back() * maxAreaScale(f.transform.a));
  });
  sampling_ = std::move(built);
  prepared_ = true;
  samplingSeconds_ = clock.seconds();
}

std::vector<LeafAreas::FlatInstance> LeafAreas::flatten(const localz::LzbAccel& accel,
                                                        uint32_t node) const {
  const Scene& scene = accel.scene();
  const auto usableInstances = [&](uint32_t n, auto&& visit) {
    const localz::NodeAccel& a = accel.node(n);
    for (size_t i = 0; i < scene.nodes[n].instances.size(); ++i)
      if (!a.empty() && a.instanceUsable(uint32_t(i))) visit(uint32_t(i));
  };
  const auto instancesOnly = [&](uint32_t n) {
    return scene.nodes[n].mesh.empty() && !scene.nodes[n].instances.empty();
  };
  std::vector<FlatInstance> entries;
  usableInstances(node, [&](uint32_t i) {
    const Instance& inst = scene.nodes[node].instances[i];
    entries.push_back({inst.node, Affine::from(inst.transform),
                       accel.node(node).instanceInverse(i), scene.childOffset(node, i)});
  });
  for (;;) {  // one more level of instance-only nodes while the budget allows
    size_t next = 0;
    bool deeper = false;
    for (const FlatInstance& e : entries) {
      if (!instancesOnly(e.node)) {
        ++next;
        continue;
      }
      deeper = true;
      usableInstances(e.node, [&](uint32_t) { ++next; });
    }
    if (!deeper || next > kFlatBudget || flatTotal_ + next > kFlatTotal) return entries;
    std::vector<FlatInstance> expanded;
    expanded.reserve(next);
    for (const FlatInstance& e : entries) {
      if (!instancesOnly(e.node)) {
        expanded.push_back(e);
        continue;
      }
      usableInstances(e.node, [&](uint32_t j) {
        const Instance& inst = scene.nodes[e.node].instances[j];
        expanded.push_back({inst.node, e.transform * Affine::from(inst.transform),
                            accel.node(e.node).instanceInverse(j) * e.inverse,
                            e.idOffset + scene.childOffset(e.node, j)});
      });
    }
    entries = std::move(expanded);
  }
}

uint64_t LeafAreas::memoryBytes() const {
  uint64_t bytes = 0;
  for (const PerNode& n : nodes_)
    bytes += n.maxArea.size() * sizeof(double) + n.flat.size() * sizeof(FlatInstance);
  for (const Sampling& n : sampling_)
    bytes += (n.begin.size() + n.order.size() + n.wholeOrder.size() + n.guide.size()) *
                 sizeof(uint32_t) +
             (n.prefix.size() + n.wholePrefix.size() + n.flatPrefix.size()) * sizeof(double);
  return bytes;
}

}  // namespace lzb::hybrid
