#pragma once
// A rank's part of a scene under --distribute data: the pieces of the whole scene it holds and
// the map from the part's triangle IDs back to the whole scene's, so that an ID names the same
// triangle on any number of ranks.
//
// The pieces ("units") are the main mesh's triangles (the root's own, or a recentred mesh
// file's), each alone, and whole instances with their subtrees; an instance too large for the
// region count is opened into its node's own mesh and its node's instances, the largest first. An
// opened mesh too large for the region count whose node the scene places once (a mesh file of a
// TOML scene, one of several files) is cut into its triangles, a unit each; else it stays one
// unit. A procedural object's mesh is cut too, except for a method that samples the object's
// definition (sqrt5: its layout maps a parameter point to a triangle of the whole object), for
// which it stays one unit. A part keeps the whole scene's instance
// chains, transforms and node boxes, and its units in the whole scene's order, so exact methods
// compute every hit bit for bit as on the whole scene, and IDs rise with the whole scene's.
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "src/core/scene.hpp"
#include "src/core/scene_outline.hpp"

namespace lzb::regions {

// Expanded IDs of a part, mapped to the whole scene's in runs of consecutive IDs.
class IdMap {
 public:
  // Appends `count` IDs that are the whole scene's [global, global + count).
  void add(uint64_t global, uint64_t count);
  // The whole scene's ID of the part's ID `local` (kNoId stays kNoId).
  uint64_t global(uint64_t local) const;
  // The part's ID of the whole scene's ID `global`, kNoId where the part does not hold it (the
  // runs rise in both: a part keeps its units in the whole scene's order).
  uint64_t local(uint64_t global) const;
  uint64_t size() const { return size_; }

 private:
  struct Run {
    uint64_t local, global, count;
  };
  std::vector<Run> runs_;
  uint64_t size_ = 0;
};

// One unit beyond the root's own triangles: the instance chain from the root (instance indices,
// node by node) to the node it names, and whether it is that instance's whole subtree or the
// node's own mesh.
struct SceneUnit {
  std::vector<uint32_t> path;
  bool subtree = true;
  uint64_t idBase = 0;      // the whole scene's ID of its first triangle
  uint64_t triangles = 0;   // expanded
  glm::dvec3 centre{0.0};   // world position: its box's centre (not split)
  bool split = false;       // the node's own mesh cut into its triangles: `triangles` units
  uint64_t firstUnit = 0;   // the index of its (first) unit among all units
  glm::dmat4 toWorld{1.0};  // split: the node's frame -> world (its triangles' centroids)
};

// The units of `scene` for `regions` regions, in expanded-ID order: the triangles of its main mesh
// (one unit each, kept implicit: a scene of 10^8 triangles needs no 10^8 unit records), then the
// rest (a split mesh's triangles implicit too). The main mesh is the root's own, or, when the root
// holds only one instance, that of the node such a chain of single instances leads to (a mesh file
// stored recentred, mesh_file.hpp). Instances holding more than 1/8 of a region's share are opened
// while any is (and can be), at most 2^20 of them.
struct SceneUnits {
  std::vector<uint32_t> meshPath;  // the chain of instances from the root to the main mesh's node
  glm::dmat4 meshToWorld{1.0};     // that node's frame -> world
  uint64_t meshTriangles = 0;      // units [0, meshTriangles): the main mesh's triangle u
  std::vector<SceneUnit> opened;   // the units after them, in ID order
  uint64_t openedUnits = 0;        // the units they make (a split mesh's triangles one each)
  size_t size() const { return meshTriangles + openedUnits; }
  // Every unit's world centre into `out`, a deferred node's triangles read through `read`.
  void centres(const Scene& scene, std::vector<glm::dvec3>& out,
               const DeferredReader& read = {}) const;
  // Unit u's expanded triangles.
  uint64_t triangles(size_t u) const;
  // The entry of `opened` holding unit u (>= meshTriangles).
  const SceneUnit& entryOf(size_t u) const;
};
// wholeProcedural: procedural objects' meshes stay one unit each (and the main mesh too, if
// procedural).
SceneUnits sceneUnits(const Scene& scene, uint32_t regions, bool wholeProcedural = false);

struct ScenePart {
  Scene scene;         // the units kept; nodes opened for some units are new nodes; finalized
  IdMap ids;           // the part's expanded IDs -> the whole scene's
  uint64_t units = 0;  // units kept
};

// Which part each unit goes to: an index below the number of parts, or kNoPart.
using PartOf = std::vector<uint32_t>;
constexpr uint32_t kNoPart = ~uint32_t(0);

// The `parts` parts of `whole` made of the units u with partOf[u] == p (units from
// sceneUnits(whole, ...)), units in the whole scene's order in each. A deferred node's triangles
// are read through `read` where a part keeps some (a cut mesh chunk by chunk, a whole one read
// whole); a part holds them as read.
std::vector<ScenePart> cutScene(const Scene& whole, const SceneUnits& units, const PartOf& partOf,
                                uint32_t parts, const DeferredReader& read = {});

// The main mesh's units, whole (cutScene) or chunk by chunk (a streamed scene): appends each
// triangle t of `from` with p = partOf[firstId + t] != kNoPart to node `meshNode`'s mesh of
// parts[p], with the whole scene's ID firstId + t.
void keepMainMeshTriangles(const Mesh& from, uint64_t firstId, const PartOf& partOf,
                           uint32_t meshNode, std::vector<ScenePart>& parts);
// Room in node `meshNode`'s mesh of each part for the triangles partOf sends it among the first
// `count`.
void reserveKept(const PartOf& partOf, uint64_t count, uint32_t meshNode,
                 std::vector<ScenePart>& parts);

// A part of a scene that is one mesh (a file or a generator read in chunks or slices): its frame,
// the root holding the triangles or placing by `placement` the recentred node that does, as the
// loader makes it; returns the node the triangles go to.
uint32_t startMeshPart(const SceneOutline& outline, const glm::dmat4& placement, Scene& s);
// Finalises such a part; one holding triangles keeps the whole scene's boxes (its node's own box
// `nodeBox` and the outline's), as cutScene keeps them: Embree places positions relative to them.
void finishMeshPart(const SceneOutline& outline, uint32_t meshNode, const Bounds& nodeBox,
                    Scene& s);

// The world centre of triangle t of `mesh` placed by `toWorld`: a main-mesh unit's centre, the
// same whether the mesh was loaded whole or is streamed (src/regions/streamed_share.hpp).
glm::dvec3 placedCentroid(const Mesh& mesh, size_t t, const glm::dmat4& toWorld);

}  // namespace lzb::regions
