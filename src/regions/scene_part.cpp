#include "src/regions/scene_part.hpp"

#include <absl/container/flat_hash_map.h>

#include <algorithm>
#include <map>
#include <queue>
#include <stdexcept>

namespace lzb::regions {

void IdMap::add(uint64_t global, uint64_t count) {
  if (count == 0) return;
  if (!runs_.empty() && runs_.back().global + runs_.back().count == global)
    runs_.back().count += count;
  else
    runs_.push_back({size_, global, count});
  size_ += count;
}

uint64_t IdMap::global(uint64_t local) const {
  if (local >= size_) return kNoId;
  const auto after = std::upper_bound(runs_.begin(), runs_.end(), local,
                                      [](uint64_t id, const Run& r) { return id < r.local; });
  const Run& run = *(after - 1);
  return run.global + (local - run.local);
}

uint64_t IdMap::local(uint64_t global) const {
  const auto after = std::upper_bound(runs_.begin(), runs_.end(), global,
                                      [](uint64_t id, const Run& r) { return id < r.global; });
  if (after == runs_.begin()) return kNoId;
  const Run& run = *(after - 1);
  return global - run.global < run.count ? run.local + (global - run.global) : kNoId;
}

namespace {

uint32_t indexAtPath(const Scene& scene, const std::vector<uint32_t>& path) {
  uint32_t n = scene.root;
  for (uint32_t i : path) n = scene.nodes[n].instances[i].node;
  return n;
}
const Node& nodeAtPath(const Scene& scene, const std::vector<uint32_t>& path) {
  return scene.nodes[indexAtPath(scene, path)];
}

// Instances opened at most: each adds a few units.
constexpr size_t kMaxOpened = size_t(1) << 20;

glm::dvec3 meshCentre(const Node& node, const glm::dmat4& toWorld) {
  const Bounds b = node.ownBounds();
  return b.empty() ? glm::dvec3(toWorld[3]) : b.transformed(toWorld).center();
}

// A unit with the world transform of the node it names (to open it).
struct OpenableUnit {
  SceneUnit unit;
  uint32_t node;
  glm::dmat4 toWorld;
};

// The units node `node` (reached by `path`, placed by `toWorld`, its IDs from `idBase`) opens
// into: its own mesh, then each instance whole.
void openNode(const Scene& scene, uint32_t node, const std::vector<uint32_t>& path,
              const glm::dmat4& toWorld, uint64_t idBase, std::vector<OpenableUnit>& out) {
  const Node& n = scene.nodes[node];
  if (n.ownTriangles() > 0)
    out.push_back({{path, false, idBase, n.ownTriangles(), meshCentre(n, toWorld)}, node, toWorld});
  for (size_t i = 0; i < n.instances.size(); ++i) {
    const Instance& inst = n.instances[i];
    if (scene.expandedCount[inst.node] == 0) continue;
    std::vector<uint32_t> p = path;
    p.push_back(uint32_t(i));
    const glm::dmat4 w = toWorld * inst.transform;
    out.push_back(
        {{std::move(p), true, idBase + scene.childOffset(node, i), scene.expandedCount[inst.node],
          scene.nodeBounds[inst.node].transformed(w).center()},
         inst.node,
         w});
  }
}

// Larger first; among equals the earlier in ID order.
struct Larger {
  bool operator()(const OpenableUnit& a, const OpenableUnit& b) const {
    if (a.unit.triangles != b.unit.triangles) return a.unit.triangles < b.unit.triangles;
    return a.unit.idBase > b.unit.idBase;
  }
};

// Calls f(mesh, first) with node n's triangles: its whole mesh (first 0), or its deferred
// triangles read chunk by chunk, each with the index of its first triangle.
template <class F>
void forChunks(const Scene& whole, uint32_t n, const DeferredReader& read, F&& f) {
  if (!whole.nodes[n].deferred) return f(whole.nodes[n].mesh, uint64_t(0));
  if (!read)
    throw std::logic_error("cutScene: the triangles of node '" + whole.nodes[n].name +
                           "' are not read");
  uint64_t first = 0;
  read(n, [&](const Mesh& chunk) {
    f(chunk, first);
    first += chunk.size();
  });
}

// Node n's triangles as the loaded scene holds them: its mesh, or its deferred triangles read.
Mesh heldMesh(const Scene& whole, uint32_t n, const DeferredReader& read) {
  if (!whole.nodes[n].deferred) return whole.nodes[n].mesh;
  Mesh mesh;
  forChunks(whole, n, read, [&](const Mesh& chunk, uint64_t) { mesh.append(chunk); });
  mesh.uniformColors();
  return mesh;
}

// A node of the part standing for the whole scene's node `original` at an opened path.
struct PartBuilder {
  const Scene& whole;
  const DeferredReader& read;
  ScenePart& part;
  std::map<std::vector<uint32_t>, uint32_t> opened;           // path -> part node
  std::vector<std::pair<uint32_t, uint32_t>> openedOriginal;  // (part node, whole node)
  std::vector<bool> copied;

