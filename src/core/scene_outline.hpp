#pragma once
// What a render needs of a scene besides its triangles: where it lies, how many triangles it has,
// its light, camera, camera path and image size, and the figures the report gives. A method that
// keeps every triangle in a file of its own (a sample tree store) keeps the outline there too, so a
// scene larger than memory is rendered without loading it (sceneFromOutline).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "src/core/scene.hpp"

namespace lzb {

struct SceneOutline {
  std::string source;
  Bounds bounds;
  uint64_t uniqueTriangles = 0, expandedTriangles = 0;
  uint64_t nodes = 0;
  int instanceDepth = 0;
  LoadStats stats;
  Light light;
  std::optional<CameraSpec> camera;
  std::vector<CameraSpec> keyframes;
  std::optional<int> width, height;
};

SceneOutline outlineOf(const Scene& scene);

// The outline of a scene that is one node of `triangles` stored triangles bounded by nodeBounds in
// its own frame: the loader keeps a node at the origin as the root itself and a recentred one
// (placement not the identity) as the root's one instance, so the bounds, node count and depth
// follow that rule. base gives the source, light and camera.
SceneOutline placedMeshOutline(SceneOutline base, const Bounds& nodeBounds,
                               const glm::dmat4& placement, uint64_t triangles,
                               const LoadStats& stats);

// JSON text; doubles round-trip exactly, so a render from the outline frames the scene alike.
std::string outlineText(const SceneOutline& outline);
// Throws InputError naming `where` for text that is not an outline.
SceneOutline parseOutline(const std::string& text, const std::string& where);

// Whether scene arguments a and b name one scene: the same text, or paths of one existing file.
bool namesSameScene(const std::string& a, const std::string& b);

// A scene without triangles standing for the outlined one: one empty node whose bounds and
// expanded count are the outline's, so camera paths, clip planes and ID widths come out as for
// the loaded scene. Only a method holding the triangles itself can render it.
Scene sceneFromOutline(const SceneOutline& outline);

}  // namespace lzb
