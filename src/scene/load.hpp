#pragma once
// The one entry point for scene input.
#include <string>

#include "src/core/scene.hpp"
#include "src/scene/toml_scene.hpp"

namespace lzb {

// Loads and finalizes the scene named by spec:
//   "builtin:NAME?key=value&..."  a built-in generator (see builtin.hpp)
//   "*.toml"                      a TOML scene file (see toml_scene.hpp, README.md)
//   anything else                 a mesh file read through assimp (see mesh_file.hpp)
// Throws InputError naming the file, line, generator or key on bad input. Unless quiet, prints a
// warning to stderr when triangles were dropped (they are counted in Scene::stats either way).
Scene loadScene(const std::string& spec, bool quiet = false);
// loadScene's scene with a TOML scene's streamed mesh files and generators left unread
// (loadTomlOutline: their nodes deferred, `read` reads them); any other spec loaded whole (`read`
// unset).
TomlOutline loadSceneDeferred(const std::string& spec, bool quiet, bool deferProcedural);
// Fits the meshes' arrays to their size and hands the heap's free memory back to the system.
void releaseSlack(Scene& scene);
// The one warning line for triangles a loader dropped (none when it dropped none).
void warnDropped(const std::string& spec, const LoadStats& stats);

}  // namespace lzb
