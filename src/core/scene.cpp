#include "src/core/scene.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "src/core/error.hpp"

namespace lzb {

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The cross product and its length in double: the degeneracy test and the normal agree.
glm::dvec3 doubleCross(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  return glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
}

}  // namespace

glm::vec3 triangleNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::dvec3 n = doubleCross(a, b, c);
  const double len = glm::length(n);
  return len > 0.0 && std::isfinite(len) ? glm::vec3(n / len) : glm::vec3(0.0f);
}

bool Mesh::add(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, Rgba8 color) {
  if (!finite(a) || !finite(b) || !finite(c)) return false;
  const double len = glm::length(doubleCross(a, b, c));
  if (!(len > 0.0) || !std::isfinite(len)) return false;
  positions.insert(positions.end(), {a, b, c});
  colors.push_back(color);
  return true;
}

void Mesh::append(const Mesh& other) {
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  colors.insert(colors.end(), other.colors.begin(), other.colors.end());
}

uint32_t Scene::addNode(std::string name) {
  Node node;
  node.name = std::move(name);
  nodes.push_back(std::move(node));
  return uint32_t(nodes.size() - 1);
}

void Scene::finalize() {
  require(!nodes.empty() && root < nodes.size(), source, "scene has no root node");
  const size_t n = nodes.size();
  expandedCount.assign(n, 0);
  nodeBounds.assign(n, Bounds{});
  instanceOffsets.assign(n, {});
  std::vector<int> height(n, 0);  // instances on the longest path down from each node
  enum : uint8_t { kNew, kActive, kDone };
  std::vector<uint8_t> state(n, kNew);
  // Iterative post-order DFS (a recursive one overflows the stack on long chains): `path` holds
  // the nodes from the root down, each with its next instance to follow.
  struct OnPath {
    uint32_t node;
    size_t next;
  };
  std::vector<OnPath> path{{root, 0}};
  state[root] = kActive;
  while (!path.empty()) {
    const uint32_t i = path.back().node;
    const Node& node = nodes[i];
    if (path.back().next < node.instances.size()) {
      const uint32_t child = node.instances[path.back().next++].node;
      require(child < n, source, "node '" + node.name + "' references a missing node");
      require(state[child] != kActive, source,
              "instancing cycle through node '" + nodes[child].name + "'");
      if (state[child] == kDone) continue;
      require(path.size() <= size_t(kMaxInstanceDepth), source,
              "instances nest deeper than " + std::to_string(kMaxInstanceDepth) +
                  " levels: node '" + nodes[child].name + "' is at level " +
                  std::to_string(path.size()) + " below the root");
      state[child] = kActive;
      path.push_back({child, 0});
      continue;
    }
    finishNode(i, height);
    state[i] = kDone;
    path.pop_back();
  }
  instanceDepth = height[root];
}

// Derived data of node i from its own triangles and its finished children.
void Scene::finishNode(uint32_t i, std::vector<int>& height) {
  const Node& node = nodes[i];
  const auto checkCount = [&](uint64_t count) {
    if (count > kMaxExpandedTriangles)
      throw InputError(source + ": too large: node '" + node.name +
                       "' expands to more than 2^62 triangles");
  };
  uint64_t count = node.mesh.size();
  checkCount(count);
  Bounds b;
  for (const glm::vec3& p : node.mesh.positions) b.extend(glm::dvec3(p));
  int h = 0;
  for (const Instance& inst : node.instances) {
    instanceOffsets[i].push_back(count);
    // Both terms are at most 2^62: the sum cannot wrap.
    count += expandedCount[inst.node];
    checkCount(count);
    b.extend(nodeBounds[inst.node].transformed(inst.transform));
    h = std::max(h, height[inst.node] + 1);
  }
  require(h <= kMaxInstanceDepth, source,
          "instances nest deeper than " + std::to_string(kMaxInstanceDepth) + " levels below node '" +
              node.name + "' (" + std::to_string(h) + ")");
  expandedCount[i] = count;
  nodeBounds[i] = b;
  height[i] = h;
}

uint64_t Scene::uniqueTriangles() const {
  uint64_t total = 0;
  for (const Node& node : nodes) total += node.mesh.size();
  return total;
}

uint64_t Scene::heldBytes() const {
  uint64_t total = 0;
  for (const Node& node : nodes)
    total += node.mesh.positions.capacity() * sizeof(glm::vec3) +
             node.mesh.colors.capacity() * sizeof(Rgba8) +
             node.instances.capacity() * sizeof(Instance);
  for (const std::vector<uint64_t>& offsets : instanceOffsets)
    total += offsets.capacity() * sizeof(uint64_t);
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
    if (offsets.empty()) return std::nullopt;  // an outline's count without triangles
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
