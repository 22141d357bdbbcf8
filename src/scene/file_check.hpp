#pragma once
// Checks before assimp reads a mesh file: the data a PLY/OFF header promises (assimp invents empty
// or repeated faces when it is missing), the end of an STL file, PLY header lines and OFF face
// sizes assimp hangs or crashes on, and GLB lengths it would allocate unchecked.
#include <filesystem>

namespace lzb {

// Throws InputError naming the file when a .ply, .off, .stl or .glb file ends before its data
// does or holds what assimp cannot read safely.
// Other extensions pass unchecked (assimp reports their errors itself).
void checkMeshFileComplete(const std::filesystem::path& path);

}  // namespace lzb
