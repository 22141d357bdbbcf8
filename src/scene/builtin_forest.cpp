// forest?trees=T&levels=L&seed=S: trees instanced on terrain tiles. The tile is a periodic
// heightfield (a sum of sine waves with whole periods across the tile, evaluated on wrapped grid
// indices) so identical tiles join without seams; T trees of 4 variants (two conifers, two
// broadleaf, 1,800 to 2,800 leaf triangles each) stand on it at the terrain height. Level k is a
// 4 x 4 grid of level k - 1, so the expanded count is 16^L * (8192 + sum of the tile's trees).
#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <vector>

#include "src/scene/builtin_generators.hpp"
#include "src/scene/mesh_builder.hpp"
#include "src/scene/random.hpp"

namespace lzb {

namespace {

constexpr double kTile = 128.0;  // tile side (m)
constexpr int kGrid = 64;        // terrain cells per tile side: 2 * 64^2 = 8192 triangles
constexpr double kCell = kTile / kGrid;
constexpr int kWaves = 6;
constexpr int kTrunkSides = 8;

struct TreeShape {
  bool conifer;
  double height;
  int leaves;
};
constexpr std::array<TreeShape, 4> kTrees = {
    {{true, 9.0, 1800}, {true, 13.0, 2400}, {false, 8.0, 2000}, {false, 11.0, 2800}}};

// Heights on the wrapped grid: h[(i mod G) * G + (j mod G)].
std::vector<double> terrainHeights(uint64_t seed) {
  Rng rng(seed);
  struct Wave {
    int kx, kz;
    double amplitude, phase;
  };
  std::vector<Wave> waves;
  while (waves.size() < kWaves) {
    const int kx = int(rng.integer(-3, 3)), kz = int(rng.integer(-3, 3));
    const double amplitude = rng.uniform(0.5, 3.0),
                 phase = rng.uniform(0.0, 2.0 * std::numbers::pi);
    if (kx == 0 && kz == 0) continue;
    waves.push_back({kx, kz, amplitude / std::hypot(kx, kz), phase});
  }
  std::vector<double> h(size_t(kGrid) * kGrid);
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      double sum = 0.0;
      for (const Wave& w : waves)
        sum += w.amplitude *
               std::sin(2.0 * std::numbers::pi * (w.kx * i + w.kz * j) / kGrid + w.phase);
      h[size_t(i) * kGrid + size_t(j)] = sum;
    }
  return h;
}

double heightAt(const std::vector<double>& h, int i, int j) {
  const auto wrap = [](int v) { return ((v % kGrid) + kGrid) % kGrid; };
  return h[size_t(wrap(i)) * kGrid + size_t(wrap(j))];
}

// The height of the triangulated surface (cells split along their (0,0)-(1,1) diagonal) at tile
// coordinates x, z in [-kTile/2, kTile/2).
double surfaceHeight(const std::vector<double>& h, double x, double z) {
  const double gx = (x + 0.5 * kTile) / kCell, gz = (z + 0.5 * kTile) / kCell;
  const int i = int(std::floor(gx)), j = int(std::floor(gz));
  const double u = gx - i, v = gz - j;
  const double h00 = heightAt(h, i, j), h10 = heightAt(h, i + 1, j), h01 = heightAt(h, i, j + 1),
               h11 = heightAt(h, i + 1, j + 1);
  return u >= v ? h00 + u * (h10 - h00) + v * (h11 - h10) : h00 + v * (h01 - h00) + u * (h11 - h01);
}

void addTerrain(Mesh& mesh, LoadStats& stats, const std::vector<double>& h, Rng& rng) {
  MeshBuilder b(mesh, stats);
  double lo = h[0], hi = h[0];
  for (double v : h) lo = std::min(lo, v), hi = std::max(hi, v);
  const auto vertex = [&](int i, int j) {
    return glm::dvec3(-0.5 * kTile + i * kCell, heightAt(h, i, j), -0.5 * kTile + j * kCell);
  };
  const auto color = [&](const glm::dvec3& a, const glm::dvec3& c) {
    const double t = ((a.y + c.y) * 0.5 - lo) / std::max(hi - lo, 1e-9);
    const glm::dvec3 low(0.22, 0.36, 0.12), high(0.48, 0.45, 0.26);
    return packRgb(glm::vec3(glm::mix(low, high, t) * rng.uniform(0.9, 1.1)));
  };
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const glm::dvec3 v00 = vertex(i, j), v10 = vertex(i + 1, j), v01 = vertex(i, j + 1),
                       v11 = vertex(i + 1, j + 1);
      b.triangle(v00, v11, v10, color(v00, v11));  // wound for an upward normal
      b.triangle(v00, v01, v11, color(v00, v11));
    }
}

