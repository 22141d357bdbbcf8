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

}  // namespace lzb
