// city?blocks=K&seed=S: a densely occluded random city: K x K blocks separated by streets, each
// block a raised plot with 2 x 2 or 3 x 3 buildings of random footprint and height (taller
// towards the centre). A building is a stack of floors, each with four wall quads, a protruding
// ledge and protruding window boxes, under a roof with a rooftop box. One node per block, placed
// by a translation; blocks are generated in parallel from per-block seeds, so the result does not
// depend on the thread count. About 12,600 triangles per block (2.13 M at the default K = 13).
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "src/scene/builtin_generators.hpp"
#include "src/scene/mesh_builder.hpp"
#include "src/scene/random.hpp"

namespace lzb {

namespace {

constexpr double kBlock = 80.0;   // side of a block plot (m)
constexpr double kStreet = 16.0;  // street width
constexpr double kPitch = kBlock + kStreet;
constexpr double kSidewalk = 3.0;  // plot margin around the lots
constexpr double kPlinth = 0.2;    // plot (kerb) height
constexpr double kFloor = 3.5;     // storey height
constexpr double kLedge = 0.3, kLedgeOut = 0.25;
constexpr double kWindowPitch = 3.0, kWindowW = 1.4, kWindowH = 1.8, kWindowOut = 0.12;

constexpr Rgba8 kAsphalt = packRgba8(58, 58, 62);
constexpr Rgba8 kPavement = packRgba8(150, 148, 142);
constexpr Rgba8 kRoof = packRgba8(90, 88, 86);

uint64_t splitmix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

Rgba8 scaled(const glm::dvec3& c, double k) {
  return packRgb(glm::vec3(glm::clamp(c * k, 0.0, 1.0)));
}

// Window boxes along one facade: the wall runs from `from` to `to` (at floor height y0) and its
// outward normal is `out`.
void addWindows(MeshBuilder& b, const glm::dvec3& from, const glm::dvec3& to, const glm::dvec3& out,
                double y0, Rgba8 glass) {
  const double length = glm::length(to - from);
  const int count = int(length / kWindowPitch);
  const glm::dvec3 along = (to - from) / length;
  const glm::dvec3 side = glm::cross(out, glm::dvec3(0, 1, 0));  // horizontal, in the wall plane
  for (int w = 0; w < count; ++w) {
    const glm::dvec3 c = from + along * (length * (w + 0.5) / count);
    const glm::dvec3 lo = c - side * (0.5 * kWindowW) + glm::dvec3(0, y0 + 0.9, 0);
    const glm::dvec3 hi = c + side * (0.5 * kWindowW) + glm::dvec3(0, y0 + 0.9 + kWindowH, 0);
    // A box from the wall to kWindowOut outside it, without the face against the wall.
    Bounds box;
    box.extend(lo);
    box.extend(hi + out * kWindowOut);
    const glm::dvec3 &l = box.lo, &h = box.hi;
    if (out.x != 0.0) {
      const double front = out.x > 0 ? h.x : l.x;
      b.quad({front, l.y, l.z}, {front, h.y, l.z}, {front, h.y, h.z}, {front, l.y, h.z}, out,
             glass);
      b.quad({l.x, l.y, l.z}, {h.x, l.y, l.z}, {h.x, h.y, l.z}, {l.x, h.y, l.z}, {0, 0, -1}, glass);
      b.quad({l.x, l.y, h.z}, {h.x, l.y, h.z}, {h.x, h.y, h.z}, {l.x, h.y, h.z}, {0, 0, 1}, glass);
    } else {
      const double front = out.z > 0 ? h.z : l.z;
      b.quad({l.x, l.y, front}, {h.x, l.y, front}, {h.x, h.y, front}, {l.x, h.y, front}, out,
             glass);
      b.quad({l.x, l.y, l.z}, {l.x, h.y, l.z}, {l.x, h.y, h.z}, {l.x, l.y, h.z}, {-1, 0, 0}, glass);
      b.quad({h.x, l.y, l.z}, {h.x, h.y, l.z}, {h.x, h.y, h.z}, {h.x, l.y, h.z}, {1, 0, 0}, glass);
    }
    b.quad({l.x, h.y, l.z}, {h.x, h.y, l.z}, {h.x, h.y, h.z}, {l.x, h.y, h.z}, {0, 1, 0}, glass);
    b.quad({l.x, l.y, l.z}, {h.x, l.y, l.z}, {h.x, l.y, h.z}, {l.x, l.y, h.z}, {0, -1, 0}, glass);
  }
}

// The four vertical sides of the box [x0, x1] x [y0, y1] x [z0, z1], facing outwards.
void addSides(MeshBuilder& b, double x0, double x1, double y0, double y1, double z0, double z1,
              Rgba8 color) {
  b.quad({x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}, {-1, 0, 0}, color);
  b.quad({x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}, {1, 0, 0}, color);
  b.quad({x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}, {0, 0, -1}, color);
  b.quad({x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}, {0, 0, 1}, color);
}

void addBuilding(MeshBuilder& b, Rng& rng, double x0, double x1, double z0, double z1, int floors) {
  const glm::dvec3 facade(rng.uniform(0.45, 0.85), rng.uniform(0.4, 0.8), rng.uniform(0.35, 0.75));
  const Rgba8 wall = scaled(facade, 1.0), ledge = scaled(facade, 1.15);
  const Rgba8 glass = packRgb(glm::vec3(
      float(rng.uniform(0.1, 0.2)), float(rng.uniform(0.15, 0.25)), float(rng.uniform(0.25, 0.4))));
  for (int f = 0; f < floors; ++f) {
    const double y0 = kPlinth + f * kFloor, y1 = y0 + kFloor;
    addSides(b, x0, x1, y0, y1, z0, z1, wall);
    addSides(b, x0 - kLedgeOut, x1 + kLedgeOut, y1 - kLedge, y1, z0 - kLedgeOut, z1 + kLedgeOut,
             ledge);
    addWindows(b, {x0, 0, z0}, {x1, 0, z0}, {0, 0, -1}, y0, glass);
    addWindows(b, {x0, 0, z1}, {x1, 0, z1}, {0, 0, 1}, y0, glass);
    addWindows(b, {x0, 0, z0}, {x0, 0, z1}, {-1, 0, 0}, y0, glass);
    addWindows(b, {x1, 0, z0}, {x1, 0, z1}, {1, 0, 0}, y0, glass);
  }
  const double top = kPlinth + floors * kFloor;
  b.quad({x0, top, z0}, {x1, top, z0}, {x1, top, z1}, {x0, top, z1}, {0, 1, 0}, kRoof);
  // A stair/plant housing on the roof.
  const double hx = rng.uniform(0.2, 0.4) * (x1 - x0), hz = rng.uniform(0.2, 0.4) * (z1 - z0);
  const double cx = rng.uniform(x0 + hx, x1 - hx), cz = rng.uniform(z0 + hz, z1 - hz);
  Bounds housing;
  housing.extend(glm::dvec3(cx - 0.5 * hx, top, cz - 0.5 * hz));
  housing.extend(glm::dvec3(cx + 0.5 * hx, top + rng.uniform(2.0, 4.0), cz + 0.5 * hz));
  b.box(housing, scaled(facade, 0.8), false);
}

// One block in its own frame (centred at the origin); `downtown` in [0, 1] raises the buildings.
void addBlock(Mesh& mesh, LoadStats& stats, uint64_t seed, double downtown) {
  MeshBuilder b(mesh, stats);
  Rng rng(seed);
  Bounds plot;
  plot.extend(glm::dvec3(-0.5 * kBlock, 0.0, -0.5 * kBlock));
  plot.extend(glm::dvec3(0.5 * kBlock, kPlinth, 0.5 * kBlock));
  b.box(plot, kPavement, false);
  const int lots = int(rng.integer(2, 3));
  const double lot = (kBlock - 2.0 * kSidewalk) / lots;
  for (int j = 0; j < lots; ++j)
    for (int i = 0; i < lots; ++i) {
      const double lx = -0.5 * kBlock + kSidewalk + i * lot,
                   lz = -0.5 * kBlock + kSidewalk + j * lot;
      const double w = rng.uniform(0.55, 0.9) * lot, d = rng.uniform(0.55, 0.9) * lot;
      // Keep a ledge's width inside the lot so neighbours never intersect.
      const double x0 = lx + kLedgeOut + rng.uniform() * (lot - w - 2 * kLedgeOut);
      const double z0 = lz + kLedgeOut + rng.uniform() * (lot - d - 2 * kLedgeOut);
      const int floors = 2 + int(rng.integer(0, 4 + int64_t(std::lround(22.0 * downtown))));
      addBuilding(b, rng, x0, x0 + w, z0, z0 + d, floors);
    }
}

}  // namespace

Generated generateCity(Scene& scene, BuiltinParams& params) {
  const int64_t blocks = params.integer("blocks", 13, 1, 64);
  const uint64_t seed = params.seed("seed", 1);
  params.finish();
  const int k = int(blocks);
  const double half = 0.5 * k * kPitch;  // half the city's side, streets included

  Generated out;
  out.root = scene.addNode("city");
  std::vector<uint32_t> nodes(size_t(k) * size_t(k));
  for (size_t b = 0; b < nodes.size(); ++b)
    nodes[b] = scene.addNode("city/block" + std::to_string(b));
  std::vector<LoadStats> stats(nodes.size());
  const auto centre = [&](int i) { return (i - 0.5 * (k - 1)) * kPitch; };
#pragma omp parallel for schedule(dynamic)
  for (size_t b = 0; b < nodes.size(); ++b) {
    const int i = int(b % size_t(k)), j = int(b / size_t(k));
    const double r = std::hypot(centre(i), centre(j)) / std::max(half, 1.0);
    addBlock(scene.nodes[nodes[b]].mesh, stats[b], splitmix(seed ^ splitmix(b)),
             std::clamp(1.0 - r, 0.0, 1.0));
  }
  for (size_t b = 0; b < nodes.size(); ++b) {
    scene.stats.merge(stats[b]);
    const int i = int(b % size_t(k)), j = int(b / size_t(k));
    scene.nodes[out.root].instances.push_back(
        {nodes[b], glm::translate(glm::dmat4(1.0), glm::dvec3(centre(i), 0.0, centre(j)))});
  }
  // The ground: streets between and around the blocks.
  MeshBuilder ground(scene.nodes[out.root].mesh, scene.stats);
  const double g = half + kStreet;
  ground.quad({-g, 0, -g}, {g, 0, -g}, {g, 0, g}, {-g, 0, g}, {0, 1, 0}, kAsphalt);

  // Street level, looking down the street nearest the middle (every view is walled in).
  const double street = (k / 2 - 0.5 - 0.5 * (k - 1)) * kPitch;
  CameraSpec camera;
  camera.position = {street + 2.0, 6.0, half + 4.0};
  camera.lookAt = {street - 1.0, 12.0, -half};
  camera.fovyDegrees = 60.0;
  camera.nearPlane = 0.5;
  out.camera = camera;
  return out;
}

}  // namespace lzb
