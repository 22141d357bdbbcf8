#pragma once
// Completeness checks for mesh formats whose truncation assimp accepts silently (it invents
// empty or repeated faces): the data a PLY/OFF header promises, and the end of an STL file.
#include <filesystem>

namespace lzb {

// Throws InputError naming the file when a .ply, .off or .stl file ends before its data does.
// Other extensions pass unchecked (assimp reports their errors itself).
void checkMeshFileComplete(const std::filesystem::path& path);

}  // namespace lzb
