#pragma once
// Surfelization (Tobor et al., section 3): one object (a scene node's own triangles) turned into
// the surfels of a grid of `grid`^3 cells over its bounding cube, packed into a surfel collector.
//
// Two ways, both ending in the same per-cell merge:
//   raster: software 3D rasterization. Every triangle visits the cells of its bounding box
//           column by column along its dominant axis and keeps those it overlaps (the closed
//           triangle-box test of src/octree): a conservative voxelization, so every cell the
//           surface passes through gets a surfel. A candidate's sample is the point of the
//           triangle inside the cell nearest the cell's centre.
//   shots:  multi-view z-buffer shots. The object is drawn orthographically from the 26
//           directions of the cube's faces, edges and corners (a regular set on the sphere) by the
//           native z-buffer's triangle set-up and rasterization (src/zbuffer/native_raster.hpp),
//           two pixels per cell; each pixel's ID buffer names its triangle, which gives the
//           colour and normal buffers, and its exact point (the pixel's line of sight meeting that
//           triangle) gives the depth buffer. Cells seen from no direction (deep in concavities)
//           get no surfel.
// Merge: a cell's candidates (triangle, sample, weight) are averaged into one surfel: mean
// normal and colour, and the representative triangle = the candidate whose sample is nearest the
// cell's centre, its sample the surfel's position (quantized on the collector's lattice). With
// `split` (the paper's rule) the candidates whose normal is more than kSplitDegrees from the
// representative's or whose colour differs by more than kSplitColour in a channel form a second
// surfel with its own representative; a cell keeps at most two. The result depends on neither the
// thread count nor the order of the work.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "src/core/scene.hpp"
#include "src/surfels/collector.hpp"
#include "src/surfels/normal_quantizer.hpp"

namespace lzb::surfels {

enum class Surfelizer { kRaster, kShots };

constexpr double kSplitDegrees = 60.0;
constexpr int kSplitColour = 32;  // of 255

// The object's bounding cube: lattice coordinate u = (p - origin) / side * n for an n^3 grid.
struct Domain {
  glm::dvec3 origin{0.0};
  double side = 1.0;
  static Domain around(const Mesh& mesh);
};

struct SurfelizeParams {
  Surfelizer method = Surfelizer::kRaster;
  CollectorQuality quality = CollectorQuality::kHigh;
  int grid = 64;  // cells per axis: a power of two, at most the collector's lattice
  bool split = true;
  int threads = 1;
};

// One level of detail of one object.
struct SurfelLevel {
  int grid = 0;
  Domain domain;
  SurfelCollector collector;
  uint64_t cells = 0;       // cells with surfels
  uint64_t splitCells = 0;  // cells with two
  double seconds = 0.0;     // building it
  // The lattice step of the collector's positions, in object units.
  double latticeStep() const { return domain.side / double(collector.layout().lattice()); }
};

SurfelLevel surfelize(const Mesh& mesh, const OctahedralNormals& normals, const SurfelizeParams& p);

// A cell candidate before the merge (exposed for the tests).
struct Candidate {
  uint64_t cell;  // x + n (y + n z)
  uint32_t triangle;
  uint32_t weight;   // pixels (shots) or 1 (raster)
  glm::vec3 sample;  // grid units
  float dist2;       // squared distance of the sample from the cell's centre, grid units
};
std::vector<Candidate> rasterCandidates(const Mesh& mesh, const Domain& d, int grid, int threads);
std::vector<Candidate> shotCandidates(const Mesh& mesh, const Domain& d, int grid, int threads);

}  // namespace lzb::surfels
