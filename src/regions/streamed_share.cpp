#include "src/regions/streamed_share.hpp"

#include <vector>

#include "src/regions/memory_estimate.hpp"

namespace lzb::regions {

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

std::optional<ChunkedScene> openSharedStream(const std::string& spec, bool wholeProcedural,
                                             bool quiet) {
  std::optional<ChunkedScene> chunked = openChunkedScene(spec, quiet);
  if (chunked && chunked->procedural && wholeProcedural) chunked.reset();
  return chunked;
}

std::vector<uint64_t> streamedTrianglesPerRank(const ChunkedScene& scene, uint32_t regions,
                                               Parts layout, int ranks, SceneOutline& outline) {
  Bounds box;
  const std::vector<glm::dvec3> centres = centresOf(scene, box, outline);
  regions = regionCount(regions, outline.uniqueTriangles, layout == Parts::kOne);
  return trianglesPerRank(cutIntoRegions(centres, {}, regions).regionTriangles, ranks);
}

HeldShare holdStreamedShare(const ChunkedScene& scene, uint32_t regions, const WorkShare& share,
                            Parts layout, SceneOutline& outline,
                            const std::function<void(const HeldShare&)>& beforeKeeping) {
  HeldShare held;
  PartOf partOf;
  Bounds nodeBox;
  {
    const std::vector<glm::dvec3> centres = centresOf(scene, nodeBox, outline);
    held.regions = regionCount(regions, outline.uniqueTriangles, layout == Parts::kOne);
    held.units = centres.size();
    partOf = partOfRank(cutIntoRegions(centres, {}, held.regions), held, share, layout);
  }
  if (beforeKeeping) beforeKeeping(held);
  held.parts.resize(partCount(held, layout));
  uint32_t meshNode = 0;
  for (ScenePart& part : held.parts) meshNode = startMeshPart(outline, scene.placement, part.scene);
  keepTriangles(scene, partOf, meshNode, held.parts);
  for (ScenePart& part : held.parts) finishMeshPart(outline, meshNode, nodeBox, part.scene);
  return held;
}

}  // namespace lzb::regions
