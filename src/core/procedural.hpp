#pragma once
// Procedural objects (Stamminger & Drettakis, "Interactive sampling and rendering for complex and
// procedural geometry"): a surface given by a function p(u, v) over the unit square, here a plane,
// a sphere or a terrain heightfield displaced by deterministic fractal value noise.
//
// A node that carries a ProceduralSurface also holds its tessellation in Node::mesh, so every
// triangle method (and the exact references and the accuracy metric, which compare triangle IDs)
// renders it unchanged; --method sqrt5 samples p(u, v) itself and gives each sample the ID of the
// tessellated triangle containing (u, v).
//
// Tessellation layout: the unit square is cut into tess x tess cells; cell (i, j) covers
// u in [i, i + 1) / tess, v in [j, j + 1) / tess and is split along its (0,0)-(1,1) diagonal into
// layout slot 2 (j tess + i) (the half with fu >= fv, corners 00, 11, 10) and slot
// 2 (j tess + i) + 1 (fu < fv, corners 00, 01, 11). A slot whose triangle is degenerate (a
// sphere's pole row) is dropped from the mesh; slotTriangle maps each slot to its mesh triangle,
// or to the other half of its cell when it was dropped.
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "src/core/color.hpp"

namespace lzb {

struct Mesh;

enum class ProceduralKind { kPlane, kSphere, kTerrain };

struct ProceduralSpec {
  ProceduralKind kind = ProceduralKind::kPlane;
  double size = 10.0;      // plane and terrain: side of the square; sphere: radius
  double amplitude = 0.5;  // displacement amplitude; terrain: the largest height
  double frequency = 0.5;  // noise cycles per unit length of the undisplaced surface
  int octaves = 4;         // fractal octaves, each twice the frequency and half the amplitude
  uint64_t seed = 1;
  Rgba8 color = packRgba8(180, 170, 150);
  int tess = 256;  // grid cells per side of the tessellation

  // The surface point at (u, v) (node frame); u, v slightly outside [0, 1] extend it smoothly.
  glm::dvec3 position(double u, double v) const;
  // The undisplaced surface's area (the paper's A_total).
  double baseArea() const;
  // Largest |displacement| from the undisplaced surface.
  double maxDisplacement() const { return amplitude; }
  std::string kindName() const;
};

// Fractal value noise in [-1, 1]: `octaves` octaves of smoothly (quintic) interpolated lattice
// values hashed from the integer lattice point and the seed; no state, no thread dependence.
double fractalNoise(const glm::dvec3& p, int octaves, uint64_t seed);

struct ProceduralSurface {
  ProceduralSpec spec;
  std::vector<uint32_t> slotTriangle;  // per layout slot: its mesh triangle (see above)

  static constexpr uint32_t kNoTriangle = ~0u;
  // The mesh triangle whose (u, v) cell half contains (u, v), clamped to the unit square.
  uint32_t triangleAt(double u, double v) const;
};

// Fills `mesh` (emptied first) with the tessellation in the layout above and returns the surface
// with its slot map. Throws InputError naming `where` when tess is out of [1, kMaxTess] or the
// mesh would not fit in memory.
constexpr int kMaxTess = 4096;
ProceduralSurface tessellate(const ProceduralSpec& spec, Mesh& mesh, const std::string& where);
// The same triangles in the same order, handed out as meshes of rowsPerChunk grid rows each,
// never held whole (--distribute data, build-tree --mem-mb); returns how many were kept.
uint64_t tessellateInChunks(const ProceduralSpec& spec, const std::string& where,
                            const std::function<void(const Mesh&)>& chunk, size_t rowsPerChunk);

}  // namespace lzb
