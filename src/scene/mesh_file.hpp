#pragma once
// Mesh files through assimp (OBJ, PLY, OFF, STL, glTF/GLB and the rest assimp reads), or, where
// the streaming reader gives the same triangles (src/scene/mesh_stream.hpp: binary PLY, OFF, most
// OBJ), read by it chunk by chunk into the model, without assimp's copy of the file beside it.
#include <cstdint>
#include <filesystem>
#include <optional>

#include "src/core/color.hpp"
#include "src/core/scene.hpp"

namespace lzb {

// Default colour of triangles whose file gives none (no material, no vertex colours).
constexpr Rgba8 kDefaultMeshColor = packRgba8(200, 200, 200);

// Adds the triangles of a mesh file to `scene` and returns the node that stands for the whole
// file. The assimp node hierarchy is kept as follows: meshes used once are baked (double
// precision) into the file node; meshes used several times become nodes of their own, placed by
// instances. Geometry far from the origin relative to its size is stored recentred and placed by
// a double-precision translation. Colours: colorOverride, else vertex colours, else the material
// diffuse colour, else kDefaultMeshColor. Dropped triangles are counted in scene.stats.
// Throws InputError naming the file when it is missing, unreadable, malformed, truncated or has
// no valid triangle.
// reader: kAssimp reads every file through assimp (the reference the streaming readers' tests
// compare with).
enum class MeshReader { kStreamWhereExact, kAssimp };
uint32_t addMeshFile(Scene& scene, const std::filesystem::path& path,
                     const std::optional<Rgba8>& colorOverride = std::nullopt,
                     MeshReader reader = MeshReader::kStreamWhereExact);

}  // namespace lzb