  // The part node at `path` (the root for the empty path), made with its parents when new.
  uint32_t nodeAt(const std::vector<uint32_t>& path) {
    if (path.empty()) return whole.root;
    const auto found = opened.find(path);
    if (found != opened.end()) return found->second;
    const std::vector<uint32_t> parentPath(path.begin(), path.end() - 1);
    const uint32_t parent = nodeAt(parentPath);
    const Instance& inst = wholeNodeAt(parentPath).instances[path.back()];
    const uint32_t made = part.scene.addNode(whole.nodes[inst.node].name);
    part.scene.nodes[parent].instances.push_back({made, inst.transform});
    opened.emplace(path, made);
    openedOriginal.emplace_back(made, inst.node);
    return made;
  }
  const Node& wholeNodeAt(const std::vector<uint32_t>& path) const {
    return nodeAtPath(whole, path);
  }
  void copySubtree(uint32_t i) {
    std::vector<uint32_t> stack{i};
    while (!stack.empty()) {
      const uint32_t n = stack.back();
      stack.pop_back();
      if (copied[n]) continue;
      copied[n] = true;
      part.scene.nodes[n] = whole.nodes[n];
      if (whole.nodes[n].deferred) {
        part.scene.nodes[n].mesh = heldMesh(whole, n, read);
        part.scene.nodes[n].deferred.reset();
      }
      for (const Instance& inst : whole.nodes[n].instances) stack.push_back(inst.node);
    }
  }
  void add(const SceneUnit& u) {
    if (u.subtree) {
      const std::vector<uint32_t> parentPath(u.path.begin(), u.path.end() - 1);
      const uint32_t parent = nodeAt(parentPath);
      const Instance& inst = wholeNodeAt(parentPath).instances[u.path.back()];
      part.scene.nodes[parent].instances.push_back(inst);
      copySubtree(inst.node);
    } else {
      Node& to = part.scene.nodes[nodeAt(u.path)];
      to.mesh = heldMesh(whole, indexAtPath(whole, u.path), read);
      to.procedural = wholeNodeAt(u.path).procedural;
    }
    part.ids.add(u.idBase, u.triangles);
    ++part.units;
  }
};

}  // namespace

void reserveKept(const PartOf& partOf, uint64_t count, uint32_t meshNode,
                 std::vector<ScenePart>& parts) {
  std::vector<uint64_t> kept(parts.size(), 0);
  for (uint64_t t = 0; t < count && t < partOf.size(); ++t)
    if (partOf[t] != kNoPart) ++kept[partOf[t]];
  for (size_t p = 0; p < parts.size(); ++p) {
    Mesh& to = parts[p].scene.nodes[meshNode].mesh;
    to.indices.reserve(to.indices.size() + 3 * kept[p]);
    to.colors.reserve(to.colors.size() + kept[p]);
  }
}

namespace {

// Appends each triangle t of `from` (unit firstUnit + t, ID firstId + t) to the mesh of node
// nodeOf(p) of parts[p], p = partOf[firstUnit + t], unless kNoPart.
template <class NodeOf>
void keepTriangles(const Mesh& from, uint64_t firstUnit, uint64_t firstId, const PartOf& partOf,
                   NodeOf&& nodeOf, std::vector<ScenePart>& parts) {
  // (part, vertex of `from`) -> the part's vertex: a vertex shared by triangles of one part
  // stays shared there.
  absl::flat_hash_map<uint64_t, uint32_t> vertexIn;
  for (size_t t = 0; t < from.size(); ++t) {
    const uint64_t unit = firstUnit + t;
    if (unit >= partOf.size() || partOf[unit] == kNoPart) continue;
    const uint32_t p = partOf[unit];
    ScenePart& part = parts[p];
    Mesh& to = part.scene.nodes[nodeOf(p)].mesh;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = from.indices[3 * t + size_t(k)];
      const auto [it, added] = vertexIn.try_emplace((uint64_t(p) << 32) | v, 0u);
      if (added) it->second = to.addVertex(from.positions[v]);
      to.indices.push_back(it->second);
    }
    to.colors.push_back(from.color(t));
    part.ids.add(firstId + t, 1);
    ++part.units;
  }
}

}  // namespace

