#pragma once
// Binary PLY files written value by value, in either byte order, and a polygon mesh that meets
// every rule of the mesh loaders (the streaming reader's tests and the streamed scene's).
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace lzb::test {

// A PLY file written value by value in either byte order.
struct PlyFile {
  bool big = false;
  std::string header, data;
  template <class T>
  void put(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big) std::reverse(b, b + sizeof(T));
    data.append(b, sizeof(T));
  }
  std::filesystem::path write(const std::filesystem::path& p) const {
    std::ofstream(p, std::ios::binary)
        << "ply\nformat " << (big ? "binary_big_endian" : "binary_little_endian") << " 1.0\n"
        << header << "end_header\n"
        << data;
    return p;
  }
};

// A jittered grid of coloured vertices (doubles, with properties to skip), faces of 1 to 6
// vertices (lines, triangles, quads, concave pentagons, hexagons), repeated corners, a NaN vertex,
// a colourless-property face list; `offset` moves it all (1e7: recentred by the loader).
PlyFile polygonMesh(bool big, double offset, int n = 24);

}  // namespace lzb::test
