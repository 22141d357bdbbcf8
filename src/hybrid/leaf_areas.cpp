#include "src/hybrid/leaf_areas.hpp"

#include <algorithm>
#include <numeric>

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

}  // namespace

LeafAreas::LeafAreas(const LzbAccel& accel) {
  const Scene& scene = accel.scene();
  nodes_.resize(scene.nodes.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (size_t n = 0; n < scene.nodes.size(); ++n) {
    const NodeAccel& a = accel.node(uint32_t(n));
    const Mesh& mesh = scene.nodes[n].mesh;
    PerNode& out = nodes_[n];
    std::vector<double> area(mesh.size());
    for (size_t t = 0; t < mesh.size(); ++t) {
      const glm::dvec3 v0(mesh.vertex(t, 0)), v1(mesh.vertex(t, 1)), v2(mesh.vertex(t, 2));
      area[t] = 0.5 * glm::length(glm::cross(v1 - v0, v2 - v0));
      out.wholeMax = std::max(out.wholeMax, area[t]);
    }
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
    const uint32_t count = a.empty() ? 0 : a.octree().nodeCount();
    out.begin.assign(size_t(count) + 1, 0);
    out.maxArea.assign(count, 0.0);
    for (uint32_t leaf = 0; leaf < count; ++leaf) {
      out.begin[leaf] = uint32_t(out.prefix.size());
      const std::span<const uint32_t> tris = a.leafTriangles(leaf);
      for (uint32_t t : tris) out.maxArea[leaf] = std::max(out.maxArea[leaf], area[t]);
      list(std::vector<uint32_t>(tris.begin(), tris.end()), out.order, out.prefix);
    }
    out.begin[count] = uint32_t(out.prefix.size());
  }
}

uint64_t LeafAreas::memoryBytes() const {
  uint64_t bytes = 0;
  for (const PerNode& n : nodes_)
    bytes += (n.begin.size() + n.order.size() + n.wholeOrder.size()) * sizeof(uint32_t) +
             (n.prefix.size() + n.maxArea.size() + n.wholePrefix.size()) * sizeof(double);
  return bytes;
}

}  // namespace lzb::hybrid
