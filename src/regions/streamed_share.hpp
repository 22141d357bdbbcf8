#pragma once
// --distribute data without loading the whole scene: a scene read as chunks (a PLY, OFF or OBJ,
// builtin:landscape; src/scene/chunked_scene.hpp) is read twice. The first pass takes each
// triangle's world centre (32 bytes a triangle of the whole scene, freed before the second pass)
// and cuts the regions from them as holdShare cuts the loaded scene's; the second keeps the
// triangles of this rank's regions. The part, its IDs and the outline are those that loadScene,
// holdShare and outlineOf give (streamed_share_test), so the frames are too.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "src/core/scene_outline.hpp"
#include "src/regions/share.hpp"
#include "src/scene/chunked_scene.hpp"

namespace lzb::regions {

// `spec` as the ranks read it under --distribute data: as chunks when it streams
// (openChunkedScene), except a procedural object for a method that samples its definition
// (wholeProcedural), which needs it loaded (nullopt then, as for a scene that does not stream).
std::optional<ChunkedScene> openSharedStream(const std::string& spec, bool wholeProcedural,
                                             bool quiet);

// This rank's share of `scene` cut into `regions` regions (0: the default, regionCount) in parts of
// `layout`, and the whole scene's outline. beforeKeeping(held) runs once the regions are dealt,
// before any triangle is kept (to refuse a share that would not fit). Throws InputError when the
// centres would not fit in memory, or as the reader does (a file changed between the passes).
HeldShare holdStreamedShare(const ChunkedScene& scene, uint32_t regions, const WorkShare& share,
                            Parts layout, SceneOutline& outline,
                            const std::function<void(const HeldShare&)>& beforeKeeping = {});

// The triangles each of `ranks` ranks would hold (trianglesPerRank) and the outline, from the
// first pass alone: what lzb info estimates without holding the scene.
std::vector<uint64_t> streamedTrianglesPerRank(const ChunkedScene& scene, uint32_t regions,
                                               Parts layout, int ranks, SceneOutline& outline);

}  // namespace lzb::regions
