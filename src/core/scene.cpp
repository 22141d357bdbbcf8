#include "src/core/scene.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "src/core/error.hpp"

namespace lzb {

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Saturating add: expanded counts of absurd nested scenes stay at UINT64_MAX instead of wrapping.
uint64_t addSat(uint64_t a, uint64_t b) { return a > ~uint64_t(0) - b ? ~uint64_t(0) : a + b; }

}  // namespace

bool Mesh::add(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, Rgba8 color) {
  if (!finite(a) || !finite(b) || !finite(c)) return false;
  // Double precision so triangles at 1e-20 scale do not underflow to a zero normal.
  glm::dvec3 n = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
  double len = glm::length(n);
  if (!(len > 0.0) || !std::isfinite(len)) return false;
  positions.insert(positions.end(), {a, b, c});
  normals.push_back(glm::vec3(n / len));
  colors.push_back(color);
  return true;
}

void Mesh::append(const Mesh& other) {
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  normals.insert(normals.end(), other.normals.begin(), other.normals.end());
  colors.insert(colors.end(), other.colors.begin(), other.colors.end());
}

uint32_t Scene::addNode(std::string name) {
  nodes.push_back(Node{std::move(name), {}, {}});
  return uint32_t(nodes.size() - 1);
}

void Scene::finalize() {
  require(!nodes.empty() && root < nodes.size(), source, "scene has no root node");
  const size_t n = nodes.size();
  expandedCount.assign(n, 0);
  nodeBounds.assign(n, Bounds{});
  instanceOffsets.assign(n, {});
  enum : uint8_t { kNew, kActive, kDone };
  std::vector<uint8_t> state(n, kNew);
  // Post-order DFS: children are finished before their parents use them.
  std::function<void(uint32_t)> visit = [&](uint32_t i) {
    state[i] = kActive;
    Node& node = nodes[i];
    uint64_t count = node.mesh.size();
    Bounds b;
    for (const glm::vec3& p : node.mesh.positions) b.extend(glm::dvec3(p));
    for (const Instance& inst : node.instances) {
      instanceOffsets[i].push_back(count);
      require(inst.node < n, source, "node '" + node.name + "' references a missing node");
      require(state[inst.node] != kActive, source,
              "instancing cycle through node '" + nodes[inst.node].name + "'");
      if (state[inst.node] == kNew) visit(inst.node);
      count = addSat(count, expandedCount[inst.node]);
      b.extend(nodeBounds[inst.node].transformed(inst.transform));
    }
    expandedCount[i] = count;
    nodeBounds[i] = b;
    state[i] = kDone;
  };
  visit(root);
}

uint64_t Scene::uniqueTriangles() const {
  uint64_t total = 0;
  for (const Node& node : nodes) total += node.mesh.size();
  return total;
}

std::optional<Scene::TriangleRef> Scene::resolve(uint64_t id) const {
  if (id >= expandedTriangles()) return std::nullopt;
  TriangleRef ref{root, 0, glm::dmat4(1.0)};
  for (;;) {
    const Node& node = nodes[ref.node];
    if (id < node.mesh.size()) {
      ref.triangle = uint32_t(id);
      return ref;
    }
    // The last instance whose expanded list starts at or before id.
    const std::vector<uint64_t>& offsets = instanceOffsets[ref.node];
    const size_t k = size_t(std::upper_bound(offsets.begin(), offsets.end(), id) - offsets.begin()) - 1;
    id -= offsets[k];
    ref.transform = ref.transform * node.instances[k].transform;
    ref.node = node.instances[k].node;
  }
}

std::vector<DrawItem> flattenScene(const Scene& scene) {
  std::vector<DrawItem> items;
  std::function<void(uint32_t, const glm::dmat4&, uint64_t)> visit =
      [&](uint32_t i, const glm::dmat4& m, uint64_t base) {
        const Node& node = scene.nodes[i];
        if (!node.mesh.empty()) items.push_back({i, m, base});
        uint64_t offset = base + node.mesh.size();
        for (const Instance& inst : node.instances) {
          visit(inst.node, m * inst.transform, offset);
          offset += scene.expandedCount[inst.node];
        }
      };
  visit(scene.root, glm::dmat4(1.0), 0);
  return items;
}

}  // namespace lzb
