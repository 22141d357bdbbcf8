// landscape?objects=N&seed=S: a terrain with N distinct objects, every triangle stored (no
// instances), so expanded = stored: the input for the sample tree's out-of-core work, where
// instancing would hide the size. The terrain (128 x 128 cells, 32,768 triangles) grows with N
// so the objects' density stays the same; each object is a rock or a tree (24 triangles) with
// its own size, colour and randomly jittered vertices, standing at the terrain height.
#include <cmath>
#include <functional>
#include <numbers>

#include "src/scene/builtin_generators.hpp"
#include "src/scene/mesh_builder.hpp"
#include "src/scene/random.hpp"

namespace lzb {

namespace {

constexpr int kGrid = 128;      // terrain cells per side
constexpr int kSides = 6;       // of a rock's or a crown's cone and a trunk's prism
constexpr double kSpacing = 6;  // metres of terrain side per sqrt(object)

// The terrain's height at (x, z): three sine waves across the side `side`.
struct Terrain {
  double side, phase[3];
  double height(double x, double z) const {
    const double u = 2.0 * std::numbers::pi / side;
    return 4.0 * std::sin(u * x + phase[0]) + 3.0 * std::sin(2.0 * u * z + phase[1]) +
           1.5 * std::sin(3.0 * u * (x + z) + phase[2]);
  }
};

void addTerrain(MeshBuilder& b, const Terrain& t) {
  const double cell = t.side / kGrid, h = 0.5 * t.side;
  const Rgba8 ground = packRgba8(96, 118, 70);
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const double x0 = -h + i * cell, x1 = x0 + cell, z0 = -h + j * cell, z1 = z0 + cell;
      const glm::dvec3 a(x0, t.height(x0, z0), z0), c(x1, t.height(x1, z0), z0),
          d(x1, t.height(x1, z1), z1), e(x0, t.height(x0, z1), z1);
      b.triangle(a, e, d, ground);
      b.triangle(a, d, c, ground);
    }
}

// A cone of kSides around the y axis from `base` up to `top`, vertices jittered: 2 * kSides.
void addCone(MeshBuilder& b, Rng& rng, const glm::dvec3& base, double radius, double height,
             Rgba8 colour) {
  glm::dvec3 ring[kSides];
  for (int k = 0; k < kSides; ++k) {
    const double a = 2.0 * std::numbers::pi * k / kSides, r = radius * rng.uniform(0.75, 1.25);
    ring[k] = base + glm::dvec3(r * std::cos(a), rng.uniform(-0.1, 0.1) * height, r * std::sin(a));
  }
  const glm::dvec3 top = base + glm::dvec3(rng.uniform(-0.1, 0.1) * radius, height, 0.0);
  for (int k = 0; k < kSides; ++k) {
    b.triangle(ring[k], top, ring[(k + 1) % kSides], colour);
    b.triangle(ring[(k + 1) % kSides], base, ring[k], colour);
  }
}

void addObject(MeshBuilder& b, const Terrain& t, Rng& rng) {
  const double h = 0.5 * t.side, x = rng.uniform(-h, h), z = rng.uniform(-h, h);
  const glm::dvec3 ground(x, t.height(x, z), z);
  const auto shade = [&](int r, int g, int bl) {
    const double f = rng.uniform(0.7, 1.3);
    return packRgba8(uint8_t(std::min(255.0, r * f)), uint8_t(std::min(255.0, g * f)),
                     uint8_t(std::min(255.0, bl * f)));
  };
  if (rng.uniform() < 0.3) {  // a rock: two cones base to base
    const double r = rng.uniform(0.5, 2.0);
    const Rgba8 grey = shade(128, 124, 118);
    addCone(b, rng, ground, r, rng.uniform(0.5, 1.5) * r, grey);
    addCone(b, rng, ground, r, -0.3 * r, grey);
    return;
  }
  const double height = rng.uniform(4.0, 12.0);  // a tree: trunk cone and crown cone
  addCone(b, rng, ground, 0.04 * height, 0.4 * height, shade(100, 72, 48));
  addCone(b, rng, ground + glm::dvec3(0.0, 0.3 * height, 0.0), rng.uniform(0.15, 0.3) * height,
          0.7 * height, shade(52, 110, 48));
}

// The landscape's parameters and its generator state, shared by the in-memory generator and the
// stream: both draw the same random numbers in the same order, so they make the same triangles.
struct Landscape {
  int64_t objects;
  Rng rng;
  Terrain terrain;
  explicit Landscape(BuiltinParams& params)
      : objects(params.integer("objects", 1000, 0, int64_t(1) << 22)),
        rng(params.seed("seed", 1)),
        terrain{kSpacing * std::sqrt(double(objects) + 400.0), {}} {
    params.finish();
    for (double& p : terrain.phase) p = rng.uniform(0.0, 2.0 * std::numbers::pi);
  }
  size_t triangles() const { return size_t(2 * kGrid * kGrid) + size_t(objects) * 4 * kSides; }
};

constexpr int64_t kStreamObjects = 1 << 12;  // objects per streamed chunk (~100 K triangles, 5 MB)

CameraSpec landscapeCamera(const Terrain& terrain) {
  CameraSpec camera;  // low over one edge, looking across
  camera.position = {0.0, 25.0, 0.5 * terrain.side + 10.0};
  camera.lookAt = {0.0, 0.0, 0.0};
  camera.fovyDegrees = 50.0;
  camera.nearPlane = 0.5;
  return camera;
}

}  // namespace

Generated generateLandscape(Scene& scene, BuiltinParams& params) {
  Landscape land(params);
  Generated out;
  out.root = scene.addNode("landscape");
  Mesh& mesh = scene.nodes[out.root].mesh;
  mesh.positions.reserve(land.triangles());  // shared corners: 0.65 a triangle measured
  mesh.indices.reserve(3 * land.triangles());
  mesh.colors.reserve(land.triangles());
  MeshBuilder builder(mesh, scene.stats);
  addTerrain(builder, land.terrain);
  for (int64_t k = 0; k < land.objects; ++k) addObject(builder, land.terrain, land.rng);
  out.camera = landscapeCamera(land.terrain);
  return out;
}

BuiltinChunks landscapeChunks(BuiltinParams& params) {
  const Landscape shape(params);
  return {shape.triangles(),
          [spec = params.spec()](const std::function<void(const Mesh&)>& chunk) {
            BuiltinParams again(spec);
            Landscape land(again);
            Mesh mesh;
            LoadStats stats;
            MeshBuilder builder(mesh, stats);
            addTerrain(builder, land.terrain);
            for (int64_t k = 0; k < land.objects; ++k) {
              addObject(builder, land.terrain, land.rng);
              if ((k + 1) % kStreamObjects == 0) {
                chunk(mesh);
                mesh = Mesh();
              }
            }
            if (!mesh.empty()) chunk(mesh);
            return stats;
          },
          landscapeCamera(shape.terrain), false, "landscape"};
}

}  // namespace lzb
