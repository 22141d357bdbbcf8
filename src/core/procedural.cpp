#include "src/core/procedural.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "src/core/error.hpp"
#include "src/core/scene.hpp"
#include "src/core/system.hpp"

namespace lzb {

namespace {

uint64_t mix(uint64_t z) {  // splitmix64's finaliser: every input bit reaches every output bit
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// The lattice value at integer point (x, y, z), uniform in [-1, 1).
double latticeValue(int64_t x, int64_t y, int64_t z, uint64_t seed) {
  uint64_t h = mix(seed ^ 0x9e3779b97f4a7c15ull);
  h = mix(h ^ uint64_t(x));
  h = mix(h ^ uint64_t(y));
  h = mix(h ^ uint64_t(z));
  return double(h >> 11) * 0x1.0p-52 - 1.0;
}

double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }  // C2 at the lattice

double valueNoise(const glm::dvec3& p, uint64_t seed) {
  const glm::dvec3 f = glm::floor(p);
  const int64_t x = int64_t(f.x), y = int64_t(f.y), z = int64_t(f.z);
  const double fx = fade(p.x - f.x), fy = fade(p.y - f.y), fz = fade(p.z - f.z);
  double c[2][2];
  for (int j = 0; j < 2; ++j)
    for (int k = 0; k < 2; ++k) {
      const double a = latticeValue(x, y + j, z + k, seed),
                   b = latticeValue(x + 1, y + j, z + k, seed);
      c[j][k] = a + fx * (b - a);
    }
  const double lo = c[0][0] + fy * (c[1][0] - c[0][0]), hi = c[0][1] + fy * (c[1][1] - c[0][1]);
  return lo + fz * (hi - lo);
}

// The undisplaced sphere's direction at (u, v): latitude pi v from +y, longitude -2 pi u (so the
// layout's triangles face outwards).
glm::dvec3 sphereDirection(double u, double v) {
  const double theta = std::numbers::pi * v, phi = 2.0 * std::numbers::pi * u;
  // exactly on the axis at the poles (sin(pi) is 1.2e-16), so their rows close up
  const double s = v == 0.0 || v == 1.0 ? 0.0 : std::sin(theta);
  return {s * std::cos(phi), std::cos(theta), -s * std::sin(phi)};
}

// Terrain colour by relative height (meadow to rock), as the forest's tiles.
Rgba8 heightColor(double t) {
  const glm::dvec3 low(0.22, 0.36, 0.12), high(0.55, 0.50, 0.40);
  return packRgb(glm::vec3(glm::mix(low, high, std::clamp(t, 0.0, 1.0))));
}

}  // namespace

double fractalNoise(const glm::dvec3& p, int octaves, uint64_t seed) {
  double sum = 0.0, weight = 1.0, total = 0.0, scale = 1.0;
  for (int o = 0; o < octaves; ++o) {
    sum += weight * valueNoise(p * scale, seed + uint64_t(o));
    total += weight;
    weight *= 0.5;
    scale *= 2.0;
  }
  return total > 0.0 ? sum / total : 0.0;
}

glm::dvec3 ProceduralSpec::position(double u, double v) const {
  if (kind == ProceduralKind::kSphere) {
    const glm::dvec3 d = sphereDirection(u, v);
    return (size + amplitude * fractalNoise(d * (size * frequency), octaves, seed)) * d;
  }
  const double x = size * (u - 0.5), z = size * (v - 0.5);
  // 0.37: off the lattice's integer planes, whose values alone would repeat across octaves
  const double n = fractalNoise(glm::dvec3(x * frequency, 0.37, z * frequency), octaves, seed);
  const double y = kind == ProceduralKind::kTerrain ? amplitude * (0.5 + 0.5 * n) : amplitude * n;
  return {x, y, z};
}

double ProceduralSpec::baseArea() const {
  return kind == ProceduralKind::kSphere ? 4.0 * std::numbers::pi * size * size : size * size;
}

std::string ProceduralSpec::kindName() const {
  switch (kind) {
    case ProceduralKind::kPlane: return "plane";
    case ProceduralKind::kSphere: return "sphere";
    case ProceduralKind::kTerrain: return "terrain";
  }
  return "plane";
}

uint32_t ProceduralSurface::triangleAt(double u, double v) const {
  const int n = spec.tess;
  const double gu = std::clamp(u, 0.0, 1.0) * n, gv = std::clamp(v, 0.0, 1.0) * n;
  const int i = std::min(int(gu), n - 1), j = std::min(int(gv), n - 1);
  const bool upper = gu - i >= gv - j;
  return slotTriangle[2 * (size_t(j) * size_t(n) + size_t(i)) + (upper ? 0 : 1)];
}

namespace {

// Rows [j0, j1) of spec's tessellation added to mesh in the layout's order (each row's grid
// points computed anew: the same values whichever rows a call covers); slotTriangle, when given,
// receives each cell half's mesh triangle.
void addRows(const ProceduralSpec& spec, size_t j0, size_t j1, Mesh& mesh,
             std::vector<uint32_t>* slotTriangle) {
  const size_t n = size_t(spec.tess);
  std::vector<glm::dvec3> grid((j1 - j0 + 1) * (n + 1));
  for (size_t j = j0; j <= j1; ++j)
    for (size_t i = 0; i <= n; ++i)
      grid[(j - j0) * (n + 1) + i] = spec.position(double(i) / double(n), double(j) / double(n));
  const double lo = spec.kind == ProceduralKind::kTerrain ? 0.0 : -spec.amplitude;
  const double span = std::max(spec.kind == ProceduralKind::kTerrain ? spec.amplitude
                                                                      : 2.0 * spec.amplitude,
                               1e-12);
  const auto color = [&](const glm::dvec3& a, const glm::dvec3& b) {
    if (spec.kind != ProceduralKind::kTerrain) return spec.color;
    return heightColor((0.5 * (a.y + b.y) - lo) / span);
  };
  for (size_t j = j0; j < j1; ++j)
    for (size_t i = 0; i < n; ++i) {
      const size_t r = (j - j0) * (n + 1);
      const glm::dvec3 &v00 = grid[r + i], &v10 = grid[r + i + 1], &v01 = grid[r + n + 1 + i],
                       &v11 = grid[r + n + 1 + i + 1];
      const size_t slot = 2 * (j * n + i);
      if (mesh.add(glm::vec3(v00), glm::vec3(v11), glm::vec3(v10), color(v00, v11)) && slotTriangle)
        (*slotTriangle)[slot] = uint32_t(mesh.size() - 1);
      if (mesh.add(glm::vec3(v00), glm::vec3(v01), glm::vec3(v11), color(v00, v11)) && slotTriangle)
        (*slotTriangle)[slot + 1] = uint32_t(mesh.size() - 1);
    }
}

void requireTess(const ProceduralSpec& spec, const std::string& where) {
  require(spec.tess >= 1 && spec.tess <= kMaxTess, where + ": tess",
          "must be in [1, " + std::to_string(kMaxTess) + "], got " + std::to_string(spec.tess));
}

}  // namespace

ProceduralSurface tessellate(const ProceduralSpec& spec, Mesh& mesh, const std::string& where) {
  requireTess(spec, where);
  const size_t n = size_t(spec.tess), slots = 2 * n * n;
  // positions, normal, colour and slot entry per triangle, and the vertex grid
  requireMemory(slots * (3 * sizeof(glm::vec3) + sizeof(glm::vec3) + sizeof(Rgba8) + 4) +
                    (n + 1) * (n + 1) * sizeof(glm::dvec3),
                where + ": tess", "a tessellation of " + std::to_string(slots) + " triangles");
  mesh = Mesh{};
  ProceduralSurface out{spec, std::vector<uint32_t>(slots, ProceduralSurface::kNoTriangle)};
  addRows(spec, 0, n, mesh, &out.slotTriangle);
  // A dropped half takes its cell's other half (both dropped: the cell is a point; none remain).
  for (size_t s = 0; s < slots; s += 2) {
    if (out.slotTriangle[s] == ProceduralSurface::kNoTriangle) out.slotTriangle[s] = out.slotTriangle[s + 1];
    if (out.slotTriangle[s + 1] == ProceduralSurface::kNoTriangle) out.slotTriangle[s + 1] = out.slotTriangle[s];
  }
  require(!mesh.empty(), where, "the procedural surface has no non-degenerate triangle");
  return out;
}

uint64_t tessellateInChunks(const ProceduralSpec& spec, const std::string& where,
                            const std::function<void(const Mesh&)>& chunk, size_t rowsPerChunk) {
  requireTess(spec, where);
  const size_t n = size_t(spec.tess);
  uint64_t kept = 0;
  for (size_t j = 0; j < n; j += rowsPerChunk) {
    Mesh mesh;
    addRows(spec, j, std::min(n, j + rowsPerChunk), mesh, nullptr);
    kept += mesh.size();
    if (!mesh.empty()) chunk(mesh);
  }
  require(kept > 0, where, "the procedural surface has no non-degenerate triangle");
  return kept;
}

}  // namespace lzb
