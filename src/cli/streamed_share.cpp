#include "src/cli/streamed_share.hpp"

#include <vector>

#include "src/cli/memory_estimate.hpp"

namespace lzb {

namespace {

// Pass 1: the triangles' world centres and the node's own bounds; the outline from them.
std::vector<glm::dvec3> centresOf(const ChunkedScene& scene, Bounds& box, SceneOutline& outline) {
  requireEstimate(streamedCutBytes(scene.triangles), scene.base.source,
                  "cutting the scene into regions (--distribute data)");
  std::vector<glm::dvec3> centres;
  centres.reserve(scene.triangles);
  const LoadStats stats = scene.chunks([&](const Mesh& mesh) {
    for (const glm::vec3& p : mesh.positions) box.extend(glm::dvec3(p));
    for (size_t t = 0; t < mesh.size(); ++t)
      centres.push_back(placedCentroid(mesh, t, scene.placement));
  });
  outline = placedMeshOutline(scene.base, box, scene.placement, centres.size(), stats);
  return centres;
}

// The part's frame: the root, holding the triangles or placing the recentred node that does.
uint32_t partSkeleton(const ChunkedScene& scene, const SceneOutline& outline, Scene& s) {
  s.source = outline.source;
  s.camera = outline.camera;
  s.stats = outline.stats;
  s.root = s.addNode(outline.source);
  if (scene.placement == glm::dmat4(1.0)) return s.root;
  const uint32_t mesh = s.addNode(outline.source + "/recentred");
  s.nodes[s.root].instances.push_back({mesh, scene.placement});
  return mesh;
}

// Pass 2: the kept triangles, with the whole scene's IDs.
void keepTriangles(const ChunkedScene& scene, const PartOf& partOf, uint32_t meshNode,
                   std::vector<ScenePart>& parts) {
  reserveKept(partOf, partOf.size(), meshNode, parts);
  uint64_t id = 0;
  scene.chunks([&](const Mesh& mesh) {
    keepMainMeshTriangles(mesh, id, partOf, meshNode, parts);
    id += mesh.size();
  });
}

}  // namespace

std::optional<ChunkedScene> openSharedStream(const std::string& spec, const std::string& method,
                                             bool quiet) {
  std::optional<ChunkedScene> chunked = openChunkedScene(spec, quiet);
  if (chunked && chunked->procedural && wholeProceduralFor(method)) chunked.reset();
  return chunked;
}

std::vector<uint64_t> streamedTrianglesPerRank(const ChunkedScene& scene, uint32_t regions,
                                               Parts layout, int ranks, SceneOutline& outline) {
  Bounds box;
  const std::vector<glm::dvec3> centres = centresOf(scene, box, outline);
  if (!regions) regions = defaultRegions(outline.uniqueTriangles, layout);
  return trianglesPerRank(centres, {}, regions, ranks);
}

HeldShare holdStreamedShare(const ChunkedScene& scene, uint32_t regions, const WorkShare& share,
                            Parts layout, SceneOutline& outline,
                            const std::function<void(const HeldShare&)>& beforeKeeping) {
  HeldShare held;
  PartOf partOf;
  Bounds nodeBox;
  {
    const std::vector<glm::dvec3> centres = centresOf(scene, nodeBox, outline);
    held.regions = regions ? regions : defaultRegions(outline.uniqueTriangles, layout);
    held.units = centres.size();
    partOf = partOfRank(centres, {}, held, share, layout);
  }
  if (beforeKeeping) beforeKeeping(held);
  held.parts.resize(partCount(held, layout));
  uint32_t meshNode = 0;
  for (ScenePart& part : held.parts) meshNode = partSkeleton(scene, outline, part.scene);
  keepTriangles(scene, partOf, meshNode, held.parts);
  for (ScenePart& part : held.parts) {
    part.scene.finalize();
    // The whole scene's boxes, as cutScene keeps them (Embree places positions relative to them).
    if (part.scene.expandedTriangles() > 0) {
      part.scene.nodeBounds[meshNode] = nodeBox;
      part.scene.nodeBounds[part.scene.root] = outline.bounds;
    }
  }
  return held;
}

}  // namespace lzb
