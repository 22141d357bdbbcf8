#pragma once
// The generators behind addBuiltin (one file each: builtin_<name>.cpp).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "src/core/scene.hpp"
#include "src/scene/builtin.hpp"
#include "src/scene/builtin_params.hpp"

namespace lzb {

Generated generateChessboard(Scene& scene, BuiltinParams& params);
Generated generateCity(Scene& scene, BuiltinParams& params);
Generated generateForest(Scene& scene, BuiltinParams& params);
Generated generateSphereflake(Scene& scene, BuiltinParams& params);
Generated generateLandscape(Scene& scene, BuiltinParams& params);
// The same triangles as generateLandscape, handed out in chunks (parameters checked now).
BuiltinChunks landscapeChunks(BuiltinParams& params);
Generated generateDisplaced(Scene& scene, BuiltinParams& params);
Generated generateTerrain(Scene& scene, BuiltinParams& params);
// terrain and displaced as chunks of grid rows (the tessellation never held whole); nullopt for
// any other generator.
std::optional<BuiltinChunks> proceduralChunks(BuiltinParams& params);
Generated generateHaltonForest(Scene& scene, BuiltinParams& params);
Generated generateReplicated(Scene& scene, BuiltinParams& params,
                             const std::filesystem::path& baseDir);

// Expanded IDs are 64-bit: throws InputError naming `key` when base * factor^levels > 2^62.
void requireIdSpace(const BuiltinParams& params, const std::string& key, uint64_t base,
                    uint64_t factor, int64_t levels);

}  // namespace lzb
