#pragma once
// Built-in scene generators, named by a spec "NAME?key=value&key=value":
//   chessboard?n=N&block=B            n x n squares, nested 2x2 instancing above B x B blocks
//   city?blocks=K&seed=S              densely occluded random city of K x K blocks
//   forest?trees=T&levels=L&seed=S    instanced trees on periodic terrain tiles, 4x4 nested L times
//   sphereflake?depth=D               Haines' sphereflake through nested instancing
//   replicated?mesh=PATH&k=K&levels=L a mesh file on a k x k grid, nested L times
//   displaced?shape=plane|sphere&...  a procedural plane or sphere displaced by fractal noise
//   terrain?extent=E&height=H&...     a procedural fractal heightfield, viewed along the ground
//   halton-forest?trees=T&levels=L    the forest's meshed trees (one level by default)
// Every generator is deterministic (fixed default seed, no thread or rank dependence).
// src/scene/README.md documents the parameters and the triangle counts.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "src/core/scene.hpp"

namespace lzb {

struct Generated {
  uint32_t root = 0;                 // the node holding the generated scene
  std::optional<CameraSpec> camera;  // the generator's default view of it (in root's frame)
};

// Adds the generator's nodes to `scene`. Relative file paths in parameters resolve against
// baseDir. Throws InputError naming the generator or the key for an unknown name or key, or a bad
// value.
Generated addBuiltin(Scene& scene, const std::string& spec,
                     const std::filesystem::path& baseDir = {});

std::vector<std::string> builtinNames();

// A built-in scene handed out in chunks, in triangle order, for builders that stream a scene
// larger than memory: one node of stored triangles without instances, so the expanded IDs count
// up through the chunks. generate() makes the same chunks on every call.
struct BuiltinChunks {
  uint64_t triangles = 0;  // before degenerate ones are dropped
  // Returns the triangles kept and dropped, as the loaded scene's stats count them.
  std::function<LoadStats(const std::function<void(const Mesh&)>&)> generate;
  std::optional<CameraSpec> camera;  // the loaded scene's
  bool procedural = false;           // a procedural object's tessellation (terrain, displaced)
  std::string name;                  // the loaded scene's node
};
// landscape, terrain and displaced stream: nullopt for every other generator. Throws InputError
// for a bad spec.
std::optional<BuiltinChunks> builtinChunks(const std::string& spec);

}  // namespace lzb
