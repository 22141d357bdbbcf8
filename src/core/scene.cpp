#include "src/core/scene.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "src/core/error.hpp"

namespace lzb {

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

bool keepsTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  return finite(a) && finite(b) && finite(c) && triangleNormal(a, b, c) != glm::vec3(0.0f);
}

uint32_t Mesh::addVertex(const glm::vec3& p) {
  if (positions.size() >= size_t(UINT32_MAX))
    throw std::length_error("a mesh holds at most 2^32 - 1 vertices");
  positions.push_back(p);
  return uint32_t(positions.size() - 1);
}

bool Mesh::add(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, Rgba8 color) {
  if (!keepsTriangle(a, b, c)) return false;
  const uint32_t i = addVertex(a), j = addVertex(b), k = addVertex(c);
  spreadColors();
  indices.insert(indices.end(), {i, j, k});
  colors.push_back(color);
  return true;
}

bool Mesh::addTriangle(uint32_t i, uint32_t j, uint32_t k, Rgba8 color) {
  if (!keepsTriangle(positions[i], positions[j], positions[k])) return false;
  spreadColors();
  indices.insert(indices.end(), {i, j, k});
  colors.push_back(color);
  return true;
}

void Mesh::append(const Mesh& other) {
  if (positions.size() + other.positions.size() > size_t(UINT32_MAX))
    throw std::length_error("a mesh holds at most 2^32 - 1 vertices");
  spreadColors();
  const uint32_t base = uint32_t(positions.size());
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  for (const uint32_t i : other.indices) indices.push_back(base + i);
  for (size_t t = 0; t < other.size(); ++t) colors.push_back(other.color(t));
}

void Mesh::uniformColors() {
  if (colors.size() > 1 &&
      std::all_of(colors.begin(), colors.end(), [&](Rgba8 c) { return c == colors[0]; }))
    colors = {colors[0]};
}

void Mesh::spreadColors() {
  if (colors.size() == 1 && size() > 1) colors.assign(size(), colors[0]);
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
  uint64_t count = node.ownTriangles();
  checkCount(count);
  Bounds b = node.ownBounds();
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

Bounds Node::ownBounds() const {
  Bounds b = deferred ? deferred->bounds : Bounds{};
  for (const glm::vec3& p : mesh.positions) b.extend(glm::dvec3(p));
  return b;
}

uint64_t Scene::uniqueTriangles() const {
  uint64_t total = 0;
  for (const Node& node : nodes) total += node.ownTriangles();
  return total;
}

uint64_t Scene::heldBytes() const {
  uint64_t total = 0;
  for (const Node& node : nodes)
    total += node.mesh.positions.capacity() * sizeof(glm::vec3) +
             node.mesh.indices.capacity() * sizeof(uint32_t) +
             node.mesh.colors.capacity() * sizeof(Rgba8) +
             node.instances.capacity() * sizeof(Instance);
  for (const std::vector<uint64_t>& offsets : instanceOffsets)
    total += offsets.capacity() * sizeof(uint64_t);
  return total;
}

namespace {

// Whether m only translates (its linear part the identity, its last row (0, 0, 0, 1)).
bool translationOnly(const glm::dmat4& m) {
  return m[0] == glm::dvec4(1, 0, 0, 0) && m[1] == glm::dvec4(0, 1, 0, 0) &&
         m[2] == glm::dvec4(0, 0, 1, 0) && m[3].w == 1.0;
}

// a * b, where both only translate: their translations added, as the product would sum them
// (the zero products it would add change no bit but the sign of a zero).
void composeTranslations(glm::dmat4& a, const glm::dmat4& b) {
  a[3] = glm::dvec4(glm::dvec3(b[3]) + glm::dvec3(a[3]), 1.0);
}

}  // namespace

std::optional<Scene::TriangleRef> Scene::resolve(uint64_t id) const {
  if (id >= expandedTriangles()) return std::nullopt;
  TriangleRef ref{root, 0, glm::dmat4(1.0)};
  // Instanced grids (a chessboard of 10^12 squares) nest translations many levels deep: summed
  // while both sides only translate, instead of a 4 x 4 product a level.
  bool translating = true;
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
    const glm::dmat4& m = node.instances[k].transform;
    if (translating && translationOnly(m)) {
      composeTranslations(ref.transform, m);
    } else {
      ref.transform = ref.transform * m;
      translating = false;
    }
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
