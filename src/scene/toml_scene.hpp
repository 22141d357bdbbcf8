#pragma once
// TOML scene files: image size, camera and keyframes, light, mesh files, built-in generators and
// nodes that instance them with transforms. The format is documented in src/scene/README.md.
#include <filesystem>

#include "src/core/scene.hpp"

namespace lzb {

// Reads, builds and finalizes the scene. Throws InputError as "<file>:<line>: <field>: <what>"
// for a parse error, a missing or unknown field, a wrong type or value, an unknown or duplicate
// name and an instancing cycle.
Scene loadTomlScene(const std::filesystem::path& path);

// The scene loadTomlScene makes, with the triangles of its streamed mesh files ([[meshes]] in a
// format MeshStream reads, src/scene/mesh_stream.hpp) and of its generators that stream as one
// mesh (landscape; terrain and displaced too when deferProcedural, for a method that does not
// sample their definitions) not read: their nodes are deferred (their count, and their bounds
// from one pass) and `read` hands out their triangles, the loaded scene's in its ID order, as
// often as asked. Other files and generators are loaded. For a rank's share under --distribute
// data (src/regions/share.hpp).
struct TomlOutline {
  Scene scene;
  DeferredReader read;
};
TomlOutline loadTomlOutline(const std::filesystem::path& path, bool deferProcedural);

}  // namespace lzb
