#pragma once
// The scene model: what a scene requires and nothing more.
//
// A Node owns triangles (indexed vertices and a colour; the normal is derived from the positions)
// and references other nodes through Instances (node index + affine transform, never a copy).
// The graph is a DAG rooted at Scene::root. Mesh positions are float in the node's own frame;
// transforms are double, so a mesh far from the origin is stored recentred and placed by a
// double-precision translation.
//
// Triangle IDs ("expanded IDs") number every triangle of the fully instanced scene: a node's
// expanded list is its own triangles [0, n) followed by the expanded lists of its instances in
// order. So the ID of triangle t of a node reached through instances i1..ik is
//   childOffset(root, i1) + childOffset(node1, i2) + ... + t.
// kNoId marks a pixel that shows no triangle.
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "src/core/bounds.hpp"
#include "src/core/color.hpp"
#include "src/core/procedural.hpp"

namespace lzb {

constexpr uint64_t kNoId = ~uint64_t(0);

// Instances on any path from the root: at most this many. Every later walk over the graph (the
// cull, the draw walk, the sample trees, the Embree levels, the rays' descent) recurses once per
// level, so this bound is what keeps their stacks small; finalize() checks it once, iteratively.
constexpr int kMaxInstanceDepth = 64;
// Expanded triangles of any node: at most 2^62, so an ID offset plus a count never wraps and
// kNoId stays free. finalize() refuses more.
constexpr uint64_t kMaxExpandedTriangles = uint64_t(1) << 62;

// The unit geometric normal of a triangle, normalize(cross(b - a, c - a)) worked out in double (so
// triangles at 1e-20 scale keep one) and rounded to float: the one definition every method shades
// and culls with, derived on use rather than stored (inline: shading derives one a pixel).
inline glm::vec3 triangleNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::dvec3 n = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
  const double len = glm::length(n);
  return len > 0.0 && len <= std::numeric_limits<double>::max() ? glm::vec3(n / len)
                                                                : glm::vec3(0.0f);
}
// Whether the model keeps the triangle: finite corners and a non-zero normal.
bool keepsTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

// Indexed triangles: vertices stored once and shared (a heightfield holds half a vertex a
// triangle), three indices a triangle, and a colour a triangle or one for the whole mesh when
// they are all alike (uniformColors). Every vertex is used by some triangle, so the vertices'
// box is the triangles' box.
struct Mesh {
  std::vector<glm::vec3> positions;  // vertices, node frame
  std::vector<uint32_t> indices;     // 3 per triangle, into positions
  std::vector<Rgba8> colors;         // 1 per triangle, or 1 for every triangle (read by color())

  size_t size() const { return indices.size() / 3; }
  bool empty() const { return indices.empty(); }
  const Rgba8& color(size_t tri) const { return colors[colors.size() == 1 ? 0 : tri]; }
  // Keeps one colour when every triangle has the same (4 bytes a triangle less); adding
  // triangles later spreads it back.
  void uniformColors();
  const glm::vec3& vertex(size_t tri, int corner) const {
    return positions[indices[3 * tri + size_t(corner)]];
  }
  glm::vec3 normal(size_t tri) const {
    return triangleNormal(vertex(tri, 0), vertex(tri, 1), vertex(tri, 2));
  }
  // Appends a triangle with three new vertices; returns false (and adds nothing) when the model
  // does not keep it (keepsTriangle).
  bool add(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, Rgba8 color);
  // Appends a vertex and returns its index (throws std::length_error past 2^32 vertices).
  uint32_t addVertex(const glm::vec3& p);
  // Appends the triangle of vertices i, j, k; false (nothing added) when it is not kept.
  bool addTriangle(uint32_t i, uint32_t j, uint32_t k, Rgba8 color);
  void append(const Mesh& other);

 private:
  void spreadColors();  // one colour a triangle again, before a triangle is added
};

struct Instance {
  uint32_t node = 0;
  glm::dmat4 transform{1.0};  // child frame -> parent frame
};

// A node's triangles not read yet (a TOML scene's streamed file under --distribute data,
// loadTomlOutline in src/scene/toml_scene.hpp): their count and stored-frame bounds stand for
// `mesh` until they are read.
struct DeferredMesh {
  uint64_t triangles = 0;
  Bounds bounds;
};
// Reads the triangles of a node whose mesh is deferred: hands them to `out` in ID order, in
// meshes of some triangles each, as the loaded scene's node holds them.
using DeferredReader =
    std::function<void(uint32_t node, const std::function<void(const Mesh&)>& out)>;

