#pragma once
// PLY files written value by value, binary in either byte order or ASCII, and a polygon mesh that
// meets every rule of the mesh loaders (the streaming reader's tests and the streamed scene's).
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <type_traits>

namespace lzb::test {

enum class PlyEncoding { kLittleEndian, kBigEndian, kAscii };

// A PLY file written value by value: binary, or ASCII with one element a line (endElement).
struct PlyFile {
  PlyEncoding encoding = PlyEncoding::kLittleEndian;
  std::string header, data;
  template <class T>
  void put(T v) {
    if (encoding == PlyEncoding::kAscii) return putText(v);
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (encoding == PlyEncoding::kBigEndian) std::reverse(b, b + sizeof(T));
    data.append(b, sizeof(T));
  }
  void endElement() {
    if (encoding == PlyEncoding::kAscii) data.back() = '\n';
  }
  std::filesystem::path write(const std::filesystem::path& p) const {
    const char* format[] = {"binary_little_endian", "binary_big_endian", "ascii"};
    std::ofstream(p, std::ios::binary) << "ply\nformat " << format[int(encoding)] << " 1.0\n"
                                       << header << "end_header\n"
                                       << data;
    return p;
  }

 private:
  template <class T>
  void putText(T v) {
    char b[40];
    if constexpr (std::is_floating_point_v<T>)
      std::snprintf(b, sizeof b, "%.*g ", sizeof(T) == 4 ? 9 : 17, double(v));
    else
      std::snprintf(b, sizeof b, "%lld ", static_cast<long long>(v));
    data += b;
  }
};

// A jittered grid of coloured vertices (doubles, with properties to skip), faces of 1 to 6
// vertices (lines, triangles, quads, concave pentagons, hexagons), repeated corners, a NaN vertex,
// a colourless-property face list; `offset` moves it all (1e7: recentred by the loader).
PlyFile polygonMesh(PlyEncoding encoding, double offset, int n = 24);

// A jittered grid of n x n vertices in triangles only (two a cell), every face record of one size
// as the slice reader takes them (src/scene/ply_slices.hpp): an element of fixed size before the
// vertices, a scalar face property before the index list, degenerate triangles (a repeated
// corner) and a NaN vertex that the loaders drop. shared: the triangles index the grid's
// vertices, else each has three of its own; doubles: positions as doubles, else floats;
// coloured: vertex colours. `offset` moves it all (1e7: recentred by the loader).
struct TriangleMeshShape {
  bool shared = true, doubles = false, coloured = true;
};
PlyFile triangleMesh(PlyEncoding encoding, double offset, int n, TriangleMeshShape shape = {});

}  // namespace lzb::test