void keepMainMeshTriangles(const Mesh& from, uint64_t firstId, const PartOf& partOf,
                           uint32_t meshNode, std::vector<ScenePart>& parts) {
  keepTriangles(
      from, firstId, firstId, partOf, [meshNode](uint32_t) { return meshNode; }, parts);
}

uint32_t startMeshPart(const SceneOutline& outline, const glm::dmat4& placement, Scene& s) {
  s.source = outline.source;
  s.camera = outline.camera;
  s.stats = outline.stats;
  s.root = s.addNode(outline.source);
  if (placement == glm::dmat4(1.0)) return s.root;
  const uint32_t mesh = s.addNode(outline.source + "/recentred");
  s.nodes[s.root].instances.push_back({mesh, placement});
  return mesh;
}

void finishMeshPart(const SceneOutline& outline, uint32_t meshNode, const Bounds& nodeBox,
                    Scene& s) {
  s.finalize();
  if (s.expandedTriangles() == 0) return;
  s.nodeBounds[meshNode] = nodeBox;
  s.nodeBounds[s.root] = outline.bounds;
}

glm::dvec3 placedCentroid(const Mesh& mesh, size_t t, const glm::dmat4& toWorld) {
  const glm::dvec3 c = (glm::dvec3(mesh.vertex(t, 0)) + glm::dvec3(mesh.vertex(t, 1)) +
                        glm::dvec3(mesh.vertex(t, 2))) /
                       3.0;
  return glm::dvec3(toWorld * glm::dvec4(c, 1.0));
}

namespace {

// Whether each node is reached by exactly one chain of instances from the root (paths counted
// in topological order, saturating at 2).
std::vector<bool> placedOnce(const Scene& scene) {
  std::vector<uint32_t> order;  // post-order from the root: children before parents
  std::vector<uint8_t> state(scene.nodes.size(), 0);
  std::vector<std::pair<uint32_t, size_t>> stack{{scene.root, 0}};
  state[scene.root] = 1;
  while (!stack.empty()) {
    auto& [n, next] = stack.back();
    if (next < scene.nodes[n].instances.size()) {
      const uint32_t child = scene.nodes[n].instances[next++].node;
      if (!state[child]) state[child] = 1, stack.push_back({child, 0});
      continue;
    }
    order.push_back(n);
    stack.pop_back();
  }
  std::vector<uint8_t> paths(scene.nodes.size(), 0);
  paths[scene.root] = 1;
  for (auto it = order.rbegin(); it != order.rend(); ++it)
    for (const Instance& inst : scene.nodes[*it].instances)
      paths[inst.node] = uint8_t(std::min(2, paths[inst.node] + paths[*it]));
  std::vector<bool> once(scene.nodes.size());
  for (size_t n = 0; n < once.size(); ++n) once[n] = paths[n] == 1;
  return once;
}

// The node of a scene's main mesh: down from the root while a node holds one instance alone.
uint32_t mainMeshNode(const Scene& scene, SceneUnits& units) {
  uint32_t n = scene.root;
  while (scene.nodes[n].ownTriangles() == 0 && !scene.nodes[n].procedural &&
         scene.nodes[n].instances.size() == 1) {
    const Instance& inst = scene.nodes[n].instances[0];
    units.meshPath.push_back(0);
    units.meshToWorld = units.meshToWorld * inst.transform;
    n = inst.node;
  }
  return n;
}

}  // namespace

