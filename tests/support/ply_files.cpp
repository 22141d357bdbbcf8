#include "tests/support/ply_files.hpp"

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

}  // namespace lzb::test
