#include "tests/support/ply_files.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace lzb::test {

PlyFile polygonMesh(PlyEncoding encoding, double offset, int n) {
  PlyFile f;
  f.encoding = encoding;
  const int vertices = n * n;
  const int faces = (n - 1) * (n - 1);
  f.header = "comment polygons\nelement vertex " + std::to_string(vertices) +
             "\nproperty double x\nproperty double y\nproperty double z\nproperty float nx\n"
             "property uchar red\nproperty uchar green\nproperty uchar blue\n"
             "property list uchar int extra\nelement face " +
             std::to_string(faces) +
             "\nproperty uchar flags\nproperty list uchar int vertex_indices\n"
             "property list ushort float weights\nelement edge 2\nproperty int a\nproperty int b\n";
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool nan = i == 3 && j == 4;
      f.put(nan ? std::numeric_limits<double>::quiet_NaN() : offset + i + jitter(rng));
      f.put(offset + j + jitter(rng));
      f.put(0.2 * std::sin(0.7 * i) + jitter(rng));
      f.put(0.5f);
      f.put(uint8_t(rng())), f.put(uint8_t(rng())), f.put(uint8_t(rng()));
      f.put(uint8_t(i % 3));
      for (int k = 0; k < i % 3; ++k) f.put(int32_t(k));
      f.endElement();
    }
  const auto at = [&](int i, int j) { return int32_t(j * n + i); };
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      std::vector<int32_t> poly = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
      switch ((i + 2 * j) % 7) {
        case 0:
          poly.resize(3);
          break;  // triangle
        case 1:
          poly.resize(2);
          break;  // a line
        case 2:
          poly.insert(poly.begin() + 2, at(i, j));
          break;  // concave-ish pentagon
        case 3:
          poly = {at(i, j), at(i, j), at(i + 1, j + 1)};
          break;  // degenerate
        case 4:
          poly.push_back(at(i, j)), poly.push_back(at(i + 1, j));
          break;  // hexagon, repeats
        default:
          break;  // quad
      }
      f.put(uint8_t(7));
      f.put(uint8_t(poly.size()));
      for (int32_t v : poly) f.put(v);
      f.put(uint16_t(1));
      f.put(0.25f);
      f.endElement();
    }
  for (int e = 0; e < 4; ++e) {
    f.put(int32_t(e));
    if (e % 2) f.endElement();
  }
  return f;
}

PlyFile triangleMesh(PlyEncoding encoding, double offset, int n, TriangleMeshShape shape) {
  PlyFile f;
  f.encoding = encoding;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<std::array<double, 3>> grid;
  std::vector<std::array<uint8_t, 3>> rgb;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool nan = i == 2 && j == 3;
      grid.push_back({nan ? std::numeric_limits<double>::quiet_NaN() : offset + i + jitter(rng),
                      offset + j + jitter(rng), 0.3 * std::sin(0.5 * i + 0.2 * j)});
      rgb.push_back({uint8_t(rng()), uint8_t(rng()), uint8_t(rng())});
    }
  std::vector<std::array<int32_t, 3>> faces;
  const auto at = [&](int i, int j) { return int32_t(j * n + i); };
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      // Every eleventh cell's second triangle repeats a corner: degenerate.
      faces.push_back({at(i, j), (i + j) % 11 ? at(i + 1, j + 1) : at(i, j), at(i, j + 1)});
    }
  const size_t vertices = shape.shared ? grid.size() : 3 * faces.size();
  const std::string type = shape.doubles ? "double" : "float";
  f.header =
      "comment triangles\nelement camera 1\nproperty float view_px\nproperty float view_py\n"
      "element vertex " +
      std::to_string(vertices) + "\nproperty " + type + " x\nproperty " + type + " y\nproperty " +
      type + " z\n" +
      (shape.coloured ? "property uchar red\nproperty uchar green\nproperty uchar blue\n" : "") +
      "element face " + std::to_string(faces.size()) +
      "\nproperty uchar flags\nproperty list uchar int vertex_indices\n";
  f.put(1.5f), f.put(2.5f), f.endElement();
  const auto putVertex = [&](size_t v) {
    for (const double c : grid[v]) shape.doubles ? f.put(c) : f.put(float(c));
    if (shape.coloured)
      for (const uint8_t c : rgb[v]) f.put(c);
    f.endElement();
  };
  if (shape.shared)
    for (size_t v = 0; v < grid.size(); ++v) putVertex(v);
  else
    for (const auto& face : faces)
      for (const int32_t v : face) putVertex(size_t(v));
  for (size_t t = 0; t < faces.size(); ++t) {
    f.put(uint8_t(t % 5)), f.put(uint8_t(3));
    for (int k = 0; k < 3; ++k) f.put(shape.shared ? faces[t][size_t(k)] : int32_t(3 * t) + k);
    f.endElement();
  }
  return f;
}

}  // namespace lzb::test
