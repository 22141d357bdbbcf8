#pragma once
// Jittered grids written as OFF and OBJ text in every form their loaders and streaming readers
// take (mesh_stream_test, streamed_share_test).
#include <string>

namespace lzb::test {

// `keyword` its header (C: colours, N: normals), with faces of 1 to 9 vertices (lines,
// triangles, quads, concave and repeated corners), a NaN vertex, face colours after some faces'
// indices, blank lines and comments where the loader skips them; `offset` moves it all (1e7:
// recentred by the loader).
std::string offGrid(const std::string& keyword, double offset, const std::string& eol = "\n",
                    int n = 9);

// Vertices (with colours where `coloured`), normals and texture coordinates, faces of 1 to 7
// corners in every corner form, relative and forward indices, vertices among the faces, a NaN
// vertex, comments, smoothing groups, an object and a group before the first face.
std::string objGrid(bool coloured, double offset, const std::string& eol = "\n", int n = 9);

}  // namespace lzb::test
