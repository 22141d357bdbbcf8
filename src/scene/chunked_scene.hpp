#pragma once
// A scene read as chunks of one node's triangles, never whole: a PLY, OFF or OBJ file streamed
// (mesh_stream.hpp) or builtin:landscape, terrain or displaced generated (builtin.hpp). Every pass
// hands out the triangles loadScene makes of the scene, in its ID order, in the node's stored
// frame; the loaded scene holds them in its root or, for a file stored recentred, in the node its
// root's one instance places (placedMeshOutline gives the outline either way). For builders that
// cannot hold the scene: the sample tree's external build, a rank's share under --distribute data.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "src/core/scene.hpp"
#include "src/core/scene_outline.hpp"

namespace lzb {

struct ChunkedScene {
  using Chunks = std::function<LoadStats(const std::function<void(const Mesh&)>&)>;
  SceneOutline base;          // the source and camera (counts and bounds come from a pass)
  uint64_t triangles = 0;     // expected (a generator's before degenerate ones are dropped)
  glm::dmat4 placement{1.0};  // the node's stored frame -> world
  bool generated = false;     // made anew on every pass (a copy on disk may read faster)
  bool procedural = false;    // a procedural object's tessellation, its definition not kept
  uint64_t heldBytes = 0;     // held while open (a file's vertices), besides the passes' chunks
  Chunks chunks;              // one pass: hands out the chunks, returns what was kept and dropped
};

// `spec` as chunks, or nullopt when it is not read that way (another generator or format, or a
// mesh file that the loader might read otherwise: unless quiet, a note says why). Throws InputError
// as loadScene would for a bad spec or file.
std::optional<ChunkedScene> openChunkedScene(const std::string& spec, bool quiet);
// `spec` as chunks when a generator makes it (opening it generates nothing, so its triangle
// count comes for free), else nullopt. Opening a mesh file stream reads the whole file once.
std::optional<ChunkedScene> openGeneratedScene(const std::string& spec);

}  // namespace lzb