const SceneUnit& SceneUnits::entryOf(size_t u) const {
  const auto after =
      std::upper_bound(opened.begin(), opened.end(), uint64_t(u),
                       [](uint64_t unit, const SceneUnit& e) { return unit < e.firstUnit; });
  return *(after - 1);
}

void SceneUnits::centres(const Scene& scene, std::vector<glm::dvec3>& out,
                         const DeferredReader& read) const {
  out.resize(size());
  // The triangles of one node, units first, first + 1, ...: read in one pass when deferred.
  const auto meshCentres = [&](const std::vector<uint32_t>& path, const glm::dmat4& toWorld,
                               uint64_t first) {
    forChunks(scene, indexAtPath(scene, path), read, [&](const Mesh& m, uint64_t at) {
      for (size_t t = 0; t < m.size(); ++t) out[first + at + t] = placedCentroid(m, t, toWorld);
    });
  };
  if (meshTriangles > 0) meshCentres(meshPath, meshToWorld, 0);
  for (const SceneUnit& e : opened) {
    if (e.split)
      meshCentres(e.path, e.toWorld, e.firstUnit);
    else
      out[e.firstUnit] = e.centre;
  }
}

uint64_t SceneUnits::triangles(size_t u) const {
  if (u < meshTriangles) return 1;
  const SceneUnit& e = entryOf(u);
  return e.split ? 1 : e.triangles;
}

SceneUnits sceneUnits(const Scene& scene, uint32_t regions, bool wholeProcedural) {
  SceneUnits units;
  const uint32_t main = mainMeshNode(scene, units);
  const Node& mesh = scene.nodes[main];
  std::vector<OpenableUnit> open;
  openNode(scene, main, units.meshPath, units.meshToWorld, 0, open);
  // A procedural object's mesh is cut like any other unless the method samples its definition.
  const auto cuttable = [wholeProcedural](const Node& n) {
    return n.ownTriangles() > 0 && !(wholeProcedural && n.procedural);
  };
  if (cuttable(mesh)) {
    units.meshTriangles = mesh.ownTriangles();
    open.erase(open.begin());  // the main mesh: its triangles, one unit each
  }
  const uint64_t limit = std::max<uint64_t>(1, scene.expandedTriangles() / (8 * uint64_t(regions)));
  std::priority_queue<OpenableUnit, std::vector<OpenableUnit>, Larger> queue(Larger{},
                                                                             std::move(open));
  size_t opened = 0;
  const std::vector<bool> once = placedOnce(scene);
  while (!queue.empty()) {
    OpenableUnit c = queue.top();
    queue.pop();
    const Node& node = scene.nodes[c.node];
    // A mesh placed once is cut into its triangles: as many units as the scene has triangles.
    const bool splittable = once[c.node] && cuttable(node);
    const bool openable =
        c.unit.subtree && (!node.instances.empty() || splittable) && opened < kMaxOpened;
    c.unit.split = !c.unit.subtree && c.unit.triangles > limit && splittable;
    if (c.unit.split) c.unit.toWorld = c.toWorld;
    if (c.unit.triangles <= limit || !openable) {
      units.opened.push_back(std::move(c.unit));
      continue;
    }
    ++opened;
    std::vector<OpenableUnit> children;
    openNode(scene, c.node, c.unit.path, c.toWorld, c.unit.idBase, children);
    for (OpenableUnit& child : children) queue.push(std::move(child));
  }
  std::sort(units.opened.begin(), units.opened.end(),
            [](const SceneUnit& a, const SceneUnit& b) { return a.idBase < b.idBase; });
  uint64_t unit = units.meshTriangles;
  for (SceneUnit& e : units.opened) {
    e.firstUnit = unit;
    unit += e.split ? e.triangles : 1;
  }
  units.openedUnits = unit - units.meshTriangles;
  return units;
}

