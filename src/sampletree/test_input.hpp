#pragma once
// Tests' synthetic triangle sets for the sample tree, and the bytes of the files they write.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <vector>

#include "src/sampletree/tree_input.hpp"

namespace lzb::sampletree::test {

// n triangles scattered in the unit cube, sides up to `maxSide`, colours and IDs in order.
inline TriangleInput scatteredTriangles(size_t n, float maxSide, uint32_t seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), offset(-maxSide, maxSide);
  TriangleInput in;
  for (size_t t = 0; t < n; ++t) {
    const glm::vec3 a(unit(rng), unit(rng), unit(rng));
    const glm::vec3 b = a + glm::vec3(offset(rng), offset(rng), offset(rng));
    const glm::vec3 c = a + glm::vec3(offset(rng), offset(rng), offset(rng));
    in.add(a, b, c, t, Rgba8(rng()) | 0xff000000u);
  }
  return in;
}

// A file's bytes (stores are compared and damaged byte by byte).
inline std::vector<char> fileBytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace lzb::sampletree::test