glm::dvec3 randomUnit(Rng& rng) {
  for (;;) {
    const glm::dvec3 v(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const double l = glm::length(v);
    if (l > 0.1 && l <= 1.0) return v / l;
  }
}

// A tree standing at the origin on y = 0: an open 8-sided trunk and shape.leaves leaf triangles
// scattered in a cone (conifer) or an ellipsoid (broadleaf).
void addTree(Mesh& mesh, LoadStats& stats, const TreeShape& shape, Rng& rng) {
  MeshBuilder b(mesh, stats);
  const double trunkTop = shape.conifer ? 0.35 * shape.height : 0.55 * shape.height;
  const double radius = shape.conifer ? 0.22 : 0.3;
  const Rgba8 bark = packRgba8(92, 64, 40);
  for (int s = 0; s < kTrunkSides; ++s) {
    const double a0 = 2 * std::numbers::pi * s / kTrunkSides,
                 a1 = 2 * std::numbers::pi * (s + 1) / kTrunkSides;
    const glm::dvec3 p0(radius * std::cos(a0), 0, radius * std::sin(a0));
    const glm::dvec3 p1(radius * std::cos(a1), 0, radius * std::sin(a1));
    const glm::dvec3 up(0, trunkTop + 0.5, 0);
    b.quad(p0, p1, p1 + up, p0 + up, p0 + p1, bark);
  }
  const glm::dvec3 leafBase =
      shape.conifer ? glm::dvec3(0.16, 0.30, 0.14) : glm::dvec3(0.25, 0.48, 0.16);
  const double leafSize = shape.conifer ? 0.45 : 0.6;
  const size_t target = mesh.size() + size_t(shape.leaves);
  while (mesh.size() < target) {
    glm::dvec3 p;
    if (shape.conifer) {
      // Uniform in the cone from trunkTop * 0.6 to the tip, radius shrinking linearly.
      const double y0 = 0.6 * trunkTop, r0 = 0.3 * shape.height;
      const double y = rng.uniform(y0, shape.height),
                   r = r0 * (shape.height - y) / (shape.height - y0);
      const double a = rng.uniform(0, 2 * std::numbers::pi), d = r * std::sqrt(rng.uniform());
      p = {d * std::cos(a), y, d * std::sin(a)};
    } else {
      const glm::dvec3 c(0, 0.68 * shape.height, 0),
          radii(0.36 * shape.height, 0.3 * shape.height, 0.36 * shape.height);
      glm::dvec3 q;
      do q = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
      while (glm::dot(q, q) > 1.0);
      p = c + q * radii;
    }
    const glm::dvec3 u = randomUnit(rng), v = randomUnit(rng);
    const Rgba8 color = packRgb(glm::vec3(leafBase * rng.uniform(0.75, 1.25)));
    if (glm::length(glm::cross(u, v)) < 0.2) continue;  // too thin a leaf
    b.triangle(p, p + u * leafSize, p + v * leafSize, color);
  }
}

}  // namespace

Generated generateForest(Scene& scene, BuiltinParams& params) {
  const int64_t trees = params.integer("trees", 64, 0, 100000);
  const int64_t levels = params.integer("levels", 2, 0, 12);
  const uint64_t seed = params.seed("seed", 1);
  params.finish();
  requireIdSpace(params, "levels", uint64_t(2 * kGrid * kGrid) + uint64_t(trees) * 2816, 16,
                 levels);

  std::array<uint32_t, kTrees.size()> variants;
  for (size_t v = 0; v < kTrees.size(); ++v) {
    variants[v] = scene.addNode("forest/tree" + std::to_string(v));
    Rng rng(seed * 4 + v + 1);
    addTree(scene.nodes[variants[v]].mesh, scene.stats, kTrees[v], rng);
  }
  const std::vector<double> h = terrainHeights(seed);
  uint32_t child = scene.addNode("forest/tile");
  Rng rng(seed ^ 0x5eed5eed5eedull);
  addTerrain(scene.nodes[child].mesh, scene.stats, h, rng);
  for (int64_t t = 0; t < trees; ++t) {
    const double x = rng.uniform(-0.5 * kTile, 0.5 * kTile),
                 z = rng.uniform(-0.5 * kTile, 0.5 * kTile);
    const size_t v = size_t(rng.integer(0, int64_t(kTrees.size()) - 1));
    const double angle = rng.uniform(0, 2 * std::numbers::pi), scale = rng.uniform(0.8, 1.25);
    // Sunk a little so the trunk never floats over the slope.
    const glm::dvec3 at(x, surfaceHeight(h, x, z) - 0.3 * scale, z);
    const glm::dmat4 m = glm::translate(glm::dmat4(1.0), at) *
                         glm::rotate(glm::dmat4(1.0), angle, glm::dvec3(0, 1, 0)) *
                         glm::scale(glm::dmat4(1.0), glm::dvec3(scale));
    scene.nodes[child].instances.push_back({variants[v], m});
  }
  for (int64_t level = 1; level <= levels; ++level) {
    const uint32_t node = scene.addNode("forest/level" + std::to_string(level));
    const double spacing = kTile * std::pow(4.0, double(level - 1));
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        scene.nodes[node].instances.push_back(
            {child, glm::translate(glm::dmat4(1.0),
                                   glm::dvec3((i - 1.5) * spacing, 0, (j - 1.5) * spacing))});
    child = node;
  }
  Generated out;
  out.root = child;
  double top = h[0];
  for (double v : h) top = std::max(top, v);
  const double world = kTile * std::pow(4.0, double(levels));
  CameraSpec camera;
  camera.position = {0.0, top + 14.0, 0.45 * world};
  camera.lookAt = {0.0, 0.5 * top, -0.5 * world};
  camera.fovyDegrees = 55.0;
  camera.nearPlane = 0.5;
  out.camera = camera;
  return out;
}

}  // namespace lzb