namespace {

// A part's frame: the whole scene's settings and nodes (names only), nothing kept yet.
void startPart(const Scene& whole, Scene& s) {
  s.source = whole.source;
  s.light = whole.light;
  s.camera = whole.camera;
  s.keyframes = whole.keyframes;
  s.width = whole.width;
  s.height = whole.height;
  s.stats = whole.stats;
  s.root = whole.root;
  s.nodes.resize(whole.nodes.size());
  for (size_t n = 0; n < whole.nodes.size(); ++n) s.nodes[n].name = whole.nodes[n].name;
}

// Opened nodes and the root keep the whole scene's boxes (supersets of theirs): what is placed
// relative to a node's box (Embree's recentred positions) then comes out bit for bit alike.
void finishPart(const Scene& whole, const PartBuilder& build, Scene& s) {
  s.finalize();
  if (s.expandedTriangles() == 0) return;
  s.nodeBounds[s.root] = whole.nodeBounds[whole.root];
  for (const auto& [made, original] : build.openedOriginal)
    s.nodeBounds[made] = whole.nodeBounds[original];
}

}  // namespace

std::vector<ScenePart> cutScene(const Scene& whole, const SceneUnits& units, const PartOf& partOf,
                                uint32_t parts, const DeferredReader& read) {
  if (partOf.size() != units.size())
    throw std::invalid_argument("cutScene: partOf has " + std::to_string(partOf.size()) +
                                " entries for " + std::to_string(units.size()) + " units");
  std::vector<ScenePart> cut(parts);
  std::vector<PartBuilder> builds;
  builds.reserve(parts);
  uint32_t meshNode = whole.root;
  for (ScenePart& part : cut) {
    startPart(whole, part.scene);
    builds.push_back({whole, read, part, {}, {}, std::vector<bool>(whole.nodes.size(), false)});
    builds.back().copied[whole.root] =
        true;  // the root is cut, never copied (no instance reaches it)
    // First in every part: the main mesh's node has one index in all of them.
    if (units.meshTriangles > 0) meshNode = builds.back().nodeAt(units.meshPath);
  }
  // Whether a part keeps some of units [first, first + count): a deferred mesh none keeps is not
  // read.
  const auto someKept = [&](uint64_t first, uint64_t count) {
    return std::any_of(partOf.begin() + std::ptrdiff_t(first),
                       partOf.begin() + std::ptrdiff_t(first + count),
                       [](uint32_t p) { return p != kNoPart; });
  };
  if (units.meshTriangles > 0 && someKept(0, units.meshTriangles)) {
    reserveKept(partOf, units.meshTriangles, meshNode, cut);
    forChunks(whole, indexAtPath(whole, units.meshPath), read, [&](const Mesh& m, uint64_t first) {
      keepMainMeshTriangles(m, first, partOf, meshNode, cut);
    });
  }
  for (const SceneUnit& e : units.opened) {
    if (e.split) {
      if (!someKept(e.firstUnit, e.triangles)) continue;
      // The node made in a part only when it keeps some of the triangles (in ID order).
      std::vector<uint32_t> node(parts, kNoPart);
      const auto nodeOf = [&](uint32_t p) {
        if (node[p] == kNoPart) node[p] = builds[p].nodeAt(e.path);
        return node[p];
      };
      forChunks(whole, indexAtPath(whole, e.path), read, [&](const Mesh& m, uint64_t first) {
        keepTriangles(m, e.firstUnit + first, e.idBase + first, partOf, nodeOf, cut);
      });
      continue;
    }
    const uint32_t p = partOf[e.firstUnit];
    if (p != kNoPart) builds[p].add(e);
  }
  for (uint32_t p = 0; p < parts; ++p) finishPart(whole, builds[p], cut[p].scene);
  return cut;
}

}  // namespace lzb::regions