struct Node {
  std::string name;
  Mesh mesh;
  std::vector<Instance> instances;
  // A procedural object (src/core/procedural.hpp): `mesh` is then its tessellation, in the
  // layout that maps a parameter point (u, v) to its triangle.
  std::optional<ProceduralSurface> procedural;
  std::optional<DeferredMesh> deferred;  // set: `mesh` is empty and stands for these
  // Its own triangles, read or deferred.
  uint64_t ownTriangles() const { return deferred ? deferred->triangles : mesh.size(); }
  // The box of its own triangles' vertices (node frame), read or deferred.
  Bounds ownBounds() const;
};

// Triangles dropped at load time and why (reported, never silently lost).
struct LoadStats {
  uint64_t loaded = 0;      // triangles kept
  uint64_t degenerate = 0;  // zero area (or collapsed after float rounding)
  uint64_t nonFinite = 0;   // NaN or Inf vertices
  void merge(const LoadStats& o) {
    loaded += o.loaded;
    degenerate += o.degenerate;
    nonFinite += o.nonFinite;
  }
};

struct Light {
  glm::dvec3 direction{0.3, 0.8, 0.5};  // towards the light, world space (normalised on use)
  double ambient = 0.25;
};

struct CameraSpec {
  glm::dvec3 position{0.0, 0.0, 1.0};
  glm::dvec3 lookAt{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fovyDegrees = 45.0;
  double nearPlane = 0.0;  // 0: choose from the scene bounds
  double farPlane = 0.0;   // 0: choose from the scene bounds
};

struct Scene {
  std::string source;  // what it was loaded from, for messages and the report
  std::vector<Node> nodes;
  uint32_t root = 0;
  Light light;
  std::optional<CameraSpec> camera;   // from a scene file or generator; else framed on bounds
  std::vector<CameraSpec> keyframes;  // camera path from a scene file
  std::optional<int> width, height;   // image size from a scene file
  LoadStats stats;

  // Derived data; call finalize() after building or editing the graph.
  std::vector<uint64_t> expandedCount;  // per node: triangles with all instances expanded
  std::vector<Bounds> nodeBounds;       // per node, in its own frame
  std::vector<std::vector<uint64_t>> instanceOffsets;  // per node: childOffset of each instance
  // Fills the derived data. Throws InputError naming `source` and the node on a cycle, a dangling
  // node index, nesting deeper than kMaxInstanceDepth or more than kMaxExpandedTriangles.
  void finalize();
  int instanceDepth = 0;  // instances on the longest path from the root (set by finalize)

  const Node& rootNode() const { return nodes[root]; }
  uint64_t uniqueTriangles() const;  // stored once each
  // What the model holds: the meshes' arrays (vertices, 3 indices and a colour a triangle) and
  // the instances with their ID offsets, as allocated.
  uint64_t heldBytes() const;
  uint64_t expandedTriangles() const { return expandedCount[root]; }
  const Bounds& bounds() const { return nodeBounds[root]; }
  // Offset of instance i's expanded list inside node n's expanded list.
  uint64_t childOffset(uint32_t node, size_t instance) const {
    return instanceOffsets[node][instance];
  }
  uint32_t addNode(std::string name);

  // Which stored triangle an expanded ID names, and where (node frame -> world).
  struct TriangleRef {
    uint32_t node;
    uint32_t triangle;
    glm::dmat4 transform;
  };
  std::optional<TriangleRef> resolve(uint64_t id) const;

 private:
  void finishNode(uint32_t i, std::vector<int>& height);
};

// One mesh drawn with a world transform: the scene graph flattened to its leaves.
struct DrawItem {
  uint32_t node;
  glm::dmat4 transform;  // node frame -> world
  uint64_t idBase;       // expanded ID of the node's triangle 0 at this place
};

// Every (node with triangles, world transform) pair in expanded-ID order. Memory grows with the
// number of instances, so callers that face 10^12-triangle scenes traverse the graph instead.
std::vector<DrawItem> flattenScene(const Scene& scene);

}  // namespace lzb
