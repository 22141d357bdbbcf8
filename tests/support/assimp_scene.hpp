#pragma once
// A mesh file loaded by assimp alone: the reference the streaming readers' tests compare with,
// since addMeshFile reads the files they stream through them.
#include <filesystem>
#include <optional>

#include "src/scene/mesh_file.hpp"

namespace lzb::test {

inline Scene loadedByAssimp(const std::filesystem::path& file) {
  Scene scene;
  scene.source = file.string();
  scene.root = addMeshFile(scene, file, std::nullopt, MeshReader::kAssimp);
  scene.finalize();
  return scene;
}

}  // namespace lzb::test
