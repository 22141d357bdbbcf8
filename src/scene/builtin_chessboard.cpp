// chessboard?n=N&block=B: n x n squares on a board of fixed side, so its projected area stays
// the same as n grows. Above B x B squares it is built from one block of real triangles and
// levels of 2 x 2 instances (n = B * 2^L), which reaches 10^12 triangles in kilobytes.
#include <glm/gtc/matrix_transform.hpp>

#include "src/core/error.hpp"
#include "src/scene/builtin_generators.hpp"
#include "src/scene/mesh_builder.hpp"

namespace lzb {

namespace {

constexpr double kBoardSide = 100.0;
constexpr Rgba8 kDark = packRgba8(40, 40, 46);
constexpr Rgba8 kLight = packRgba8(225, 222, 210);

// m x m squares of side s in the y = 0 plane, centred at the origin, square (0, 0) dark.
void addSquares(Mesh& mesh, LoadStats& stats, int64_t m, double s) {
  MeshBuilder builder(mesh, stats);
  mesh.positions.reserve(size_t((m + 1) * (m + 1)));  // the squares share their corners
  mesh.indices.reserve(size_t(6 * m * m));
  mesh.colors.reserve(size_t(2 * m * m));
  const double half = 0.5 * double(m) * s;
  for (int64_t j = 0; j < m; ++j)
    for (int64_t i = 0; i < m; ++i) {
      const double x0 = -half + double(i) * s, x1 = -half + double(i + 1) * s;
      const double z0 = -half + double(j) * s, z1 = -half + double(j + 1) * s;
      builder.quad({x0, 0, z0}, {x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0}, {0, 1, 0},
                   (i + j) % 2 == 0 ? kDark : kLight);
    }
}

}  // namespace

Generated generateChessboard(Scene& scene, BuiltinParams& params) {
  const int64_t n = params.integer("n", 1024, 1, int64_t(1) << 30);
  const int64_t block = params.integer("block", 64, 1, 2048);
  params.finish();
  const double s = kBoardSide / double(n);
  Generated out;
  // The default view: low over the board's near edge, looking across it (Wand et al.).
  CameraSpec camera;
  camera.position = {0.0, 4.0, 0.5 * kBoardSide + 6.0};
  camera.lookAt = {0.0, 0.0, -0.1 * kBoardSide};
  camera.fovyDegrees = 50.0;
  camera.nearPlane = 0.5;
  out.camera = camera;

  if (n <= block) {
    out.root = scene.addNode("chessboard");
    addSquares(scene.nodes[out.root].mesh, scene.stats, n, s);
    return out;
  }
  require(block % 2 == 0, params.where("block"),
          "must be even when n > block, so the checker pattern continues across blocks");
  int64_t levels = 0;
  while (block << levels < n) ++levels;
  require(block << levels == n, params.where("n"),
          "must be block (" + std::to_string(block) +
              ") times a power of two when larger than "
              "block, got " +
              std::to_string(n));
  uint32_t child = scene.addNode("chessboard/block");
  addSquares(scene.nodes[child].mesh, scene.stats, block, s);
  for (int64_t level = 1; level <= levels; ++level) {
    const uint32_t node = scene.addNode("chessboard/level" + std::to_string(level));
    const double h = 0.25 * double(block << level) * s;  // child centre offset
    for (int dz = -1; dz <= 1; dz += 2)
      for (int dx = -1; dx <= 1; dx += 2)
        scene.nodes[node].instances.push_back(
            {child, glm::translate(glm::dmat4(1.0), glm::dvec3(dx * h, 0.0, dz * h))});
    child = node;
  }
  out.root = child;
  return out;
}

}  // namespace lzb
